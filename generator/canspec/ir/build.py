"""Build the frozen IR from a resolved, validated spec. All meaning is computed here."""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache
from typing import Any, NamedTuple

from canspec import __version__, ir
from canspec.ir import j1939
from canspec.ir.bits import segments, storage_bits, word_shift
from canspec.ir.build_json import build_json, plain
from canspec.ir.dbc_attributes import Attributes, AttributeValue, DbcAttributeDef
from canspec.ir.encoding import (
    FLOAT_MAX,
    covering_decimal,
    decimal_text,
    decimals,
    fits_runtime,
    raw_range,
    raw_type_range,
    to_physical_runtime,
    to_raw_runtime,
)
from canspec.ir.fingerprint import layout_fingerprint
from canspec.ir.ids import id_text
from canspec.ir.mux import MuxCondition, groups, ranges_of
from canspec.ir.names import humanize
from canspec.spec.loader import LoadedSpec
from canspec.spec.resolve import Resolved, ResolvedCan, label_dbc, label_pair
from canspec.spec.yamlsource import LocDict

MAX_DECIMALS = 15  # log texts print physical doubles with Signal.decimals places: a double holds no more significant digits


def _value_table(name: str, table: LocDict) -> ir.ValueTable:
    entries = sorted((r, label_pair(v), label_dbc(v)) for r, v in table.items())
    return ir.ValueTable(name, tuple(ir.ValueEntry(raw, ident, zh, humanize(ident), table.loc_of(raw), text) for raw, (ident, zh), text in entries), table.loc)


def _labels(table: ir.ValueTable | None, specials: tuple[ir.SpecialValue, ...]) -> tuple[ir.Label, ...]:
    named = {e.raw: ir.Label(e.raw, e.name, e.label_zh, e.label, False, e.dbc_text) for e in (table.entries if table else ())}
    for s in specials:
        named.setdefault(s.raw, ir.Label(s.raw, s.name, s.label_zh, s.label, True))
    return tuple(named[raw] for raw in sorted(named))


def _accepted(lo: Fraction, hi: Fraction, raws: tuple[int, int], factor: Fraction, offset: Fraction, field: tuple[int, int]) -> tuple[Fraction, Fraction]:
    """[lo, hi] (the range widened by the tie tolerance) widened further to the doubles the decoders
    return for the raw ends, wherever the runtime rule carries those back: a double's step can
    exceed the tolerance (raw 0x7FFFFFFF × 0.1 decodes to 214748364.70000002, beyond 214748364.7 +
    1e-10), and every decoded value must encode to its raw value again."""
    f, o = float(factor), float(offset)
    for raw in raws:
        x = to_physical_runtime(raw, f, o)
        # not where the double quotient leaves the field (the encoders' window refuses it) or rounds
        # elsewhere (fields wider than 2^52 steps)
        if not fits_runtime((x - o) / f, *field) or to_raw_runtime(x, f, o) != raw:
            continue
        if Fraction(x) < lo:
            lo = covering_decimal(x, up=False)
        if Fraction(x) > hi:
            hi = covering_decimal(x, up=True)
    return lo, hi


class _Ranges(NamedTuple):
    """A field's ranges (ir.Signal): raw, physical, as documented or derived, and as encode accepts them."""

    raw_min: int
    raw_max: int
    phys_min: Fraction
    phys_max: Fraction
    check_min: Fraction
    check_max: Fraction
    accept_min: Fraction
    accept_max: Fraction


@lru_cache(maxsize=4096)  # exact arithmetic on Fractions, and real buses repeat a few scalings thousands of times
def _ranges_of(length: int, signed: bool, is_float: bool, factor: Fraction, offset: Fraction, doc: tuple[Fraction | None, Fraction | None],
               stated: bool) -> _Ranges:
    doc_min, doc_max = doc
    tmin, tmax = raw_type_range(length, signed)
    if is_float:  # the bit pattern is the raw value; ranges are the float's own (ir.Signal.is_float)
        phys_min, phys_max = -FLOAT_MAX[length], FLOAT_MAX[length]
        check_min = doc_min if doc_min is not None else phys_min
        check_max = doc_max if doc_max is not None else phys_max
        return _Ranges(tmin, tmax, phys_min, phys_max, check_min, check_max, check_min, check_max)
    raw_min, raw_max = raw_range(length, signed, factor, offset, doc if stated else None)
    phys_a, phys_b = ir.to_physical(raw_min, factor, offset), ir.to_physical(raw_max, factor, offset)
    phys_min, phys_max = min(phys_a, phys_b), max(phys_a, phys_b)
    check_min = doc_min if doc_min is not None else phys_min
    check_max = doc_max if doc_max is not None else phys_max
    tolerance = Fraction(0) if _is_integer(factor, offset) else abs(factor) * Fraction(ir.TIE_EPSILON_TEXT)
    accept = _accepted(check_min - tolerance, check_max + tolerance, (raw_min, raw_max), factor, offset, (tmin, tmax))
    return _Ranges(raw_min, raw_max, phys_min, phys_max, check_min, check_max, *accept)


def _signal(sig: LocDict, tables: dict[str, ir.ValueTable], frame_bytes: int, multiplexers: frozenset[str] = frozenset()) -> ir.Signal:
    length, signed, is_float = sig["len"], bool(sig["signed"]), bool(sig["float"])
    factor, offset = Fraction(sig["factor"]), Fraction(sig["offset"])
    tmin, tmax = raw_type_range(length, signed)
    rng = sig.get("range")
    doc_min, doc_max = (Fraction(rng[0]), Fraction(rng[1])) if rng is not None else (None, None)
    ranges = _ranges_of(length, signed, is_float, factor, offset, (doc_min, doc_max), rng is not None)
    is_integer = _is_integer(factor, offset) and not is_float
    specials = tuple(
        ir.SpecialValue(raw, ident, zh, humanize(ident), ir.to_physical(raw, factor, offset))
        for raw, (ident, zh) in sorted((r, label_pair(v)) for r, v in sig.get("special", {}).items())
    )
    table = tables.get(sig["values"]) if sig.get("values") else None
    order = sig["byte_order"]
    shift = word_shift(sig["start"], length, order, frame_bytes)
    return ir.Signal(
        name=sig["name"],
        c_name=sig.get("c_name", sig["name"]),
        zh=sig.get("zh", ""),
        desc=sig["desc"],
        desc_zh=sig["desc_zh"],
        start=sig["start"],
        length=length,
        signed=signed,
        factor=factor,
        offset=offset,
        unit=sig["unit"],
        role=sig["role"],
        doc_min=doc_min,
        doc_max=doc_max,
        raw_type_min=tmin,
        raw_type_max=tmax,
        **ranges._asdict(),
        storage_bits=storage_bits(length),
        value_table=table,
        specials=specials,
        segments=segments(sig["start"], length, order),
        word_shift=shift,
        word_mask=((1 << length) - 1) << shift,
        sign_bit=1 << (length - 1) if signed else 0,
        labels=_labels(table, specials),
        decimals=0 if is_integer or is_float else min(MAX_DECIMALS, max(decimals(factor), decimals(offset))),
        is_integer=is_integer,
        is_identity=factor == 1 and offset == 0 and not is_float,
        since=str(sig["since"]) if sig.get("since") else None,
        errata=tuple(sig.get("errata", ())),
        loc=sig.loc,
        byte_order=order,
        is_float=is_float,
        mux=MuxCondition(sig["mux"]["by"], ranges_of(sig["mux"]["values"])) if "mux" in sig else None,
        is_multiplexer=sig["name"] in multiplexers,
        dbc_name=sig.get("dbc_name", sig["name"]),
        receivers=tuple(sig["receivers"]) if "receivers" in sig else None,
        dbc_attributes=_attributes(sig),
    )


def _is_integer(factor: Fraction, offset: Fraction) -> bool:
    return factor.denominator == 1 and offset.denominator == 1


def _layout_fields(signals: tuple[ir.Signal, ...]) -> list[tuple[str, int, int, bool, str, str]]:
    """The fingerprint's fields; byte order and float marked only where they are not Intel integers,
    so that a fingerprint of an Intel integer message is what it was before either existed."""
    def role(s: ir.Signal) -> str:
        return s.role + (":be" if s.is_big_endian else "") + (":float" if s.is_float else "") + (":M" if s.is_multiplexer else "") + _mux_tag(s)

    return [(role(s), s.start, s.length, s.signed, decimal_text(s.factor), decimal_text(s.offset)) for s in signals if not s.is_reserved]


def _mux_tag(s: ir.Signal) -> str:
    if s.mux is None:
        return ""
    return f":m{s.mux.by}=" + ",".join(f"{lo}-{hi}" for lo, hi in s.mux.ranges)


def _mux_groups(signals: tuple[ir.Signal, ...]) -> tuple[ir.MuxGroup, ...]:
    """Each multiplexer's pages, the top-level multiplexer's first (then the others in frame order)."""
    muxes = sorted((s for s in signals if s.is_multiplexer), key=lambda s: s.mux is not None)
    return tuple(g for m in muxes for g in groups(m.name, [(s.name, s.mux.ranges) for s in signals if s.mux is not None and s.mux.by == m.name]))


def _message(msg: LocDict, can: ResolvedCan, tables: dict[str, ir.ValueTable], node_names: tuple[str, ...]) -> ir.Message:
    dlc = msg.get("dlc", 8)
    multiplexers = frozenset(s["mux"]["by"] for s in msg["signals"] if "mux" in s)
    signals = tuple(_signal(s, tables, dlc, multiplexers) for s in msg["signals"])
    checksum = next((_checksum(s, dlc) for s in signals if s.role == "checksum"), None)
    counter = next((ir.Counter(s.name, s.length, 1 << s.length, s.word_shift, s.word_mask, s.word_order) for s in signals if s.role == "counter"), None)
    mf = msg.get("multiframe")
    multiframe = None
    if mf is not None:
        payload = next(s for s in signals if s.name == mf["payload"])
        keys = tuple(s.name for s in signals if s.role == "data" and s.name not in (mf["index"], mf["payload"]))
        multiframe = ir.MultiFrame(
            mf["index"], mf["payload"], mf["encoding"], mf["text_length"], mf["frames"], payload.length // 8, payload.start // 8, mf["padding"], keys
        )
    receivers = msg["receivers"]
    if receivers == "ALL":
        receivers = tuple(n for n in node_names if n != msg["sender"])
    fd = bool(msg.get("fd", False))
    fingerprint = layout_fingerprint(msg["id"], dlc, _layout_fields(signals), fd)
    bus = can.doc.data["bus"]
    extended = msg.get("extended", bus["id_format"] == "extended")
    cycle = msg.get("cycle_ms") or None  # 0 or absent: event-driven
    return ir.Message(
        name=msg["name"],
        c_name=msg.get("c_name", msg["name"]),
        title=msg.get("title", msg["name"]),
        zh=msg.get("zh", ""),
        desc=msg.get("desc", ""),
        section=str(msg.get("section", "")),
        frame_id=msg["id"],
        is_extended=extended,
        id_text=id_text(msg["id"], extended),
        dlc=dlc,
        cycle_ms=cycle,
        timeout_ms=cycle * ir.MONITOR_TIMEOUT_CYCLES if cycle else None,
        sender=msg["sender"],
        receivers=tuple(receivers),
        j1939=j1939.decompose(msg["id"]) if bus["addressing"] == "j1939" else None,
        signals=signals,
        layout=msg.get("layout"),
        layout_undefined=bool(msg.get("layout_undefined", False)),
        checksum=checksum,
        counter=counter,
        multiframe=multiframe,
        fingerprint=fingerprint,
        errata=tuple(msg.get("errata", ())),
        loc=msg.loc,
        dbc_name=msg.get("dbc_name", msg["name"]),
        is_fd=fd,
        brs=fd and bool(msg.get("brs", bus.get("data_bitrate") is not None)),
        mux_groups=_mux_groups(signals),
        dbc_senders=tuple(msg.get("dbc_senders", ())),
        dbc_attributes=_attributes(msg),
    )


def _checksum(sig: ir.Signal, dlc: int) -> ir.Checksum:
    byte = sig.start // 8
    covers = tuple(b for b in range(dlc) if b != byte)
    return ir.Checksum("xor", sig.name, byte, covers, sum(0xFF << (8 * b) for b in covers))


def _fault_tables(tables: dict[str, ir.ValueTable], messages: tuple[ir.Message, ...]) -> tuple[ir.FaultTable, ...]:
    out = []
    for t in tables.values():
        by_name = {e.name: e.raw for e in t.entries}
        if ir.FAULT_TIMEOUT_ENTRY not in by_name or t.by_raw(0) is None:
            continue
        codes = tuple(
            (m.name, by_name[f"{m.layout}{ir.FAULT_XOR_ERROR_SUFFIX}"])
            for m in messages
            if m.checksum is not None and m.layout and f"{m.layout}{ir.FAULT_XOR_ERROR_SUFFIX}" in by_name
        )
        out.append(ir.FaultTable(t.name, 0, by_name[ir.FAULT_TIMEOUT_ENTRY], codes))
    return tuple(out)


def build_can(can: ResolvedCan) -> ir.CanProtocol:
    data = can.doc.data
    tables = {name: _value_table(name, t) for name, t in sorted(can.value_tables.items())}
    nodes = tuple(
        ir.Node(n["name"], n.get("label", n["name"]), n.get("sa"), n.get("zh", ""), n.get("desc", ""), tuple(n.get("aliases", [])), loc=n.loc,
                dbc_name=n.get("dbc_name", n["name"]), dbc_attributes=_attributes(n))
        for n in data["nodes"]
    )
    names = tuple(n.name for n in nodes)
    p, b = data["protocol"], data["bus"]
    messages = tuple(_message(m, can, tables, names) for m in can.messages)
    return ir.CanProtocol(
        name=p["name"],
        title=p.get("title", p["name"]),
        title_zh=p.get("title_zh", ""),
        version=str(p["version"]),
        document=p.get("document", ""),
        bus=ir.Bus(b["bitrate"], b["id_format"], b["addressing"], b["byte_order"], b.get("data_bitrate")),
        nodes=nodes,
        messages=messages,
        value_tables=tuple(tables.values()),
        fault_tables=_fault_tables(tables, messages),
        loc=p.loc_of("name"),
        dbc_signal_names=p.get("dbc_signal_names", "per_message"),
        dbc_as_imported=bool(p.get("dbc_as_imported", False)),
        dbc_attribute_defs=tuple(_attribute_def(name, d) for name, d in data.get("dbc_attributes", {}).items()),
    )


def _attributes(obj: LocDict) -> Attributes:
    return tuple((name, _plain_number(v)) for name, v in obj.get("dbc_attributes", {}).items())


def _plain_number(v: Any) -> AttributeValue:
    """A YAML number (the loader may give Decimal) as an int where it is whole, else a float."""
    if isinstance(v, str | int):
        return v
    return int(v) if Fraction(v).denominator == 1 else float(v)


def _attribute_def(name: str, d: LocDict) -> DbcAttributeDef:
    def get(key: str) -> AttributeValue | None:
        return _plain_number(d[key]) if key in d else None

    return DbcAttributeDef(name, d["object"], d["type"], get("min"), get("max"), tuple(d.get("values", ())), get("default"), get("value"))


def build_changelog(doc: Any) -> ir.Changelog:
    data = doc.data
    versions = tuple(
        ir.ChangeVersion(
            version=str(v["version"]),
            date=v.get("date"),
            authors=tuple(v.get("authors", [])),
            label=v.get("label", ""),
            label_zh=v.get("label_zh", ""),
            items=tuple(
                ir.ChangeItem(
                    i + 1,
                    it.get("zh", ""),
                    it.get("en", ""),
                    tuple(it.get("ids", [])),
                    tuple(it.get("errata", [])),
                    tuple(plain(c) for c in it.get("changes", [])),
                )
                for i, it in enumerate(v["items"])
            ),
            errata=tuple(v.get("errata", [])),
        )
        for v in data["versions"]
    )
    return ir.Changelog(data["protocol"], versions)


def build(loaded: LoadedSpec, res: Resolved) -> ir.Spec:
    can = build_can(res.can) if res.can is not None else None
    jsons = tuple(build_json(d) for d in res.json)
    name = loaded.bundle_name or (can.name if can else (jsons[0].name if jsons else "spec"))
    version = can.version if can else (jsons[0].version if jsons else "0.0.0")
    return ir.Spec(
        name=name, version=version, sha256=loaded.sha256, can=can, json=jsons,
        changelog=build_changelog(res.changelog) if res.changelog is not None else None, generator_version=__version__,
        errata_md=_errata_text(loaded),
    )


def _errata_text(loaded: LoadedSpec) -> str | None:
    path = loaded.errata_path
    return path.read_text(encoding="utf-8").replace("\r\n", "\n") if path.is_file() else None
