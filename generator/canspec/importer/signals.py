"""A source message's signals as the spec's fields: name, bits, scaling, range, unit, value table,
role, multiplexing, and what a canspec-written DBC put in its comments (special values, the spec's
name of a renamed signal). Every decision a source did not make is a warning."""

from __future__ import annotations

import re
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from canspec.importer.attributes import kept_values
from canspec.importer.dbctext import Numbers
from canspec.importer.load import Loaded
from canspec.importer.names import Namer
from canspec.importer.pages import Pages
from canspec.ir.bits import positions
from canspec.ir.encoding import raw_range
from canspec.targets.dbc.comments import SEPARATOR
from canspec.targets.dbc.naming import SPEC_NAME_ATTRIBUTE

NO_NODE = "Vector__XXX"
SIG_TYPE_ROLES = {"MessageCounter": "counter", "MessageChecksum": "checksum"}
# A special value as the DBC target writes it in a comment part: `0x3FF = no_obstacle (无障碍物)`.
_SPECIAL = re.compile(r"^(-?)0x([0-9A-Fa-f]+) = ([A-Za-z_][A-Za-z0-9_]*)(?: \((.*)\))?$")
_SPEC_NAME = "spec name: "


@dataclass
class Where:
    """The message being converted: the source, its DBC ID, names, and where to warn."""

    loaded: Loaded
    dbc_id: int
    source_msg: str  # the message's name in the source
    msg_name: str  # its spec name
    lines: dict[tuple[int, str], int]
    warn: Any  # (line, text)


def _number(value: Fraction) -> int | Fraction:
    return value.numerator if value.denominator == 1 else value


def attribute(obj: Any, name: str, db: Any = None) -> Any:
    """A cantools object's DBC attribute value, or None. Without a BA_ value of its own it has the
    definition's BA_DEF_DEF_ default, as in every DBC tool (a bus whose `Baudrate` only the default
    states runs at that rate): the definitions of `db`, its database, or its own when it is one."""
    attrs = getattr(getattr(obj, "dbc", None), "attributes", None) or {}
    own = getattr(attrs.get(name), "value", None)
    if own is not None:
        return own
    definitions = getattr(getattr(obj if db is None else db, "dbc", None), "attribute_definitions", None) or {}
    return getattr(definitions.get(name), "default_value", None)


def convert_signals(at: Where, msg: Any, default_order: str, tables: dict[str, dict[int, Any]], written: dict[tuple[int, str], Numbers],
                    kept: dict[str, dict[str, Any]]) -> list[dict[str, Any]] | None:
    """The message's fields in the file's order (the first of two that can be in one frame keeps
    its bits); None when its multiplexing cannot be expressed (warned)."""
    out, names, pages = [], Namer(tuple(at.loaded.renamed.get(s.name, s.name) for s in msg.signals)), Pages(msg, at.source_msg)
    if (refusal := pages.refusal()) is not None:
        at.warn(*_refusal_at(at, refusal, [n for n, (by, _) in pages.parent.items() if by is None]))
        return None
    for name, text in pages.oddities():
        at.warn(at.lines.get((at.dbc_id, name)), text)
    spec_names: dict[str, str] = {}
    for sig in msg.signals:
        source_name = at.loaded.renamed.get(sig.name, sig.name)
        line = at.lines.get((at.dbc_id, sig.name))
        if (why := _unfit(sig, msg, pages)) is not None:
            at.warn(line, f"signal {source_name} of {at.source_msg} {why}: left out")
            continue
        pages.take(sig)
        converted = _signal(at, sig, default_order, names, written.get((at.dbc_id, sig.name)), tables, line)
        spec_names[sig.name] = converted["name"]
        converted["receivers"] = [r for r in sig.receivers if r != NO_NODE]  # the spec's names and whether to keep them: tospec._node_names
        if values := kept_values(sig, kept, lambda text, where=line: at.warn(where, text), f"signal {sig.name} of {at.source_msg}"):
            converted["dbc_attributes"] = values
        out.append(converted)
    return pages.attach(out, spec_names, lambda name, text: at.warn(at.lines.get((at.dbc_id, name)), text))


def _refusal_at(at: Where, refusal: str, orphans: list[str]) -> tuple[int | None, str]:
    """The warning for a message left out for its multiplexing, at the SG_MUL_VAL_ line that names a
    signal its own multiplexer (cantools then finds none) where there is one, else at the BO_ line."""
    for i, line in enumerate((at.loaded.text or "").split("\n"), 1):
        words = line.replace(";", " ").split()
        if len(words) >= 4 and words[0] == "SG_MUL_VAL_" and words[1] == str(at.dbc_id) and words[2] == words[3] and words[2] in orphans:
            name = at.loaded.renamed.get(words[2], words[2])
            return i, f"message {at.source_msg}: SG_MUL_VAL_ names signal {name} as its own multiplexer: left out (hint: name the M signal " \
                      "that selects its pages)"
    return at.lines.get((at.dbc_id, "")), f"message {at.source_msg}: {refusal}: left out"


def _unfit(sig: Any, msg: Any, pages: Pages) -> str | None:
    """Why a field cannot be taken (its width, its bits, another field's bits in the same frame)."""
    if not 1 <= sig.length <= 64:
        return f"is {sig.length} bits long (a field has 1 to 64 bits)"
    bits = positions(sig.start, sig.length, sig.byte_order)
    if any(b >= 8 * msg.length for b in bits):
        return f"leaves its {msg.length}-byte frame"
    clash = pages.overlaps(sig, bits)
    if clash:
        return f"overlaps {', '.join(clash)} (a field owns its bits in every frame it is in)"
    return None


def _signal(at: Where, sig: Any, default_order: str, names: Namer, numbers: Numbers | None, tables: dict[str, dict[int, Any]],
            line: int | None) -> dict[str, Any]:
    source_name = at.loaded.renamed.get(sig.name, sig.name)
    # canspec renamed it in the DBC (targets/dbc/naming.py): the spec's name comes back ("", the default, is none)
    spec_name = str(attribute(sig, SPEC_NAME_ATTRIBUTE) or "")
    name = names.name(spec_name or source_name, "signal")
    out: dict[str, Any] = {"name": name}
    if name != source_name:
        out["dbc_name"] = names.dbc(source_name, lambda text: at.warn(line, text))
    out["start"], out["len"] = sig.start, sig.length
    if sig.byte_order != default_order:
        out["byte_order"] = sig.byte_order
    if sig.is_float:
        out["float"] = True
    elif sig.is_signed:
        out["signed"] = True
    _scaling(at, sig, out, numbers, line)
    if sig.unit:
        out["unit"] = str(sig.unit)
    choices = _choices(at, sig, source_name, line)
    desc, specials = _comment(sig, dict(choices), bool(spec_name))
    if desc:
        out["desc"] = desc
    choices = [(raw, text) for raw, text in choices if raw not in specials]
    if choices:
        table, labels = f"{at.msg_name}_{name}", Namer()
        tables[table] = {raw: _label(labels.name(text, f"value_{raw}"), text) for raw, text in choices}
        out["values"] = table
    if specials:
        out["special"] = specials
    role = SIG_TYPE_ROLES.get(str(_sig_type(at.loaded, sig)))
    if role is not None:
        out["role"] = role
    return out


def _scaling(at: Where, sig: Any, out: dict[str, Any], numbers: Numbers | None, line: int | None) -> None:
    """factor, offset and range, as the SG_ line wrote them (cantools' doubles where it did not parse)."""
    source_name = out.get("dbc_name", out["name"])
    factor, offset, lo, hi = numbers if numbers is not None else (
        Fraction(str(sig.scale)), Fraction(str(sig.offset)), Fraction(str(sig.minimum or 0)), Fraction(str(sig.maximum or 0)))
    if not sig.is_float:
        if factor != 1:
            out["factor"] = _number(factor)
        if offset != 0:
            out["offset"] = _number(offset)
    elif factor != 1 or offset != 0:
        at.warn(line, f"float signal {source_name} is scaled ({factor}, {offset}): scaling dropped (a float field holds its value)")
    if lo == hi == 0:  # [0|0]: no range
        return
    lo, hi = min(lo, hi), max(lo, hi)
    if not sig.is_float and factor:
        first, last = raw_range(sig.length, bool(sig.is_signed), factor, offset, (lo, hi))
        if first > last:
            at.warn(line, f"signal {source_name}: range [{_number(lo)}|{_number(hi)}] holds no value of the field: dropped")
            return
    out["range"] = [_number(lo), _number(hi)]


def _comment(sig: Any, choices: dict[int, str], renamed: bool) -> tuple[str, dict[int, str | list[str]]]:
    """The comment as the spec's desc, and the special values a canspec-written DBC put in it
    (`0x3FF = no_obstacle (无障碍物)`, listed in VAL_ under the same name); the `spec name:` part
    of a renamed signal goes with its attribute."""
    if not sig.comment:
        return "", {}
    parts: list[str] = []
    specials: dict[int, str | list[str]] = {}
    for part in str(sig.comment).split(SEPARATOR):
        m = _SPECIAL.match(part)
        raw = int(m.group(1) + m.group(2), 16) if m else 0
        if m and choices.get(raw) == m.group(3):
            specials[raw] = [m.group(3), m.group(4)] if m.group(4) else m.group(3)
        elif not (renamed and part.startswith(_SPEC_NAME)):
            parts.append(part)
    return SEPARATOR.join(parts), specials


def _label(ident: str, text: str) -> str | dict[str, str]:
    """A value label: the identifier, with the source's own text where that differs."""
    return ident if ident == text else {"name": ident, "dbc": text}


def _sig_type(loaded: Loaded, sig: Any) -> Any:
    value = attribute(sig, "SigType")
    definitions = getattr(getattr(loaded.db, "dbc", None), "attribute_definitions", None) or {}
    choices = getattr(definitions.get("SigType"), "choices", None)
    return choices[value] if isinstance(value, int) and choices and 0 <= value < len(choices) else value


def _choices(at: Where, sig: Any, source_name: str, line: int | None) -> list[tuple[int, str]]:
    """The value table's entries that fit the field; the others dropped with a warning."""
    if sig.choices and sig.is_float:
        at.warn(line, f"float signal {source_name} has value labels: dropped (a float field has no value table)")
    if not sig.choices or sig.is_float:
        return []
    lo, hi = (-(1 << (sig.length - 1)), (1 << (sig.length - 1)) - 1) if sig.is_signed else (0, (1 << sig.length) - 1)
    kept = []
    for raw, value in sorted(sig.choices.items()):
        if lo <= int(raw) <= hi:
            kept.append((int(raw), str(getattr(value, "name", value))))
        else:
            at.warn(line, f"value {raw} of signal {source_name} does not fit its {sig.length} bits: dropped")
    return kept
