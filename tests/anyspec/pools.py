"""What the anyspec strategy draws from (strategy.py): the spec-format relaxations, the name and number
pools, and the bit helpers every part of the builder shares."""

from __future__ import annotations

from collections.abc import Sequence

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
