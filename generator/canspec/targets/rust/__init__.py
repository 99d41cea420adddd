"""Rust bindings: a `no_std` Cargo crate named after the CAN protocol (`rust/`).

The spec-independent modules (`codec`, `fd`, `ieee`, `j1939`, `monitor`) are real Rust files under
templates/rust/static/, copied with the generated header; the constants they read come from
the IR in the generated `constants` module. Every `.rs` file is formatted by rustfmt in memory
(a large one in chunks, render/formatters.py), so the committed files are exactly what `make gen` writes. The view model is `model.py`.
"""

from __future__ import annotations

from canspec import ir
from canspec.render.environment import render, static_file
from canspec.render.formatters import RUSTFMT_CHUNK_CHARS, in_chunks, rustfmt
from canspec.targets import Target
from canspec.targets.rust.check import problems
from canspec.targets.rust.model import RustCrate, build_crate
from canspec.targets.rust.monitor import build_supervision
from canspec.targets.rust.tests_view import build_tests

TARGET_NAME = "rust"
TEMPLATES = {
    "Cargo.toml": "rust/Cargo.toml.j2",
    "src/lib.rs": "rust/lib.rs.j2",
    "src/constants.rs": "rust/constants.rs.j2",
    "src/messages.rs": "rust/messages.rs.j2",
    "src/values.rs": "rust/values.rs.j2",
    "src/supervision.rs": "rust/supervision.rs.j2",
    "tests/sequences.rs": "rust/tests/sequences.rs.j2",
    "tests/monitor.rs": "rust/tests/monitor.rs.j2",
    "tests/vectors.rs": "rust/tests/vectors.rs.j2",
    "tests/properties.rs": "rust/tests/properties.rs.j2",
}
STATIC = ("src/codec.rs", "src/fd.rs", "src/ieee.rs", "src/j1939.rs", "src/monitor.rs")


def _wanted(rel: str, crate: RustCrate) -> bool:
    """Modules only where the protocol uses them: J1939 helpers on J1939 buses, enums for tables,
    FD frames and IEEE fields."""
    wanted = {"src/j1939.rs": crate.is_j1939, "src/fd.rs": crate.has_fd_frames, "src/ieee.rs": "ieee" in crate.kinds,
              "src/values.rs": bool(crate.enums), "src/messages.rs": bool(crate.messages)}
    return wanted.get(rel, True)


def render_rust(spec: ir.Spec) -> dict[str, bytes]:
    if spec.can is None:
        return {}
    crate = build_crate(spec.can)
    tests = build_tests(crate)
    sup = build_supervision(spec.can, crate)
    sources = {
        rel: render(template, spec, TARGET_NAME, can=spec.can, crate=crate, tests=tests, sup=sup) for rel, template in TEMPLATES.items() if _wanted(rel, crate)
    }
    sources.update({rel: static_file(spec, TARGET_NAME, f"rust/static/{rel}") for rel in STATIC if _wanted(rel, crate)})
    return {f"rust/{rel}": (_format(text, rel) if rel.endswith(".rs") else text).encode("utf-8") for rel, text in sorted(sources.items())}


def _format(text: str, rel: str, size: int = RUSTFMT_CHUNK_CHARS) -> str:
    return in_chunks(text, lambda piece: rustfmt(piece, rel), size)


TARGET = Target("rust", "Rust crate (no_std, serde optional)", "rust/", render_rust, order=40, cost=8, check=problems, formatters=("rustfmt",))
