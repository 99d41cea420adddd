"""YAML → plain data that remembers where every mapping, key and item came from.

Numbers with a fraction load as Decimal (0.1 stays exactly 0.1), only `true`/`false` are
booleans (YAML 1.1 would turn the value identifier `off` into False), and a duplicate
key is an error instead of a silent overwrite.
"""

from __future__ import annotations

import re
import stat
from decimal import Decimal
from pathlib import Path
from typing import Any

import yaml

from canspec.spec.problems import Loc, SpecError, error


class LocDict(dict):  # type: ignore[type-arg]
    """A mapping with the location of itself, of each key and of each value."""

    loc: Loc
    key_locs: dict[Any, Loc]
    value_locs: dict[Any, Loc]
    key_nodes: dict[Any, int]  # id of the YAML node each key came from (merge-key overrides)

    def loc_of(self, key: Any) -> Loc:
        return self.value_locs.get(key) or self.loc


class LocList(list):  # type: ignore[type-arg]
    loc: Loc
    item_locs: list[Loc]

    def loc_of(self, index: int) -> Loc:
        return self.item_locs[index] if 0 <= index < len(self.item_locs) else self.loc


def loc_of(container: Any, key: Any = None) -> Loc | None:
    """Best location for `container[key]` (or the container itself)."""
    if key is not None and isinstance(container, (LocDict, LocList)):
        return container.loc_of(key)
    return getattr(container, "loc", None)


# Spec files are small text; these bound what a hostile or broken file can cost.
MAX_FILE_BYTES = 32 * 1024 * 1024
MAX_VALUES = 5_000_000  # mapping entries and list items after expanding aliases ("billion laughs")


try:  # libyaml's scanner and parser when PyYAML has them: about 4x faster on big specs
    from yaml.cyaml import CParser as _CParser
except ImportError:  # PyYAML built without libyaml (tests/spec/test_yaml_fallback.py)
    _CParser = None

if _CParser is not None:

    class _Base(_CParser, yaml.composer.Composer, yaml.constructor.SafeConstructor, yaml.resolver.Resolver):  # type: ignore[misc]
        """libyaml turns the text into events; composing and constructing stay in Python, so
        marks, the resolvers below and the nesting limit (a RecursionError, never a C stack
        overflow as with CSafeLoader) behave as with the pure-Python loader."""

        positions_in_bytes = True  # libyaml reports reader errors at UTF-8 byte offsets

        def __init__(self, stream: str) -> None:
            _CParser.__init__(self, stream)
            yaml.composer.Composer.__init__(self)
            yaml.constructor.SafeConstructor.__init__(self)
            yaml.resolver.Resolver.__init__(self)

        get_single_node = yaml.composer.Composer.get_single_node
        get_node = yaml.composer.Composer.get_node
        check_node = yaml.composer.Composer.check_node

else:

    class _Base(yaml.SafeLoader):  # type: ignore[no-redef]
        positions_in_bytes = False


class _Loader(_Base):
    display_name = "<spec>"
    first_alias: yaml.Mark | None = None

    def compose_node(self, parent, index):  # type: ignore[no-untyped-def]
        if self.first_alias is None and self.check_event(yaml.AliasEvent):
            self.first_alias = self.peek_event().start_mark
        return super().compose_node(parent, index)


# YAML 1.2 booleans only.
_Loader.yaml_implicit_resolvers = {
    first: [(tag, rx) for tag, rx in resolvers if tag != "tag:yaml.org,2002:bool"]
    for first, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()
}
# Dates stay text (`2020-09-12`), as the spec schema expects.
_Loader.yaml_implicit_resolvers = {
    first: [(tag, rx) for tag, rx in resolvers if tag != "tag:yaml.org,2002:timestamp"]
    for first, resolvers in _Loader.yaml_implicit_resolvers.items()
}
_Loader.add_implicit_resolver(
    "tag:yaml.org,2002:bool", re.compile(r"^(?:true|True|TRUE|false|False|FALSE)$"), list("tTfF")
)


def _mark(loader: _Loader, node: yaml.Node) -> Loc:
    return Loc(loader.display_name, node.start_mark.line + 1, node.start_mark.column + 1)


def _construct_mapping(loader: _Loader, node: yaml.MappingNode) -> LocDict:
    # Keys written in this mapping. Only those may not repeat: keys merged in with `<<:` are
    # overridden by them, and among merged mappings the first listed wins (PyYAML's order).
    explicit = {id(k) for k, _ in node.value if k.tag != "tag:yaml.org,2002:merge"}
    loader.flatten_mapping(node)
    data = LocDict()
    data.loc = _mark(loader, node)
    data.key_locs = {}
    data.value_locs = {}
    data.key_nodes = {}
    for key_node, value_node in node.value:
        key = loader.construct_object(key_node, deep=True)
        try:
            hash(key)
        except TypeError:
            raise SpecError([error("a mapping key must be a scalar", _mark(loader, key_node))]) from None
        if key in data and id(key_node) in explicit and data.key_nodes[key] in explicit:
            first = data.key_locs[key]
            raise SpecError(
                [
                    error(
                        f"duplicate key {key!r} (first defined at line {first.line})",
                        _mark(loader, key_node),
                        "each key may appear once per mapping; remove or rename one of them",
                        "yaml-duplicate-key",
                    )
                ]
            )
        data[key] = loader.construct_object(value_node, deep=True)
        data.key_nodes[key] = id(key_node)
        data.key_locs[key] = _mark(loader, key_node)
        data.value_locs[key] = _mark(loader, value_node)
    return data


def _construct_sequence(loader: _Loader, node: yaml.SequenceNode) -> LocList:
    data = LocList(loader.construct_object(child, deep=True) for child in node.value)
    data.loc = _mark(loader, node)
    data.item_locs = [_mark(loader, child) for child in node.value]
    return data


def _construct_float(loader: _Loader, node: yaml.ScalarNode) -> Decimal | float:
    text = str(loader.construct_scalar(node)).replace("_", "")
    try:
        return Decimal(text)
    except ArithmeticError:
        return float(loader.construct_yaml_float(node))  # .inf / .nan: kept, rejected by validation


_Loader.add_constructor("tag:yaml.org,2002:map", _construct_mapping)
_Loader.add_constructor("tag:yaml.org,2002:seq", _construct_sequence)
_Loader.add_constructor("tag:yaml.org,2002:float", _construct_float)


# --- the fast path -----------------------------------------------------------------------------
# Building the data straight from libyaml's events, without PyYAML's node graph and its Python
# composer and constructor, halves the load of a large spec. It takes the YAML specs are written in:
# one document of mappings, sequences and scalars, without anchors, aliases, merge keys, explicit
# tags other than the core schema's, repeated keys or deep nesting. On anything else it gives up
# and the loader above reads the file, so errors and their messages come from one place
# (tests/spec/test_yaml_fast_path.py: both give the same data and locations).

FAST_DEPTH = 48  # deeper documents go to the loader above (its nesting limit and message)
_STR, _MAP, _SEQ = "tag:yaml.org,2002:str", "tag:yaml.org,2002:map", "tag:yaml.org,2002:seq"
_SCALARS = {"tag:yaml.org,2002:int", "tag:yaml.org,2002:float", "tag:yaml.org,2002:bool", "tag:yaml.org,2002:null"}


class _Unsupported(Exception):
    """The fast path does not take this document."""


class _EventBuilder:
    def __init__(self, loader: _Loader, name: str) -> None:
        self.loader, self.name, self.next = loader, name, loader.get_event
        # Scalars by (text, tag, implicit): a spec repeats the same words and numbers thousands of
        # times, and resolving and constructing each again was a third of the load. Their values
        # (str, int, Decimal, float, bool, None) are immutable, so one object can serve every use.
        self.scalars: dict[tuple[str, str | None, tuple[bool, bool]], Any] = {}

    def document(self) -> Any:
        kinds = [type(self.next()) for _ in range(2)]
        if kinds != [yaml.StreamStartEvent, yaml.DocumentStartEvent]:
            raise _Unsupported
        data = self.node(self.next(), 0)
        if [type(self.next()) for _ in range(2)] != [yaml.DocumentEndEvent, yaml.StreamEndEvent]:
            raise _Unsupported  # a second document: the loader above says so
        return data

    def loc(self, event: yaml.Event) -> Loc:
        return Loc(self.name, event.start_mark.line + 1, event.start_mark.column + 1)

    def node(self, event: yaml.Event, depth: int) -> Any:
        kind = type(event)
        if kind is yaml.ScalarEvent:
            return self.scalar(event)
        if kind not in (yaml.MappingStartEvent, yaml.SequenceStartEvent) or event.anchor is not None or depth > FAST_DEPTH:
            raise _Unsupported
        if event.tag not in (None, "!", _MAP if kind is yaml.MappingStartEvent else _SEQ):
            raise _Unsupported
        return self.mapping(event, depth) if kind is yaml.MappingStartEvent else self.sequence(event, depth)

    def mapping(self, start: yaml.Event, depth: int) -> LocDict:
        data = LocDict()
        data.loc, data.key_locs, data.value_locs, data.key_nodes = self.loc(start), {}, {}, {}
        while type(key_event := self.next()) is not yaml.MappingEndEvent:
            if type(key_event) is not yaml.ScalarEvent:
                raise _Unsupported  # a collection as key: the loader above refuses it
            key = self.scalar(key_event)
            if key in data:
                raise _Unsupported  # a repeated key: the loader above refuses it
            value_event = self.next()
            data[key] = self.node(value_event, depth + 1)
            data.key_locs[key], data.value_locs[key] = self.loc(key_event), self.loc(value_event)
            data.key_nodes[key] = len(data.key_nodes)
        return data

    def sequence(self, start: yaml.Event, depth: int) -> LocList:
        data, locs = LocList(), []
        while type(event := self.next()) is not yaml.SequenceEndEvent:
            data.append(self.node(event, depth + 1))
            locs.append(self.loc(event))
        data.loc, data.item_locs = self.loc(start), locs
        return data

    def scalar(self, event: yaml.ScalarEvent) -> Any:
        if event.anchor is not None:
            raise _Unsupported
        key = (event.value, event.tag, event.implicit)
        if key not in self.scalars:
            self.scalars[key] = self._construct(event)
        return self.scalars[key]

    def _construct(self, event: yaml.ScalarEvent) -> Any:
        tag = event.tag
        if tag is None or tag == "!":
            tag = self.loader.resolve(yaml.ScalarNode, event.value, event.implicit)
        if tag == _STR:
            return event.value
        if tag not in _SCALARS:
            raise _Unsupported  # merge keys, binary, timestamps, local tags
        node = yaml.ScalarNode(tag, event.value, event.start_mark, event.end_mark, event.style)
        return self.loader.yaml_constructors[tag](self.loader, node)


def fast_load(text: str, name: str) -> Any:
    """The data of `text` built from libyaml's events; raises _Unsupported where the loader above must read it."""
    if _CParser is None:
        raise _Unsupported
    loader = _Loader(text)
    try:
        return _EventBuilder(loader, name).document()
    except yaml.YAMLError:
        raise _Unsupported from None
    finally:
        loader.dispose()


def _line_col_of_offset(raw: bytes, offset: int) -> tuple[int, int]:
    before = raw[:offset]
    line = before.count(b"\n") + 1
    col = offset - (before.rfind(b"\n") + 1) + 1
    return line, col


def _expanded_size(data: Any, memo: dict[int, int]) -> int:
    """Entries and items of `data` counted as if every alias were copied out (shared
    containers are counted once per use, computed once)."""
    if not isinstance(data, (dict, list)):
        return 1
    key = id(data)
    if key not in memo:
        memo[key] = 0  # a recursive alias cannot construct, so this is never read early
        items = data.values() if isinstance(data, dict) else data
        memo[key] = 1 + sum(_expanded_size(v, memo) for v in items)
    return memo[key]


def load_yaml(path: Path, display_name: str | None = None) -> Any:
    """Parse one YAML file into LocDict/LocList data; every failure is a SpecError."""
    name = display_name or str(path)
    text = _read_text(path, name)
    try:
        return fast_load(text, name)
    except _Unsupported:
        return _load_with_loader(text, name)


def _read_text(path: Path, name: str) -> str:
    """The file's text (UTF-8, no BOM); a SpecError where it is too large, unreadable or empty."""
    try:
        info = path.stat()
        if not stat.S_ISREG(info.st_mode) and not stat.S_ISDIR(info.st_mode):  # a device or FIFO: endless, or blocks on open
            raise SpecError([error("is not a regular file (a device, pipe or socket)", Loc(name), "pass the spec's YAML file or its directory")])
        if info.st_size > MAX_FILE_BYTES:
            raise SpecError([error(f"file is {info.st_size / 2**20:.0f} MiB; spec files are limited to {MAX_FILE_BYTES >> 20} MiB", Loc(name),
                                   "split the spec into several files listed in a bundle")])
        raw = path.read_bytes()
    except FileNotFoundError:
        raise SpecError([error("file not found", Loc(name), "check the path (and the bundle's `files` list)")]) from None
    except NotADirectoryError:
        raise SpecError([error("not found (a parent of this path is a file)", Loc(name), "check the path")]) from None
    except IsADirectoryError:
        raise SpecError([error("is a directory, expected a YAML file", Loc(name))]) from None
    except OSError as exc:
        raise SpecError([error(f"cannot read file: {exc.strerror}", Loc(name))]) from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line, col = _line_col_of_offset(raw, exc.start)
        raise SpecError(
            [error(f"not valid UTF-8 (byte 0x{raw[exc.start]:02X})", Loc(name, line, col), "save the file as UTF-8")]
        ) from None
    text = text.removeprefix("\ufeff")
    if not text.strip():
        raise SpecError([error("file is empty", Loc(name), "a spec file starts with `schema_version:` and `kind:`")])
    return text


def _load_with_loader(text: str, name: str) -> Any:
    """PyYAML's loader, for what the fast path does not take; its errors become SpecErrors."""
    loader = None
    try:
        loader = _Loader(text)
        loader.display_name = name
        data = loader.get_single_data()
    except SpecError:
        raise
    except yaml.reader.ReaderError as exc:
        before = text.encode("utf-8")[: exc.position].decode("utf-8", "replace") if _Base.positions_in_bytes else text[: exc.position]
        line, col = before.count("\n") + 1, len(before) - (before.rfind("\n") + 1) + 1
        raise SpecError([error(f"character U+{exc.character:04X} is not allowed in YAML", Loc(name, line, col), "remove the control character")]) from None
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        loc = Loc(name, mark.line + 1, mark.column + 1) if mark else Loc(name)
        what = exc.problem or exc.context or "invalid YAML"
        raise SpecError([error(f"YAML syntax error: {what}", loc, "fix the YAML syntax at this position")]) from None
    except yaml.YAMLError as exc:
        raise SpecError([error(f"YAML error: {exc}", Loc(name))]) from None
    except RecursionError:
        try:  # the parser still stands where the nesting got too deep
            mark = loader.peek_event().start_mark if loader is not None else None
        except Exception:  # noqa: BLE001 - a location is a nicety here
            mark = None
        loc = Loc(name, mark.line + 1, mark.column + 1) if mark else Loc(name)
        raise SpecError([error("YAML nesting is too deep", loc, "a spec nests a few levels; flatten this value")]) from None
    finally:
        if loader is not None:
            loader.dispose()
    if data is None:
        raise SpecError([error("file holds no data", Loc(name), "a spec file starts with `schema_version:` and `kind:`")])
    if loader.first_alias is not None and _expanded_size(data, {}) > MAX_VALUES:
        mark = loader.first_alias
        raise SpecError([error(f"YAML aliases expand this file to more than {MAX_VALUES:,} values", Loc(name, mark.line + 1, mark.column + 1),
                               "use fewer, smaller aliases (is this a \"billion laughs\" document?)")])
    return data
