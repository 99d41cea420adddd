"""The Rust crate of every valid fixture (tests/fixtures/valid/*.yaml with a CAN protocol, and the
multiplexed specs of tests/targets/rust/specs/), held
to the toolchain's strict checks: clippy with warnings denied on every target, a no_std build,
rustdoc with warnings denied, and the crate's own tests — its vector test on that fixture's
vectors and its property tests. One cargo workspace, one target directory, offline (the
dependencies are the shipped crate's: .ci/setup.d/40-rust.sh fetches them)."""

from __future__ import annotations

import os
import re
import subprocess
from pathlib import Path

import pytest
from canspec.pipeline import compile_spec
from canspec.targets import registry
from repo_paths import ROOT
from rust_workspace import add_member, write_workspace

FIXTURES = ROOT / "tests" / "fixtures" / "valid"
RUST_SPECS = ROOT / "tests" / "targets" / "rust" / "specs"  # the Rust target's own multiplexing specs
TARGET_DIR = ROOT / "build" / "rust" / "target"
VECTORS_LINE = re.compile(r"rust vectors: (\d+) cases \+ (\d+) multi-frame texts from (\S+), (\d+) mismatches")


def _crate(path: Path, root: Path) -> str | None:
    """Generate the fixture's crate and vectors under `root/<stem>/`; the member path, or None
    for a fixture without a CAN protocol."""
    compiled = compile_spec(path, ["rust", "vectors"])
    assert compiled.spec is not None, "\n".join(p.format() for p in compiled.problems)
    files = {**registry()["rust"].render(compiled.spec), **registry()["vectors"].render(compiled.spec)}
    return add_member(files, root, path.stem, "fixture") if files else None


@pytest.fixture(scope="module")
def workspace(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, list[str]]:
    root = tmp_path_factory.mktemp("rust_fixtures")
    specs = sorted(FIXTURES.glob("*.yaml")) + sorted(RUST_SPECS.glob("*.yaml"))
    members = [m for p in specs if (m := _crate(p, root)) is not None]
    write_workspace(root, members)
    return root, members


def cargo(root: Path, *args: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    full_env = {**os.environ, "CARGO_TARGET_DIR": str(TARGET_DIR), "CARGO_TERM_COLOR": "never", **(env or {})}
    full_env.pop("RUSTFLAGS", None)
    proc = subprocess.run(["cargo", *args], cwd=root, env=full_env, capture_output=True, text=True, check=False)
    assert proc.returncode == 0, f"cargo {' '.join(args)} failed ({proc.returncode}):\n{proc.stdout[-6000:]}\n{proc.stderr[-8000:]}"
    return proc


def test_the_fixtures_give_crates(workspace):
    _, members = workspace
    assert len(members) >= 5, members  # the fixtures below tests/fixtures/valid with a CAN protocol


def test_clippy_denies_nothing(workspace):
    root, _ = workspace
    cargo(root, "clippy", "--offline", "--workspace", "--all-targets", "--all-features", "--", "-D", "warnings")
    cargo(root, "clippy", "--offline", "--workspace", "--all-targets", "--no-default-features", "--", "-D", "warnings")


def _doc_groups(root: Path, members: list[str]) -> list[list[str]]:
    """Package names in as few groups as keep library names apart (rustdoc writes one folder per library)."""
    groups: list[dict[str, str]] = []
    for member in members:
        lib = re.search(r'^\[lib\]\nname = "([^"]+)"', (root / member / "Cargo.toml").read_text(encoding="utf-8"), re.MULTILINE)
        assert lib, member
        group = next((g for g in groups if lib.group(1) not in g), None)
        if group is None:
            groups.append(group := {})
        group[lib.group(1)] = f"fixture-{member.split('/')[0].replace('_', '-')}"
    return [sorted(g.values()) for g in groups]


def test_no_std_and_docs_build(workspace):
    root, members = workspace
    cargo(root, "check", "--offline", "--workspace", "--no-default-features", "--lib")
    for packages in _doc_groups(root, members):
        selected = [arg for p in packages for arg in ("-p", p)]
        cargo(root, "doc", "--offline", *selected, "--no-deps", "--all-features", env={"RUSTDOCFLAGS": "-D warnings"})


def test_each_crate_passes_its_own_tests(workspace):
    root, members = workspace
    proc = cargo(root, "test", "--offline", "--workspace", "--all-features", "--", "--nocapture",
                 env={"CANSPEC_PROPTEST_CASES": "256", "CANSPEC_FUZZ_CASES": "20000"})
    runs = {Path(os.path.normpath(m.group(3))).parent.parent.name: (int(m.group(1)), int(m.group(4))) for m in VECTORS_LINE.finditer(proc.stdout)}
    assert sorted(runs) == sorted(m.split("/")[0] for m in members), proc.stdout[-3000:]
    assert all(mismatches == 0 for _, mismatches in runs.values()), runs
    assert "test result: FAILED" not in proc.stdout
