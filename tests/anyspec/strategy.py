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

The parts: `pools.py` (the relaxations, name and number pools, bit helpers), `choosers.py` (the
three choice streams), `strategy_fields.py` (a message's fields), `strategy_mux.py` (its pages),
`strategy_json.py` (the JSON protocol), `yamltext.py` (the YAML text); this module builds the spec.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from hypothesis import strategies as st

from anyspec.choosers import Chooser, DrawChooser, RandomChooser, ReplayChooser
from anyspec.pools import (
    ALL,
    BIG,
    CURRENT,
    DATA_BITRATES,
    KEYWORDS,
    LITTLE,
    NODE_NAMES,
    PROTOCOL_NAMES,
    TEXTS,
    ZH_WORDS,
    _Names,
)
from anyspec.strategy_fields import FieldDraws
from anyspec.strategy_json import JsonBuilder
from anyspec.strategy_layouts import LayoutDraws
from anyspec.strategy_messages import MessageDraws
from anyspec.yamltext import Hex, _scalar, block, flow

# --- the result ----------------------------------------------------------------------------


HEADER = "# A spec drawn by tests/anyspec/strategy.py.\n"


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


# --- the builder ---------------------------------------------------------------------------


class Builder(FieldDraws, LayoutDraws, MessageDraws):
    """One spec from one chooser: nodes, messages, layouts, the JSON protocol and the changelog (the fields
    of each message: strategy_fields.FieldDraws)."""

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
        fmt, addressing = self.draw_bus()
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
        facts: dict[str, Any] = {"bundle": bundle, "protocol": name, "messages": len(messages), "addressing": addressing, "id_format": fmt}
        separate_tables = bundle and tables and self.p(0.6)
        if tables and not separate_tables:
            can["value_tables"] = tables
        can_text = HEADER + self.render_can(can)
        if not bundle:
            facts["has_json"] = False
            return GeneratedSpec({"spec.yaml": can_text}, "spec.yaml", frozenset(self.used), facts=facts)
        return self.bundle(name, version, can_text, tables if separate_tables else {}, [m["id"] for m in messages], facts)

    def draw_bus(self) -> tuple[str, str]:
        """The bus (`self.bus`, its default byte order `self.order`): (id format, addressing)."""
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
        return fmt, addressing

    def bundle(self, name: str, version: str, can_text: str, tables: dict[str, Any], ids: list[int], facts: dict[str, Any]) -> GeneratedSpec:
        """A bundle of the CAN file, the value tables apart when `tables`, and maybe a JSON protocol and a changelog."""
        listed = ["can.yaml"]
        files = {"can.yaml": can_text}
        if tables:
            files["value_tables.yaml"] = HEADER + block({"schema_version": 1, "kind": "value_tables", "value_tables": tables}, 0, 1)
            listed.append("value_tables.yaml")
        has_json = self.p(0.6)
        if has_json:
            files["json.yaml"] = HEADER + JsonBuilder(self, name).render()
            listed.append("json.yaml")
        if self.p(0.5):
            files["changelog.yaml"] = HEADER + self.changelog(name, version, ids)
            listed.append("changelog.yaml")
        bundle_doc: dict[str, Any] = {"schema_version": 1, "kind": "bundle"}
        if self.p(0.7):
            bundle_doc["name"] = name if self.p(0.5) else f"{name}_bundle"
        bundle_doc["files"] = listed
        facts["has_json"] = has_json
        return GeneratedSpec({"canspec.yaml": HEADER + block(bundle_doc), **files}, "canspec.yaml", frozenset(self.used), facts=facts)

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
