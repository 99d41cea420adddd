"""Rust bindings: a `no_std` Cargo crate named after the CAN protocol (`rust/`).

Every `.rs` file is formatted by rustfmt in memory, so the committed files are exactly what
`make gen` writes. The view model (names, literals, bit expressions) is `canspec.rust_model`.
"""

from __future__ import annotations

from canspec import ir
from canspec.ir import j1939
from canspec.render.environment import render
from canspec.render.formatters import rustfmt
from canspec.targets import Target
from canspec.targets.rust.model import build_crate

SOURCES = {
    "Cargo.toml": "rust/Cargo.toml.j2",
    "src/lib.rs": "rust/lib.rs.j2",
    "src/codec.rs": "rust/codec.rs.j2",
    "src/j1939.rs": "rust/j1939.rs.j2",
    "src/values.rs": "rust/values.rs.j2",
    "src/messages.rs": "rust/messages.rs.j2",
    "tests/vectors.rs": "rust/tests/vectors.rs.j2",
    "tests/properties.rs": "rust/tests/properties.rs.j2",
}
def render_rust(spec: ir.Spec) -> dict[str, bytes]:
    if spec.can is None:
        return {}
    crate = build_crate(spec.can)
    out = {}
    for rel, template in SOURCES.items():
        text = render(template, spec, "rust", can=spec.can, crate=crate, tie_epsilon=ir.TIE_EPSILON_TEXT, pdu2_min_pf=j1939.PDU2_MIN_PF)
        if rel.endswith(".rs"):
            text = rustfmt(text, rel)
        out[f"rust/{rel}"] = text.encode("utf-8")
    return out


TARGET = Target("rust", "Rust crate (no_std, serde optional)", "rust/", render_rust, order=40, cost=8)
