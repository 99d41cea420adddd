"""Valid canspec specs, drawn at random: the input of the "any valid spec" harness.

Every spec is built by one function, `build(chooser, features)`, from a stream of integer
choices. Three choosers feed it:

- `specs()` — a Hypothesis strategy (`@given(specs())`): Hypothesis draws the integers and
  shrinks them, so a failing spec shrinks to a small one;
- `example(seed)` — a deterministic spec from a seed (`random.Random(seed)`), independent of
  the Hypothesis version: the batch harness draws spec i of a run as `example(base + i)`, and
  any failure reproduces from its seed alone;
- `replay(choices)` — the spec of a recorded choice sequence (the harness's shrinker edits
  these sequences: every choice shrinks towards its lower bound, and a shorter sequence
  gives a simpler spec, as with Hypothesis).

Smaller choices mean simpler specs throughout: fewer nodes, messages and signals, DLC 8,
identity scaling, no options, Intel order, classic frames, integer fields.

Always drawn (issue 24, no switch): the bus's default byte order (little or big endian) and
per field the other one now and then, so both orders mix in one frame and Motorola fields cross
bytes (counters and checksums too); CAN FD messages (`fd: true`, every FD length up to 64
bytes, `brs` on or off, the bus's `data_bitrate`); IEEE float32/float64 fields in either order,
with and without a range. Multi-frame text and shared layouts stay in classic frames.

The specs use the relaxed spec format of this issue. `NEW_FEATURES` names each relaxation;
`features=CURRENT` restricts the strategy to what the current checker accepts (so the
generator can be tested before the relaxations land), `features=ALL` (the default) may use
every one of them.
"""

from __future__ import annotations

import json
import random
from collections.abc import Sequence
from dataclasses import dataclass, field
from decimal import Decimal
from typing import Any

from hypothesis import strategies as st

# The relaxations of the spec format (this issue). The harness classifies a refusal by the
# current checker under the feature that explains it (see harness.classify_refusal).
NEW_FEATURES = {
    "j1939_derived": "a message under `addressing: j1939` without a `j1939:` block (derived from the ID)",
    "event_driven": "`cycle_ms: 0` or no `cycle_ms` (an event-driven message)",
    "empty_signals": "a message with `signals: []` (DLC 0) and no `layout_undefined`",
    "optional_signal_zh": "a signal without `zh`",
    "bare_value_ident": "a value-table entry `raw: ident` (no Chinese label)",
    "optional_node_sa": "a node without `sa` under `addressing: none`",
}
ALL = frozenset(NEW_FEATURES)
CURRENT: frozenset[str] = frozenset()

KEYWORDS = ("type", "match", "class", "int", "for", "async", "self", "default")
# Disjoint word pools, so that generated C/Rust/Python identifiers built from two names
# (message + signal, table + value) never collide by accident; keywords are whole names only.
MSG_WORDS = ("engine", "brake", "steer", "door", "lamp", "motor", "battery", "radar", "wiper", "seat", "horn", "pump", "valve", "charger")
MSG_SUFFIX = ("cmd", "state", "info", "status", "req", "data")
SIG_WORDS = (
    "speed", "mode", "temp", "level", "angle", "torque", "voltage", "current", "pressure", "flag", "fault", "position", "rate", "count", "value", "enable",
    "target", "limit")
TABLE_WORDS = ("mode", "state", "switch", "fault_level", "gear", "onoff", "status", "fault")
VALUE_IDENTS = (
    "off", "on", "idle", "active", "fault", "error", "ok", "low", "high", "open", "closed", "none", "auto", "manual", "unknown", "init", "invalid", "standby",
    "true", "false")
SPECIAL_IDENTS = ("not_available", "no_limit", "invalid_value", "error_value", "init_value", "no_obstacle")
NODE_NAMES = ("ECU", "VCU", "BMS", "GW", "CTRL", "EPS", "Tester", "node_a", "Radar1", "HMI")
PROTOCOL_NAMES = ("fixture", "demo_bus", "body_can", "chassis", "truck_j1939", "pt_can")
JSON_PROTOCOL_NAMES = ("remote", "tele_json", "cloud_link", "ops_api")
PARTIES = ("vehicle", "server", "autonomous", "client", "station")
JSON_FIELD_WORDS = ("speed", "mode", "angle", "level", "temp", "flag", "label", "gear", "ratio", "lat", "lng", "satCnt", "powerLevel", "note")
ZH_WORDS = ("车速", "模式", "温度", "状态", "故障", "开关", "角度", "扭矩", "电压", "心跳", "校验", "保留位", "档位")
TEXTS = (
    "A plain description.",
    "带中文的说明",
    'Percent % and "quotes"',
    "Back\\slash and 'single' quotes",
    "Comment closer */ inside",
    "Colon: and {braces} and #hash",
    "Line one.\nLine two.",
    "Ampersand & <angle> brackets",
)
UNITS = ("km/h", "%", "°C", "m/s²", "rpm", "V", "A", "deg", "Nm", "bar", "rpm/(km/h)", "1/min")
INT_FACTORS = (2, 10, 3, -1, 5, 100, 7)
INT_OFFSETS = (0, -40, 1, -1000, 250, -32768, 100000)
DEC_FACTORS = ("0.1", "0.05", "0.001", "2.5", "-0.5", "0.000001", "0.5", "0.02", "0.25", "0.3", "0.125", "0.01")
DEC_OFFSETS = ("0", "-12.8", "0.5", "-40", "1000000", "-1080", "-0.05", "1.5", "-273.15")
LENGTHS = (8, 1, 2, 4, 16, 3, 12, 10, 5, 7, 32, 24, 6, 20, 64, 48, 33, 63, 40, 11)
CLASSIC_DLCS = (8, 8, 4, 2, 1, 0, 3, 5, 6, 7)
FD_DLCS = (8, 12, 64, 16, 20, 24, 32, 48, 2, 5)  # a CAN FD frame: every FD length, and short ones
DATA_BITRATES = (2000000, 4000000, 5000000, 8000000, 1000000)
FLOAT_RANGES = (("-100", "100"), ("0", "250"), ("-1000.5", "1000.5"), ("0.1", "3.3"), ("-40", "125"), ("-1e+20", "1e+20"))
LITTLE, BIG = "little_endian", "big_endian"


# --- choosers ------------------------------------------------------------------------------


class Chooser:
    """A source of integer choices; `integer(lo, hi)` shrinks towards `lo`."""

    def integer(self, lo: int, hi: int) -> int:
        raise NotImplementedError

    def boolean(self, p: float) -> bool:
        """True with probability `p`; shrinks to False."""
        return self.integer(0, 999) >= round(1000 * (1 - p))

    def choice(self, seq: Sequence[Any]) -> Any:
        """An element of `seq`; shrinks to the first."""
        return seq[self.integer(0, len(seq) - 1)]


class RandomChooser(Chooser):
    def __init__(self, seed: int) -> None:
        self.rnd = random.Random(seed)
        self.choices: list[int] = []

    def integer(self, lo: int, hi: int) -> int:
        v = self.rnd.randint(lo, hi)
        self.choices.append(v - lo)
        return v


class ReplayChooser(Chooser):
    """Replays recorded offsets (value - lo); out of range → clamped, exhausted → lo."""

    def __init__(self, choices: Sequence[int]) -> None:
        self.source = list(choices)
        self.i = 0
        self.choices: list[int] = []

    def integer(self, lo: int, hi: int) -> int:
        off = self.source[self.i] if self.i < len(self.source) else 0
        self.i += 1
        v = lo + max(0, min(off, hi - lo))
        self.choices.append(v - lo)
        return v


class DrawChooser(Chooser):
    def __init__(self, draw: Any) -> None:
        self.draw, self.st = draw, st
        self.choices: list[int] = []

    def integer(self, lo: int, hi: int) -> int:
        v = self.draw(self.st.integers(lo, hi))
        self.choices.append(v - lo)
        return v


# --- the result ----------------------------------------------------------------------------


@dataclass
class GeneratedSpec:
    files: dict[str, str]  # relative path → YAML text
    entry: str  # what to pass to `canspec check|gen` (relative to the spec directory)
    features: frozenset[str]  # NEW_FEATURES this spec uses
    choices: list[int] = field(default_factory=list)
    seed: int | None = None
    facts: dict[str, Any] = field(default_factory=dict)  # summary: has_json, messages, ...

    def text(self) -> str:
        """Every file, for printing: `# file: NAME` before each."""
        return "".join(f"# file: {name}\n{body}" for name, body in self.files.items())

    def write(self, directory: Any) -> Any:
        """Write the files under `directory`; returns the path to give canspec."""
        from pathlib import Path

        d = Path(directory)
        d.mkdir(parents=True, exist_ok=True)
        for name, body in self.files.items():
            (d / name).write_text(body, encoding="utf-8")
        return d / self.entry


# --- YAML text -----------------------------------------------------------------------------


class Hex(int):
    """An integer written in hex."""


_PLAIN_OK = set("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_")
_YAML_SPECIAL = {"true", "false", "True", "False", "TRUE", "FALSE", "null", "Null", "NULL", "~", "y", "n", "yes", "no", "on", "off"}


def _scalar(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, Hex):
        return f"0x{int(v):X}"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, Decimal):
        return dec_text(v)
    if isinstance(v, str):
        if v and set(v) <= _PLAIN_OK and v[0].isalpha() and v not in _YAML_SPECIAL:
            return v
        return json.dumps(v, ensure_ascii=False)
    raise TypeError(f"no YAML form for {v!r}")


def dec_text(d: Decimal) -> str:
    """Decimal → YAML number text the spec loader reads back exactly (a '.' marks a decimal;
    exponents need a sign in YAML 1.1)."""
    if d == d.to_integral_value() and abs(d) < Decimal("1e15"):
        return str(int(d))
    if abs(d) >= Decimal("1e15"):
        sign, digits, exp = d.normalize().as_tuple()
        mant = format(Decimal((0, digits, -(len(digits) - 1))), "f")
        return f"{'-' if sign else ''}{mant if '.' in mant else mant + '.0'}e+{exp + len(digits) - 1}"
    if abs(d) < Decimal("0.0001"):
        sign, digits, exp = d.as_tuple()
        mant = Decimal((0, digits, -(len(digits) - 1)))
        e = exp + len(digits) - 1
        m = format(mant, "f")
        if "." not in m:
            m += ".0"
        return f"{'-' if sign else ''}{m}e{'+' if e >= 0 else '-'}{abs(e)}"
    return format(d.normalize(), "f")


def flow(v: Any) -> str:
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_scalar(k)}: {flow(x)}" for k, x in v.items()) + "}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(flow(x) for x in v) + "]"
    return _scalar(v)


def block(v: Any, indent: int = 0, flow_depth: int = 99) -> str:
    """Block-style YAML; mappings/lists deeper than `flow_depth` are written in flow style."""
    pad = " " * indent
    out = []
    if isinstance(v, dict):
        for k, x in v.items():
            key = _scalar(k)
            if isinstance(x, (dict, list)) and x and flow_depth > 0:
                out.append(f"{pad}{key}:\n{block(x, indent + 2, flow_depth - 1)}")
            else:
                out.append(f"{pad}{key}: {flow(x)}\n")
    elif isinstance(v, list):
        for x in v:
            if isinstance(x, dict) and x and flow_depth > 0:
                inner = block(x, indent + 2, flow_depth - 1)
                out.append(f"{pad}- {inner[indent + 2:]}")
            else:
                out.append(f"{pad}- {flow(x)}\n")
    return "".join(out)


# --- the builder ---------------------------------------------------------------------------


def raw_range(length: int, signed: bool) -> tuple[int, int]:
    return (-(1 << (length - 1)), (1 << (length - 1)) - 1) if signed else (0, (1 << length) - 1)


class _Names:
    """Unique names within one scope, compared by their word sequence (snake/pascal safe)."""

    def __init__(self, taken: Sequence[str] = ()) -> None:
        self.seen = {self.key(n) for n in taken}

    @staticmethod
    def key(name: str) -> str:
        return name.replace("_", "").lower()

    def free(self, name: str) -> bool:
        return self.key(name) not in self.seen

    def take(self, name: str) -> str:
        base, n = name, 2
        while not self.free(name):
            name = f"{base}_{n}"
            n += 1
        self.seen.add(self.key(name))
        return name


def occupied_all(occupied: set[int] | None) -> set[int]:
    return set(occupied or ())


def seq_bit(k: int, order: str) -> int:
    """The frame bit (DBC numbering, 8 × byte + bit) at place k of a field's run in this order: an
    Intel field's bits run upward from its LSB; a Motorola field's run from its MSB down to bit 0 of
    a byte, then on from bit 7 of the next, so place k is bit 7 - k % 8 of byte k // 8."""
    return k if order == LITTLE else 8 * (k // 8) + 7 - k % 8


def frame_bits(start: int, length: int, order: str) -> set[int]:
    """The frame bits of a field (`start` its LSB in Intel order, its MSB in Motorola order)."""
    first = seq_bit(start, order)  # seq_bit is its own inverse
    return {seq_bit(k, order) for k in range(first, first + length)}


class Builder:
    def __init__(self, ch: Chooser, features: frozenset[str]) -> None:
        self.ch = ch
        self.features = frozenset(features)
        self.used: set[str] = set()
        self.tables: dict[str, dict[int, tuple[str, str | None]]] = {}
        self.table_names = _Names()

    # small helpers
    def p(self, prob: float) -> bool:
        return self.ch.boolean(prob)

    def pick(self, seq: Sequence[Any]) -> Any:
        return self.ch.choice(seq)

    def feature(self, name: str, prob: float) -> bool:
        if name in self.features and self.p(prob):
            self.used.add(name)
            return True
        return False

    def ident(self, pool: Sequence[str], names: _Names, keyword_p: float = 0.08, compound: Sequence[str] = ()) -> str:
        if self.p(keyword_p):
            kw = self.pick(KEYWORDS)
            if names.free(kw):
                return names.take(kw)
        base = self.pick(pool)
        if compound and self.p(0.5):
            base = f"{base}_{self.pick(compound)}"
        return names.take(base)

    def text(self) -> str:
        return self.pick(TEXTS)

    def zh(self) -> str:
        return self.pick(ZH_WORDS) + ("" if not self.p(0.2) else self.pick(ZH_WORDS))

    # --- whole spec
    def build(self) -> GeneratedSpec:
        bundle = self.p(0.45)
        name = self.pick(PROTOCOL_NAMES) if not self.p(0.04) else self.pick(KEYWORDS)
        fmt = self.pick(("extended", "standard"))
        addressing = self.pick(("j1939", "none")) if fmt == "extended" else "none"
        bitrate = (
            self.pick((250000, 500000, 125000, 1000000, 10000, 20000, 50000, 100000, 800000, 83333)) if not self.p(0.2) else self.ch.integer(10000, 1000000)
        )
        self.order = BIG if self.p(0.3) else LITTLE  # the signals' default; each field may take the other
        self.bus = {"bitrate": bitrate, "id_format": fmt, "addressing": addressing, "byte_order": self.order}
        if self.p(0.3):  # a CAN FD bus: its data phase's bit rate (the FD frames' bit-rate switching)
            self.bus = {"bitrate": bitrate, "data_bitrate": self.pick(DATA_BITRATES), **{k: v for k, v in self.bus.items() if k != "bitrate"}}
        self.j1939 = addressing == "j1939"
        nodes = self.nodes()
        self.node_list = nodes
        messages, layouts = self.messages(nodes)
        version = f"{self.ch.integer(0, 3)}.{self.ch.integer(0, 9)}.{self.ch.integer(0, 12)}"
        if self.p(0.1):  # a table no signal uses
            self.new_table(0, self.pick((3, 15, 255)))
        can: dict[str, Any] = {"schema_version": 1, "kind": "can_protocol", "protocol": {"name": name, "version": version}}
        if self.p(0.3):
            can["protocol"]["title"] = self.text()
        if self.p(0.3):
            can["protocol"]["title_zh"] = self.zh()
        can["bus"] = self.bus
        can["nodes"] = nodes
        if layouts:
            can["layouts"] = layouts
        can["messages"] = messages
        tables = {
            t: {Hex(r) if r >= 0 and self.p(0.3) else r: (ident if zh is None else [ident, zh]) for r, (ident, zh) in entries.items()}
            for t, entries in self.tables.items()
        }
        files: dict[str, str] = {}
        facts: dict[str, Any] = {"bundle": bundle, "protocol": name, "messages": len(messages), "addressing": addressing, "id_format": fmt}
        separate_tables = bundle and tables and self.p(0.6)
        if tables and not separate_tables:
            can["value_tables"] = tables
        header = "# A spec drawn by tests/anyspec/strategy.py.\n"
        can_text = header + self.render_can(can)
        if not bundle:
            files["spec.yaml"] = can_text
            facts["has_json"] = False
            return GeneratedSpec(files, "spec.yaml", frozenset(self.used), facts=facts)
        listed = ["can.yaml"]
        files["can.yaml"] = can_text
        if separate_tables:
            files["value_tables.yaml"] = header + block({"schema_version": 1, "kind": "value_tables", "value_tables": tables}, 0, 1)
            listed.append("value_tables.yaml")
        has_json = self.p(0.6)
        if has_json:
            files["json.yaml"] = header + JsonBuilder(self, name).render()
            listed.append("json.yaml")
        if self.p(0.5):
            files["changelog.yaml"] = header + self.changelog(name, version, [m["id"] for m in messages])
            listed.append("changelog.yaml")
        bundle_doc: dict[str, Any] = {"schema_version": 1, "kind": "bundle"}
        if self.p(0.7):
            bundle_doc["name"] = name if self.p(0.5) else f"{name}_bundle"
        bundle_doc["files"] = listed
        files = {"canspec.yaml": header + block(bundle_doc), **files}
        facts["has_json"] = has_json
        return GeneratedSpec(files, "canspec.yaml", frozenset(self.used), facts=facts)

    def render_can(self, can: dict[str, Any]) -> str:
        out = block({k: can[k] for k in ("schema_version", "kind", "protocol", "bus")}, 0, 0)
        out += "nodes:\n" + "".join(f"  - {flow(n)}\n" for n in can["nodes"])
        if "value_tables" in can:
            out += "value_tables:\n" + block(can["value_tables"], 2, 0)
        if "layouts" in can:
            out += "layouts:\n"
            for lname, lay in can["layouts"].items():
                out += f"  {lname}:\n    signals:\n" + "".join(f"      - {flow(s)}\n" for s in lay["signals"])
        out += "messages:\n"
        for m in can["messages"]:
            first = True
            for k, v in m.items():
                lead = "  - " if first else "    "
                first = False
                if k in ("signals", "add") and v:
                    out += f"{lead}{k}:\n" + "".join(f"      - {flow(s)}\n" for s in v)
                elif k == "override" and v:
                    out += f"{lead}{k}:\n" + "".join(f"      {_scalar(t)}: {flow(p)}\n" for t, p in v.items())
                else:
                    out += f"{lead}{k}: {flow(v)}\n"
        return out

    # --- nodes
    def nodes(self) -> list[dict[str, Any]]:
        n = 1 + self.ch.integer(0, 4)
        names = _Names()
        sas: set[int] = set()
        out = []
        for _ in range(n):
            node: dict[str, Any] = {"name": self.ident(NODE_NAMES, names, 0.05)}
            if self.j1939 or not self.feature("optional_node_sa", 0.5):
                sa = self.ch.integer(0, 255)
                while sa in sas:
                    sa = (sa + 1) % 256
                sas.add(sa)
                node["sa"] = Hex(sa)
            if self.p(0.5):
                node["zh"] = self.zh()
            if self.p(0.15):
                node["desc"] = self.text()
            out.append(node)
        return out

    # --- messages
    def messages(self, nodes: list[dict[str, Any]]) -> tuple[list[dict[str, Any]], dict[str, Any]]:
        count = 1 + self.ch.integer(0, 2) + (self.ch.integer(0, 5) if self.p(0.3) else 0)
        self.msg_names = _Names()
        self.ids: set[int] = set()
        self.multiframes = 0
        out: list[dict[str, Any]] = []
        layouts: dict[str, Any] = {}
        if count >= 2 and self.p(0.25):
            lname, lay, dlc, users = self.layout()
            layouts[lname] = {"signals": lay}
            for _ in range(min(users, count)):
                out.append(self.message(nodes, layout=(lname, lay, dlc)))
        while len(out) < count:
            out.append(self.message(nodes))
        if len(out) > 1 and self.p(0.3):  # document order is not ID order
            k = self.ch.integer(1, len(out) - 1)
            out = out[k:] + out[:k]
        return out, layouts

    def frame_id(self, sender: dict[str, Any] | None, extended: bool) -> tuple[int, dict[str, Any] | None]:
        if not extended:
            fid = self.ch.integer(0, 0x7FF)
            while fid in self.ids:
                fid = (fid + 1) & 0x7FF
            self.ids.add(fid)
            return fid, None
        if not self.j1939:
            fid = self.ch.integer(0, 0x7FF) if self.p(0.1) else self.ch.integer(0, 0x1FFFFFFF)
            while fid in self.ids:
                fid = (fid + 1) & 0x1FFFFFFF
            self.ids.add(fid)
            return fid, None
        prio = self.pick((6, 3, 7, 0, 1, 2, 4, 5))
        edp = 1 if self.p(0.1) else 0
        dp = 1 if self.p(0.2) else 0
        pf = self.ch.integer(0, 255)
        ps = self.ch.integer(0, 255)
        sa = int(sender["sa"]) if sender is not None else self.ch.integer(0, 255)

        def compose() -> int:
            return (prio << 26) | (edp << 25) | (dp << 24) | (pf << 16) | (ps << 8) | sa

        while compose() in self.ids:
            ps = (ps + 1) % 256
            if ps == 0:
                pf = (pf + 1) % 256
        fid = compose()
        self.ids.add(fid)
        decl: dict[str, Any] = {"priority": prio}
        if edp or self.p(0.2):
            decl["edp"] = edp
        if dp or self.p(0.2):
            decl["dp"] = dp
        decl.update({"pf": Hex(pf), "ps": Hex(ps), "sa": Hex(sa)})
        return fid, decl

    def message(self, nodes: list[dict[str, Any]], layout: tuple[str, list[dict[str, Any]], int] | None = None) -> dict[str, Any]:
        m: dict[str, Any] = {"name": self.ident(MSG_WORDS, self.msg_names, 0.08, MSG_SUFFIX)}
        if self.p(0.1):  # a C-only name, reserved like a message name so it meets no other
            m["c_name"] = self.msg_names.take(f"{m['name']}_c")
        if self.p(0.3):
            m["title"] = self.text()
        if self.p(0.4):
            m["zh"] = self.zh()
        if self.p(0.15):
            m["desc"] = self.text()
        bus_ext = self.bus["id_format"] == "extended"
        extended = bus_ext
        if not self.j1939 and self.p(0.2):
            extended = self.p(0.5)
            m["extended"] = extended
        sender_all = self.p(0.05)
        sender = None if sender_all else nodes[self.ch.integer(0, len(nodes) - 1)]
        if self.j1939 and sender is not None and "sa" not in sender:
            sender = None
        fid, decl = self.frame_id(sender, extended)
        m["id"] = Hex(fid)
        if decl is not None and not self.feature("j1939_derived", 0.5):
            m["j1939"] = decl
        m["sender"] = "ALL" if sender is None else sender["name"]
        others = [n["name"] for n in nodes if sender is None or n["name"] != sender["name"]]
        if self.p(0.3):
            m["receivers"] = "ALL"
        elif not others or self.p(0.05):
            m["receivers"] = []
        else:
            m["receivers"] = others[: 1 + self.ch.integer(0, len(others) - 1)]
        if self.feature("event_driven", 0.2):
            if self.p(0.5):
                m["cycle_ms"] = 0
        else:
            m["cycle_ms"] = self.pick((20, 100, 10, 50, 1000, 1, 10000, 500)) if not self.p(0.2) else self.ch.integer(1, 10000)
        if layout is not None:
            return self.layout_user(m, *layout)
        fd = self.p(0.2)
        dlc = self.pick(FD_DLCS if fd else CLASSIC_DLCS)
        if dlc != 8 or self.p(0.2):
            m["dlc"] = dlc
        if fd:
            self.fd_frame(m)
        if dlc == 0 or self.p(0.03):
            if dlc > 0 or not self.feature("empty_signals", 0.6):
                m["layout_undefined"] = True
            m["signals"] = []
            return m
        mf = None
        if self.p(0.15):  # a multiplexed message (strategy_mux)
            from anyspec import strategy_mux

            sigs = strategy_mux.signals(self, dlc)
        elif 2 <= dlc <= 8 and self.multiframes < 2 and self.p(0.12):
            self.multiframes += 1
            sigs, mf = self.multiframe_signals(dlc)
        else:
            sigs = self.signals(dlc)
        if len(sigs) > 1 and self.p(0.2):
            k = self.ch.integer(1, len(sigs) - 1)
            sigs = sigs[k:] + sigs[:k]
        m["signals"] = sigs
        if mf is not None:
            m["multiframe"] = mf
        return m

    def fd_frame(self, m: dict[str, Any]) -> None:
        """`fd: true`, and `brs` where it is not the default (switching when the bus gives a data bit rate)."""
        m["fd"] = True
        if "data_bitrate" in self.bus:
            if self.p(0.3):
                m["brs"] = False
            elif self.p(0.1):
                m["brs"] = True
        elif self.p(0.2):
            m["brs"] = False

    # --- signals
    def field_order(self) -> str:
        """A field's byte order: mostly the bus default, else the other (both orders mixed in one frame)."""
        return (LITTLE if self.order == BIG else BIG) if self.p(0.25) else self.order

    def orient(self, s: dict[str, Any], order: str) -> None:
        """Write the field's `byte_order` where it differs from the bus default (now and then where it does not)."""
        if order != self.order or self.p(0.05):
            s["byte_order"] = order

    def signals(self, dlc: int, occupied: set[int] | None = None, names: _Names | None = None, counter: bool = True, checksum: bool = True,
                first_needed: bool = True) -> list[dict[str, Any]]:
        bits = 8 * dlc
        occ = set(occupied or ())
        names = names or _Names()
        out: list[dict[str, Any]] = []
        if checksum and dlc >= 2 and not set(range(bits - 8, bits)) & occ and self.p(0.25):
            out.append(self.checksum(dlc, names))
            occ |= set(range(bits - 8, bits))
        want_counter = counter and self.p(0.3)
        last = 0  # the previous field's length: rows of one width (wheel speeds, cell voltages), signed and unsigned mixed
        while (not out and first_needed) or self.p(0.8):
            order = self.field_order()
            # the field's first place (Intel: its LSB, Motorola: its MSB) and the free run from there, in its order's run of bits
            first = next((k for k in range(bits) if seq_bit(k, order) not in occ), None)
            if first is None:
                break
            run = 0
            while first + run < bits and seq_bit(first + run, order) not in occ:
                run += 1
            start = seq_bit(first, order)
            if self.p(0.2):  # a gap: free, or a reserved field
                gap = min(run, self.pick((1, 2, 3, 4, 8, 5, 7, 16)))
                if self.p(0.5):
                    out.append(self.reserved(start, gap, order))
                occ |= frame_bits(start, gap, order)
                continue
            if run >= 32 and self.p(0.2):  # an IEEE float
                length = 64 if run >= 64 and self.p(0.4) else 32
                out.append(self.float_field(start, length, names, order))
            else:
                length = min(run, last if last and self.p(0.3) else self.pick(LENGTHS))
                last = length
                if want_counter and length <= 8 and self.p(0.5):
                    want_counter = False
                    out.append(self.counter(start, length, names, order))
                else:
                    out.append(self.data(start, length, names, order=order))
            occ |= frame_bits(start, length, order)
        if first_needed and not out:  # every bit went to a free gap: one field after all
            start = min(b for b in range(bits) if b not in occupied_all(occupied))
            out.append(self.data(start, min(8, bits - start), names, order=LITTLE))
        return out

    def reserved(self, start: int, length: int, order: str) -> dict[str, Any]:
        s: dict[str, Any] = {"role": "reserved", "start": start, "len": length}
        self.orient(s, order)
        if self.p(0.2):
            s["desc_zh"] = "保留"
        return s

    def checksum(self, dlc: int, names: _Names) -> dict[str, Any]:
        s: dict[str, Any] = {"name": names.take("checksum" if self.p(0.8) else self.pick(("xor", "crc_byte", "check")))}
        self.sig_zh(s, "校验")
        order = self.field_order()
        s.update({"start": 8 * (dlc - 1) + (7 if order == BIG else 0), "len": 8})  # the last byte: its MSB is bit 7 in Motorola order
        self.orient(s, order)
        if self.p(0.5):
            s["range"] = [0, 255]
        s["role"] = "checksum"
        return s

    def counter(self, start: int, length: int, names: _Names, order: str) -> dict[str, Any]:
        s: dict[str, Any] = {"name": names.take("counter" if self.p(0.7) else self.pick(("alive", "rolling_counter", "heartbeat")))}
        self.sig_zh(s, "心跳")
        s.update({"start": start, "len": length})
        self.orient(s, order)
        if self.p(0.5):
            s["range"] = [0, (1 << length) - 1]
        s["role"] = "counter"
        return s

    def sig_zh(self, s: dict[str, Any], default: str | None = None) -> None:
        if not self.feature("optional_signal_zh", 0.3):
            s["zh"] = default if default and self.p(0.5) else self.zh()

    def scaling(self, length: int, signed: bool) -> dict[str, Any]:
        """factor / offset / range for a data field (range: None or reachable, within the field)."""
        out: dict[str, Any] = {}
        kind = self.pick(("identity", "integer", "decimal"))
        if kind == "integer":
            factor, offset = Decimal(self.pick(INT_FACTORS)), Decimal(self.pick(INT_OFFSETS))
        elif kind == "decimal":
            factor, offset = Decimal(self.pick(DEC_FACTORS)), Decimal(self.pick(DEC_OFFSETS))
        else:
            factor, offset = Decimal(1), Decimal(0)
        if factor != 1 or self.p(0.1):
            out["factor"] = factor
        if offset != 0 or self.p(0.1):
            out["offset"] = offset
        tmin, tmax = raw_range(length, signed)
        if self.p(0.6):
            lo_raw, hi_raw = tmin, tmax
            span = tmax - tmin
            if span >= 2 and self.p(0.5):
                lo_raw = tmin + self.ch.integer(0, min(span // 2, 1000))
                hi_raw = tmax - self.ch.integer(0, min(span // 2, 1000))
            a, b = sorted((lo_raw * factor + offset, hi_raw * factor + offset))
            if hi_raw - lo_raw >= 2 and self.p(0.1):  # bounds between two steps
                a, b = a + abs(factor) / 2, b - abs(factor) / 4
            out["range"] = [a, b]
            out["_raw"] = (lo_raw, hi_raw) if factor > 0 else (lo_raw, hi_raw)
        return out

    def data(self, start: int, length: int, names: _Names, name: str | None = None, order: str = LITTLE) -> dict[str, Any]:
        s: dict[str, Any] = {"name": names.take(name) if name else self.ident(SIG_WORDS, names, 0.1)}
        self.sig_zh(s)
        s.update({"start": start, "len": length})
        self.orient(s, order)
        signed = self.p(0.25)
        if signed:
            s["signed"] = True
        elif self.p(0.05):
            s["signed"] = False
        tmin, tmax = raw_range(length, signed)
        with_values = length <= 16 and self.p(0.25)
        sc = self.scaling(length, signed) if not with_values else {}
        if with_values:  # a value table on an identity field, its raws inside the range
            lo, hi = tmin, tmax
            if self.p(0.5):
                hi = min(tmax, max(lo, self.ch.integer(lo, min(tmax, lo + 15))))
                s["range"] = [lo, hi]
            s["values"] = self.table_for(lo, hi)
        raw_lo, raw_hi = sc.pop("_raw", (tmin, tmax))
        s.update(sc)
        if self.p(0.4):
            s["unit"] = self.pick(UNITS)
        if self.p(0.15):
            self.specials(s, tmin, tmax, raw_lo, raw_hi)
        if self.p(0.1):
            s["desc"] = self.text()
        if self.p(0.1):
            s["desc_zh"] = self.zh()
        return s

    def float_field(self, start: int, length: int, names: _Names, order: str) -> dict[str, Any]:
        """An IEEE 754 float32/float64 field: no scaling, sign flag or tables; a range or none (NaN, ±Inf pass)."""
        s: dict[str, Any] = {"name": self.ident(SIG_WORDS, names, 0.1)}
        self.sig_zh(s)
        s.update({"start": start, "len": length, "float": True})
        self.orient(s, order)
        if self.p(0.5):
            s["range"] = [Decimal(v) for v in self.pick(FLOAT_RANGES)]
        if self.p(0.4):
            s["unit"] = self.pick(UNITS)
        return s

    def specials(self, s: dict[str, Any], tmin: int, tmax: int, raw_lo: int, raw_hi: int) -> None:
        taken = set(self.tables[s["values"]]) if "values" in s else set()
        idents = _Names([ident for ident, _ in self.tables[s["values"]].values()] if "values" in s else ())
        candidates = [tmax, tmin, 0, raw_hi + 1 if raw_hi < tmax else tmax, raw_lo - 1 if raw_lo > tmin else tmin]
        special: dict[Any, Any] = {}
        for _ in range(1 + (1 if self.p(0.3) else 0)):
            raw = self.pick(candidates)
            if raw in taken or raw in special:
                continue
            ident = self.pick(SPECIAL_IDENTS) if not self.p(0.1) else self.pick(KEYWORDS)
            if not idents.free(ident):
                continue
            idents.take(ident)
            special[Hex(raw) if raw >= 0 and self.p(0.5) else raw] = [ident, self.zh()]
        if special:
            s["special"] = special

    # --- value tables
    def new_table(self, lo: int, hi: int) -> str:
        name = self.table_names.take(self.pick(TABLE_WORDS) if not self.p(0.08) else self.pick(KEYWORDS))
        k = 1 + self.ch.integer(0, min(4, hi - lo))
        base = 0 if lo <= 0 <= hi - k else lo
        raws: list[int] = []
        for i in range(k):
            r = base + i if self.p(0.7) else self.ch.integer(lo, hi)
            if r not in raws:
                raws.append(r)
        idents = _Names()
        entries: dict[int, tuple[str, str | None]] = {}
        for r in sorted(raws):
            ident = self.ident(VALUE_IDENTS, idents, 0.1)
            zh = None if self.feature("bare_value_ident", 0.3) else self.zh()
            entries[r] = (ident, zh)
        self.tables[name] = entries
        return name

    def table_for(self, lo: int, hi: int) -> str:
        fitting = [t for t, e in self.tables.items() if all(lo <= r <= hi for r in e)]
        if fitting and self.p(0.5):
            return self.pick(fitting)
        return self.new_table(lo, hi)

    # --- multiframe text
    def multiframe_signals(self, dlc: int) -> tuple[list[dict[str, Any]], dict[str, Any]]:
        names = _Names()
        index_len = self.pick((2, 8, 1, 3, 4))
        index: dict[str, Any] = {"name": names.take(self.pick(("frame_index", "index", "seq")))}
        self.sig_zh(index, "序号")
        index.update({"start": 0, "len": index_len})
        self.orient(index, LITTLE)  # whole bytes from bit 0 of a byte: Intel fields
        if self.p(0.5):
            index["range"] = [0, (1 << index_len) - 1]
        first_byte = (index_len + 7) // 8
        if first_byte >= dlc:
            first_byte = dlc - 1
        max_bytes = dlc - first_byte
        nbytes = 1 + self.ch.integer(0, max_bytes - 1)
        payload: dict[str, Any] = {"name": names.take(self.pick(("text_chars", "chars", "payload")))}
        self.sig_zh(payload, "字符")
        payload.update({"start": 8 * first_byte, "len": 8 * nbytes})
        self.orient(payload, LITTLE)
        frames = 1 + self.ch.integer(0, min((1 << index_len), 8) - 1)
        text_length = 1 + self.ch.integer(0, frames * nbytes - 1)
        mf = {"index": index["name"], "payload": payload["name"], "encoding": "ascii", "text_length": text_length, "frames": frames,
              "padding": Hex(self.pick((0x00, 0x20, 0xFF, 0x2A)))}
        occ = set(range(index_len)) | set(range(8 * first_byte, 8 * (first_byte + nbytes)))
        rest = self.signals(dlc, occ, names, counter=True, checksum=True, first_needed=False) if self.p(0.5) else []
        return [index, payload, *rest], mf

    # --- shared layouts
    def layout(self) -> tuple[str, list[dict[str, Any]], int, int]:
        name = self.pick(("command", "sensor_block", "status_block", "common"))
        dlc = self.pick((8, 4, 6, 2))
        sigs = self.signals(dlc)
        users = 2 + self.ch.integer(0, 1)
        return name, sigs, dlc, users

    def layout_user(self, m: dict[str, Any], lname: str, lay: list[dict[str, Any]], dlc: int) -> dict[str, Any]:
        if dlc != 8 or self.p(0.2):
            m["dlc"] = dlc
        m["layout"] = lname
        by_name = {s.get("name", f"reserved_{s['start']}"): s for s in lay}
        final_names = _Names(list(by_name))
        removed: list[str] = []
        if len(lay) > 1 and self.p(0.3):
            victim = self.pick(list(by_name))
            removed.append(victim)
        overrides: dict[str, Any] = {}
        for _ in range(self.ch.integer(0, 2)):
            target = self.pick(list(by_name))
            sig = by_name[target]
            if target in removed or target in overrides or sig.get("role") == "reserved":
                continue
            what = self.pick(("zh", "desc", "unit", "name", "scaling"))
            if what == "zh":
                overrides[target] = {"zh": self.zh()}
            elif what == "desc":
                overrides[target] = {"desc": self.text()}
            elif what == "unit" and sig.get("role", "data") == "data":
                overrides[target] = {"unit": self.pick(UNITS)}
            elif what == "name":
                new = self.ident(SIG_WORDS, final_names, 0.1)
                overrides[target] = {"name": new}
            elif what == "scaling" and sig.get("role", "data") == "data" and "values" not in sig and "special" not in sig and not sig.get("float"):
                sc = self.scaling(sig["len"], bool(sig.get("signed")))
                sc.pop("_raw", None)
                sc.setdefault("factor", Decimal(1))
                sc.setdefault("offset", Decimal(0))
                if "range" in sig and "range" not in sc:
                    lo, hi = raw_range(sig["len"], bool(sig.get("signed")))
                    a, b = sorted((lo * sc["factor"] + sc["offset"], hi * sc["factor"] + sc["offset"]))
                    sc["range"] = [a, b]
                overrides[target] = sc
        occ: set[int] = set()
        has_counter = has_checksum = False
        for s in lay:
            key = s.get("name", f"reserved_{s['start']}")
            if key in removed:
                continue
            occ |= frame_bits(s["start"], s["len"], s.get("byte_order", self.order))
            has_counter |= s.get("role") == "counter"
            has_checksum |= s.get("role") == "checksum"
        adds: list[dict[str, Any]] = []
        if self.p(0.4):
            names = _Names([*by_name, *(o["name"] for o in overrides.values() if "name" in o)])
            adds = self.signals(dlc, occ, names, counter=not has_counter, checksum=not has_checksum, first_needed=False)
        if overrides:
            m["override"] = overrides
        if removed:
            m["remove"] = removed
        if adds:
            m["add"] = adds
        return m

    # --- change record
    def changelog(self, protocol: str, version: str, ids: list[int]) -> str:
        major, minor, patch = (int(x) for x in version.split("."))
        versions = []
        older = []
        if patch > 0 and self.p(0.6):
            older.append(f"{major}.{minor}.{patch - 1}")
        if (minor > 0 or major > 0) and self.p(0.4):
            older.insert(0, f"{major}.{minor - 1}.0" if minor > 0 else f"{major - 1}.9.0")
        for v in [*older, version]:
            entry: dict[str, Any] = {"version": v}
            if self.p(0.5):
                entry["date"] = f"20{self.ch.integer(10, 29)}-0{self.ch.integer(1, 9)}-1{self.ch.integer(0, 9)}"
            if self.p(0.3):
                entry["authors"] = [self.zh()]
            items = []
            for _ in range(1 + self.ch.integer(0, 1)):
                item: dict[str, Any] = {"zh": self.zh()}
                if self.p(0.6):
                    item["en"] = self.text()
                if ids and self.p(0.3):
                    item["ids"] = [Hex(self.pick(ids))]
                items.append(item)
            entry["items"] = items
            versions.append(entry)
        doc = {"schema_version": 1, "kind": "changelog", "protocol": protocol, "versions": versions}
        return block(doc, 0, 2)


class JsonBuilder:
    """A JSON protocol that satisfies the documented dispatch model (canspec/jsonmodel.py):
    commands are told apart by `cmd` (a reply by `res`), other messages by a key only they have."""

    TYPES: dict[str, dict[str, Any]] = {
        "U8": {"json": "integer", "min": 0, "max": 255},
        "S8": {"json": "integer", "min": -128, "max": 127},
        "U16": {"json": "integer", "min": 0, "max": 65535},
        "S16": {"json": "integer", "min": -32768, "max": 32767},
        "U32": {"json": "integer", "min": 0, "max": 4294967295},
        "U64": {"json": "integer", "min": 0, "max": 9007199254740991},
        "Float32": {"json": "number", "min": Decimal("-3.4028234663852886e+38"), "max": Decimal("3.4028234663852886e+38")},
        "Float64": {"json": "number"},
        "BOOL": {"json": "boolean"},
        "ASCII": {"json": "string", "min_length": 1, "max_length": 1},
        "TEXT": {"json": "string", "min_length": 0, "max_length": 16},
    }

    def __init__(self, b: Builder, can_name: str) -> None:
        self.b = b
        self.can_name = can_name
        self.types_used: dict[str, dict[str, Any]] = {}

    def type(self, name: str) -> str:
        self.types_used[name] = self.TYPES[name]
        return name

    def render(self) -> str:
        b = self.b
        name = b.pick(JSON_PROTOCOL_NAMES)
        parties = [b.pick(PARTIES)]
        others = [p for p in PARTIES if p != parties[0]]
        parties.append(b.pick(others))
        if b.p(0.2):
            parties.append(b.pick([p for p in PARTIES if p not in parties]))
        shared: dict[str, Any] = {
            "ts": {"type": self.type("U64"), "unit": "ms", "zh": "时间戳"},
            "bn": {"type": self.type("U64"), "zh": "流水号"},
        }
        messages: list[dict[str, Any]] = []
        msg_names = _Names()
        markers = _Names(["ts", "bn", "cmd", "res"])
        plain = 1 + b.ch.integer(0, 2)
        for i in range(plain):
            frm, to = self.direction(parties)
            fields: list[Any] = []
            if b.p(0.6):
                fields.append("ts")
            if b.p(0.4):
                fields.append("bn")
            keys = _Names(["ts", "bn"])
            marker = self.field(markers, keys)
            fields.append(marker)
            for _ in range(b.ch.integer(0, 2)):
                fields.append(self.field(markers, keys))
            messages.append(self.message(msg_names, frm, to, fields, None))
        ncmd = b.ch.integer(0, 2)
        if ncmd:
            shared["cmd"] = {"type": self.type("U16"), "zh": "消息类型"}
            shared["res"] = {"type": self.type("S8"), "zh": "结果", "enum": {0: ["ok", "成功"], -1: ["failed", "失败"]}}
            if b.p(0.5):
                shared["reply_bn"] = {"name": "bn", "json_name": "bn", "type": "U64", "zh": "请求流水号"}
        for c in range(ncmd):
            cmd = c + 1 if b.p(0.7) else b.ch.integer(1, 65535)
            if any(m.get("cmd") == cmd for m in messages):
                cmd = max(m.get("cmd", 0) for m in messages) + 1
            frm, to = self.direction(parties)
            keys = _Names(["cmd", "bn", "res"])
            extra = [self.field(_Names(["ts", "bn", "cmd", "res"]), keys)] if b.p(0.4) else []
            req = self.message(msg_names, frm, to, ["cmd", "bn", *extra], cmd, "request")
            messages.append(req)
            if b.p(0.85):
                bn = "reply_bn" if "reply_bn" in shared else "bn"
                rextra = [self.field(_Names(["ts", "bn", "cmd", "res"]), _Names(["cmd", "bn", "res"]))] if b.p(0.3) else []
                rep = self.message(msg_names, to, frm, ["cmd", "res", bn, *rextra], cmd, "reply", req["name"])
                messages.append(rep)
        doc: dict[str, Any] = {"schema_version": 1, "kind": "json_protocol", "protocol": {"name": name, "version": f"1.{b.ch.integer(0, 3)}.0"}}
        doc["parties"] = [{"name": p, **({"zh": b.zh()} if b.p(0.5) else {})} for p in parties]
        doc["types"] = self.types_used
        doc["fields"] = shared
        doc["messages"] = messages
        out = block({k: doc[k] for k in ("schema_version", "kind", "protocol")}, 0, 0)
        out += "parties:\n" + "".join(f"  - {flow(p)}\n" for p in doc["parties"])
        out += "types:\n" + "".join(f"  {k}: {flow(v)}\n" for k, v in doc["types"].items())
        out += "fields:\n" + "".join(f"  {k}: {flow(v)}\n" for k, v in doc["fields"].items())
        out += "messages:\n"
        for m in messages:
            out += "  - " + "\n    ".join(f"{_scalar(k)}: {flow(v)}" for k, v in m.items()) + "\n"
        self.shared = shared
        return out

    def direction(self, parties: list[str]) -> tuple[str, str]:
        frm = self.b.pick(parties)
        to = self.b.pick([p for p in parties if p != frm])
        return frm, to

    def field(self, markers: _Names, keys: _Names) -> dict[str, Any]:
        """An inline field whose JSON key is new to the protocol (`markers`) and message (`keys`)."""
        b = self.b
        pool = JSON_FIELD_WORDS
        while True:
            base = b.pick(pool) if not b.p(0.1) else b.pick(KEYWORDS)
            key = markers.take(base)
            if keys.free(key):
                keys.take(key)
                break
        f: dict[str, Any] = {"name": key}
        kind = b.pick(("U8", "Float32", "BOOL", "S16", "ASCII", "Float64", "U64", "TEXT", "S8", "U32"))
        f["type"] = self.type(kind)
        t = self.TYPES[kind]
        f["zh"] = b.zh()
        if b.p(0.3):
            f["unit"] = b.pick(UNITS)
        if t["json"] == "integer":
            lo, hi = t["min"], t["max"]
            if b.p(0.25):
                n = 1 + b.ch.integer(0, 3)
                vals = sorted({lo + i if b.p(0.5) else max(lo, min(hi, i * 3 - 1)) for i in range(n)})
                idents = _Names()
                f["enum"] = {v: [b.ident(VALUE_IDENTS, idents, 0.1), b.zh()] for v in vals}
            elif b.p(0.5):
                rlo = max(lo, 0) + b.ch.integer(0, 10)
                rhi = rlo + b.ch.integer(0, 100)
                rhi = min(rhi, hi)
                f["range"] = [rlo, rhi]
                if lo < rlo and b.p(0.4):
                    f["sentinel"] = {rlo - 1: ["unknown", "未知"]}
        elif t["json"] == "number":
            if b.p(0.5):
                f["range"] = [Decimal(b.pick(("0", "-100", "-180", "-0.5"))), Decimal(b.pick(("100", "180", "0.5", "1000")))]
            if b.p(0.4):
                f["decimals"] = b.ch.integer(0, 6)
        elif t["json"] == "string" and kind == "ASCII" and b.p(0.5):
            letters = sorted({b.pick("NDRP-xyz") for _ in range(1 + b.ch.integer(0, 3))})
            idents = _Names()
            f["enum"] = {c: [b.ident(VALUE_IDENTS, idents, 0.1), b.zh()] for c in letters}
        if b.p(0.2):
            f["desc"] = b.text()
        if b.p(0.15) and key[0].islower():
            f["json_name"] = key
            f["name"] = key + "_value" if b.p(0.5) else key
        return f

    def message(self, names: _Names, frm: str, to: str, fields: list[Any], cmd: int | None, role: str | None = None,
                reply_to: str | None = None) -> dict[str, Any]:
        b = self.b
        m: dict[str, Any] = {"name": b.ident(("control", "status", "report", "ping", "query", "notice"), names, 0.05, ("request", "reply", "msg"))}
        if cmd is not None:
            m["cmd"] = cmd
            m["role"] = role
            if reply_to:
                m["reply_to"] = reply_to
        m["zh"] = b.zh()
        if b.p(0.3):
            m["desc"] = b.text()
        m["from"], m["to"] = frm, to
        m["fields"] = fields
        if b.p(0.7):
            m["examples"] = [self.example(fields, cmd) for _ in range(1 + b.ch.integer(0, 1))]
        return m

    def example(self, fields: list[Any], cmd: int | None) -> dict[str, Any]:
        shared = {
            "ts": {"type": "U64"}, "bn": {"type": "U64"}, "cmd": {"type": "U16"},
            "res": {"type": "S8", "enum": {0: 1, -1: 1}}, "reply_bn": {"type": "U64", "json_name": "bn"},
        }
        out: dict[str, Any] = {}
        for ref in fields:
            f = shared[ref] if isinstance(ref, str) else ref
            key = f.get("json_name", ref if isinstance(ref, str) else ref["name"])
            out[key] = cmd if key == "cmd" else self.value(f)
        return out

    def value(self, f: dict[str, Any]) -> Any:
        b = self.b
        t = self.TYPES[f["type"]]
        if "enum" in f:
            return b.pick(list(f["enum"]))
        if "sentinel" in f and b.p(0.3):
            return b.pick(list(f["sentinel"]))
        if t["json"] == "boolean":
            return b.p(0.5)
        if t["json"] == "string":
            return "x" * b.ch.integer(t["min_length"], min(t["max_length"], 4))
        if "range" in f:
            lo, hi = f["range"]
        else:
            lo, hi = max(t.get("min", -1000), -1000), min(t.get("max", 1000), 1000)
        if t["json"] == "integer":
            return b.ch.integer(int(lo), int(min(hi, lo + 1000)))
        v = Decimal(lo) + Decimal(b.ch.integer(0, 1000)) / 100
        return min(v, Decimal(hi))


# --- entry points --------------------------------------------------------------------------


def build(ch: Chooser, features: frozenset[str] = ALL) -> GeneratedSpec:
    spec = Builder(ch, features).build()
    spec.choices = list(getattr(ch, "choices", []))
    return spec


def example(seed: int, features: frozenset[str] = ALL) -> GeneratedSpec:
    """The spec of `seed` (deterministic: the same seed gives the same spec, byte for byte)."""
    spec = build(RandomChooser(seed), features)
    spec.seed = seed
    return spec


def replay(choices: Sequence[int], features: frozenset[str] = ALL) -> GeneratedSpec:
    return build(ReplayChooser(choices), features)


@st.composite
def specs(draw: Any, features: frozenset[str] = ALL) -> GeneratedSpec:
    """The Hypothesis strategy (`@given(strategy.specs())`, or `strategy.specs(CURRENT)`)."""
    return build(DrawChooser(draw), features)


def parse_features(text: str | None) -> frozenset[str]:
    """`all` (default), `current` (none of the relaxations), or a comma list of NEW_FEATURES."""
    if text in (None, "", "all", "new"):
        return ALL
    if text in ("current", "none"):
        return CURRENT
    wanted = frozenset(x.strip() for x in text.split(",") if x.strip())
    unknown = wanted - ALL
    if unknown:
        raise ValueError(f"unknown feature(s) {', '.join(sorted(unknown))}; known: {', '.join(sorted(ALL))}, or all / current")
    return wanted
