"""JSON text exactly as `json.dumps(obj, indent=N, sort_keys=True, ensure_ascii=False)` writes it,
several times faster: with an indent, the standard library leaves its C encoder and walks the data
in Python generators, one per nesting level, and joins millions of small strings at the end (a
1,000-message spec's vectors: 50 MB of text, 40 % of the vectors target's time and most of its
memory). Here each container is one loop, scalars are written by the same functions json uses, and
a list may be `Streamed`: its items are produced while the text is written, so a large list (the
vectors' cases) never exists as data all at once. tests/render/test_jsontext.py holds it to
json.dumps on every kind of value."""

from __future__ import annotations

from collections.abc import Iterable
from json.encoder import encode_basestring  # the C implementation where there is one, as json.dumps uses
from typing import Any


class Streamed:
    """A JSON array whose items come from an iterable, each written as soon as it is produced."""

    def __init__(self, items: Iterable[Any]) -> None:
        self.items = items


def _float(x: float) -> str:
    if x != x:
        return "NaN"
    if x in (float("inf"), float("-inf")):
        return "Infinity" if x > 0 else "-Infinity"
    return float.__repr__(x)


def _scalar(o: Any) -> str | None:
    """The text of a JSON scalar, in json's order of checks (a bool before an int); None for a container."""
    if isinstance(o, str):
        return encode_basestring(o)
    if o is None:
        return "null"
    if o is True:
        return "true"
    if o is False:
        return "false"
    if isinstance(o, int):
        return int.__repr__(o)
    if isinstance(o, float):
        return _float(o)
    if isinstance(o, (list, tuple, dict, Streamed)):
        return None
    raise TypeError(f"Object of type {type(o).__name__} is not JSON serializable")


def _key(k: Any) -> str:
    """A member name as json writes it: a string as it is, a number or a constant as its text."""
    if isinstance(k, str):
        return encode_basestring(k)
    text = _scalar(k)
    if text is None:
        raise TypeError(f"keys must be str, int, float, bool or None, not {type(k).__name__}")
    return encode_basestring(text.strip('"'))


# The scalar types by exact type: one dict look-up instead of json's chain of isinstance checks
# (subclasses, rare here, take the chain in _scalar).
_EXACT = {str: encode_basestring, int: int.__repr__, float: _float, bool: lambda b: "true" if b else "false", type(None): lambda _: "null"}


def _write(o: Any, out: list[str], step: int, level: int, keys: dict[Any, str]) -> None:
    exact = _EXACT.get(type(o))
    text = exact(o) if exact is not None else _scalar(o)
    if text is not None:
        out.append(text)
        return
    inner = "\n" + " " * (step * (level + 1))
    closing = "\n" + " " * (step * level)
    if isinstance(o, dict):
        if not o:
            out.append("{}")
            return
        sep = "{" + inner
        for k, v in sorted(o.items()):
            key = keys.get(k) if type(k) is str else _key(k)  # only strings: 1, 1.0 and True are one dict key
            if key is None:
                key = keys[k] = _key(k)
            exact = _EXACT.get(type(v))
            if exact is not None:
                out.append(sep + key + ": " + exact(v))
            else:
                out.append(sep + key + ": ")
                _write(v, out, step, level + 1, keys)
            sep = "," + inner
        out.append(closing + "}")
        return
    sep = "[" + inner
    for item in o.items if isinstance(o, Streamed) else o:
        out.append(sep)
        _write(item, out, step, level + 1, keys)
        sep = "," + inner
    out.append("[]" if sep[0] == "[" else closing + "]")


def dumps(obj: Any, indent: int = 1) -> str:
    """`json.dumps(obj, indent=indent, sort_keys=True, ensure_ascii=False)`, `Streamed` lists written as arrays."""
    out: list[str] = []
    _write(obj, out, indent, 0, {})  # member names repeat (every case has "raw", "kind"): each written once
    return "".join(out)
