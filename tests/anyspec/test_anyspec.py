"""The "any valid spec" property: for specs drawn by tests/anyspec/strategy.py, `canspec check`
accepts them, `canspec gen` succeeds, and every output passes its own toolchain's strict
checks and its own vectors (C with gcc/clang as C99 and C++, Python with ruff/mypy, cantools and
canmatrix on the DBC, Rust with clippy and cargo test, JSON Schemas with jsonschema and ajv,
TypeScript with tsc --strict). See tests/anyspec/README.md.

Environment: ANYSPEC_N (specs, default 100), ANYSPEC_SEED (first seed, default 20261201),
ANYSPEC_FEATURES (all | current | a comma list, default all), ANYSPEC_RUST (crates, default 12).
"""

from __future__ import annotations

import math
import os
import subprocess
import sys

import pytest
import yaml
from hypothesis import given, settings

from anyspec import fixture, harness, shrink, strategy
from anyspec.pools import frame_bits

N = int(os.environ.get("ANYSPEC_N", "100"))
SEED = int(os.environ.get("ANYSPEC_SEED", "20261201"))
FEATURES = strategy.parse_features(os.environ.get("ANYSPEC_FEATURES", "all"))
RUST = int(os.environ.get("ANYSPEC_RUST", "12"))
MIN_RUST, MIN_JSON = min(10, RUST), 10


# --- the strategy itself (fast) --------------------------------------------------------------


def test_example_is_deterministic_and_replayable():
    for seed in (0, 1, 12345):
        a, b = strategy.example(seed), strategy.example(seed)
        assert a.text() == b.text() and a.features == b.features
        assert strategy.replay(a.choices).text() == a.text()
    assert strategy.example(1).text() != strategy.example(2).text()


@settings(max_examples=40, deadline=None)
@given(strategy.specs())
def test_drawn_specs_are_well_formed_yaml(spec):
    docs = {name: yaml.safe_load(text) for name, text in spec.files.items()}
    assert spec.entry in docs
    kinds = sorted(d["kind"] for d in docs.values())
    assert "can_protocol" in kinds and all(d["schema_version"] == 1 for d in docs.values())
    assert spec.features <= strategy.ALL


@settings(max_examples=20, deadline=None)
@given(strategy.specs(strategy.CURRENT))
def test_current_format_specs_use_no_relaxation(spec):
    assert spec.features == frozenset()


def test_the_batch_draws_rows_of_one_width_of_both_signs():
    """The default batch holds a frame with two unsigned fields and a signed one of one bit count
    (not a whole byte count): strategy 3's range check ORs the unsigned ones into one local, which
    once took the signed field's type (issue 24, fixture ored_mixed_signedness)."""
    def mixed(signals: list[dict]) -> bool:  # type: ignore[type-arg]
        widths: dict[int, list[bool]] = {}
        for s in signals:
            if s.get("role") not in ("reserved", "checksum") and s["len"] not in (8, 16, 32, 64):
                widths.setdefault(s["len"], []).append(bool(s.get("signed")))
        return any(signs.count(False) >= 2 and True in signs for signs in widths.values())

    docs = (yaml.safe_load(text) for seed in range(SEED, SEED + 100) for text in strategy.example(seed, FEATURES).files.values())
    assert any(mixed(m.get("signals") or []) for d in docs if d.get("kind") == "can_protocol" for m in d["messages"])


def test_the_batch_draws_every_dimension_of_issue_24():
    """The default batch holds Motorola fields crossing bytes next to Intel ones in one frame (under
    either bus default), Motorola counters and checksums, CAN FD frames of every FD length with and
    without bit-rate switching, and float32/float64 fields in both orders with and without a range."""
    seen: set[tuple[object, ...]] = set()
    for seed in range(SEED, SEED + 100):
        for text in strategy.example(seed, FEATURES).files.values():
            doc = yaml.safe_load(text)
            if doc.get("kind") != "can_protocol":
                continue
            default = doc["bus"]["byte_order"]
            seen |= {("bus", default), ("data_bitrate", "data_bitrate" in doc["bus"])}
            for m in doc["messages"]:
                sigs = [s for s in m.get("signals") or m.get("add") or [] if "len" in s]
                orders = {s.get("byte_order", default) for s in sigs}
                seen.add(("mixed", default, len(orders) == 2))
                if m.get("fd"):
                    seen |= {("fd", m.get("dlc", 8)), ("brs", m.get("brs", "data_bitrate" in doc["bus"]))}
                for s in sigs:
                    order = s.get("byte_order", default)
                    crosses = len({b // 8 for b in frame_bits(s["start"], s["len"], order)}) > 1
                    seen.add((s.get("role", "data"), order, crosses))
                    if s.get("float"):
                        seen.add(("float", s["len"], order, "range" in s))
                mux_dimensions(sigs, seen)
    want = {("bus", "little_endian"), ("bus", "big_endian"), ("data_bitrate", True), ("mixed", "little_endian", True), ("mixed", "big_endian", True),
            ("data", "big_endian", True), ("counter", "big_endian", False), ("checksum", "big_endian", False), ("brs", True), ("brs", False),
            *(("fd", n) for n in (8, 12, 16, 20, 24, 32, 48, 64)),
            *(("float", n, o, r) for n in (32, 64) for o in ("little_endian", "big_endian") for r in (True, False)),
            ("mux", "single"), ("mux", "range"), ("mux", "overlap"), ("mux", "nested"), ("mux", "fd"), ("mux", "float")}
    assert not want - seen, sorted(want - seen, key=str)


def mux_dimensions(sigs: list[dict], seen: set[tuple[object, ...]]) -> None:  # type: ignore[type-arg]
    """A multiplexed message's pages: selected by single values and ranges, fields of different
    pages sharing bits, a multiplexer that is itself multiplexed, in FD frames, float fields."""
    muxed = [s for s in sigs if "mux" in s]
    if not muxed:
        return
    for s in muxed:
        seen |= {("mux", "range" if isinstance(v, list) else "single") for v in s["mux"]["values"]}
        seen |= {("mux", "float")} if s.get("float") else set()
    seen |= {("mux", "nested")} if {s["mux"]["by"] for s in muxed} & {s["name"] for s in muxed} else set()
    seen |= {("mux", "fd")} if max(s["start"] + s["len"] for s in sigs) > 64 else set()
    bits = [(s, frame_bits(s["start"], s["len"], s.get("byte_order", "little_endian"))) for s in muxed]
    if any(a["mux"] != b["mux"] and x & y for a, x in bits for b, y in bits):
        seen.add(("mux", "overlap"))


@settings(max_examples=200, deadline=None)
@given(drawn=strategy.specs())
def test_every_decoded_raw_end_encodes_back(drawn, tmp_path_factory):
    """Decode then encode gives the same raw value at every field's raw ends and their neighbours
    (issue 24), for every width, factor and offset: the double a decoder returns (raw × factor +
    offset, each step in doubles, as C, Python and Rust compute it) encodes back to that raw in the
    reference codec (exact decimal arithmetic on the double's shortest repr) and in the runtime
    rule every language implements (ir/encoding.py: the rounding lands in the field, then the
    accepted range). Where the quotient reaches 2^51 (fields of 52+ bits, or an offset that dwarfs
    the factor) doubles no longer tell neighbouring raws apart: there the encode may give a raw
    one double step away, never one further. The languages check the same through the vectors'
    `decoded` cases (vectors._decoded)."""
    assert_decoded_ends_encode_back(drawn.write(tmp_path_factory.mktemp("spec")))


def test_the_batch_decoded_raw_ends_encode_back(tmp_path):
    """The same over the batch's specs (their fields reach the rare cases Hypothesis's small specs
    miss: a 1-bit field ×0.001 +1000000 decodes raw 1 to 1000000.001, whose double quotient
    1.0000000000582077 the old window, q within 1e-9 of the field, refused)."""
    for seed in range(SEED, SEED + 200):
        assert_decoded_ends_encode_back(strategy.example(seed, FEATURES).write(tmp_path / str(seed)))
    for path in sorted((harness.ROOT / "tests" / "fixtures" / "valid").glob("*.yaml")):  # and every valid fixture
        assert_decoded_ends_encode_back(path)


def assert_decoded_ends_encode_back(path) -> None:  # type: ignore[no-untyped-def]
    from canspec.ir.encoding import fits_runtime, to_raw_runtime
    from canspec.pipeline import compile_spec
    from canspec.reference import codec

    compiled = compile_spec(path, targets=())
    assert compiled.spec is not None, compiled.problems
    for msg in compiled.spec.can.messages if compiled.spec.can is not None else ():  # a JSON-only fixture has none
        for sig in (s for s in msg.data_signals if not s.is_identity and not s.is_float):  # a float field: its own cases (vectors)
            f, o = float(sig.factor), float(sig.offset)
            for raw in (r for r in {sig.raw_min, sig.raw_min + 1, sig.raw_max - 1, sig.raw_max} if sig.raw_min <= r <= sig.raw_max):
                x = float(raw) * f + o
                where = f"{msg.name}.{sig.name} ({sig.length} bits, ×{sig.factor} +{sig.offset}): raw {raw} decodes to {x!r}"
                if (abs(x) + abs(o)) / abs(f) >= 2**51:
                    q = (x - o) / f
                    assert not fits_runtime(q, sig.raw_type_min, sig.raw_type_max) or abs(to_raw_runtime(x, f, o) - raw) <= 2 * math.ulp(q), where
                    continue
                assert codec.to_raw(sig, x) == raw, where
                assert fits_runtime((x - o) / f, sig.raw_type_min, sig.raw_type_max) and to_raw_runtime(x, f, o) == raw, where
                special = any(sp.raw == raw for sp in sig.specials)
                assert special or float(sig.accept_min) <= x <= float(sig.accept_max), where  # as the targets compare


def test_shrinker_reaches_a_minimal_spec():
    """A failure that needs two messages shrinks to a spec of exactly two small messages."""
    seed = next(s for s in range(100) if strategy.example(s).facts["messages"] >= 4)
    big = strategy.example(seed)
    small, _ = shrink.Shrinker(strategy.ALL, lambda s: s.facts["messages"] >= 2 or None, budget_s=60, log=lambda _: None).run(big.choices)
    assert small is not None and small.facts["messages"] == 2
    assert len(small.text()) < len(big.text()) / 2


def test_fixture_tool_writes_a_checked_valid_fixture(tmp_path):
    spec = next(strategy.example(s, strategy.CURRENT) for s in range(100) if not strategy.example(s, strategy.CURRENT).facts["bundle"])
    src = spec.write(tmp_path / "spec")
    dest = fixture.write_fixture(src, "anyspec_probe", "probe", tmp_path)
    assert dest.read_text(encoding="utf-8").splitlines()[1] == "# expect: ok"
    rc, out, err = harness.canspec("check", str(dest))
    assert rc == 0, err


def test_refusals_are_classified_by_relaxation():
    text = ("a.yaml:3:5: error: message 'm' does not declare its J1939 fields [j1939-missing]\n"
            "a.yaml:9:9: error: messages.0.signals.1: 'zh' is required [schema]\n"
            "a.yaml:9:9: error: something else [other-rule]\n")
    features, unexplained = harness.classify_refusal(text)
    assert features == ["j1939_derived", "optional_signal_zh"] and unexplained == ["a.yaml:9:9: error: something else [other-rule]"]


# --- the property over a batch of specs ------------------------------------------------------


@pytest.fixture(scope="module")
def batch() -> harness.Batch:
    missing = harness.missing_tools()
    if missing:
        pytest.fail("anyspec needs these toolchains (run `make setup`): " + "; ".join(missing))
    return harness.run_batch(N, SEED, FEATURES, rust=RUST, mypy_every=10, log=lambda line: print(line, file=sys.stderr))


def test_every_drawn_spec_passes_every_toolchain(batch):
    assert not batch.failures, harness.report(batch)


def test_the_batch_reached_every_toolchain(batch):
    """Each runner ran on the specs it should, the multiplexed ones included: C, cantools and
    canmatrix and the Python bindings on every drawn spec; Rust on its crates, half of them
    multiplexed."""
    summary = batch.runners()
    print(f"anyspec runners: {summary}", file=sys.stderr)
    muxed = sum(bool(r.facts.get("multiplexed")) for r in batch.results)
    want = {"c": (N, muxed), "cantools": (N, muxed), "canmatrix": (N, muxed), "python": (N, muxed),
            "rust": (MIN_RUST, min(muxed, MIN_RUST // 2)), "json": (min(MIN_JSON, N), 0), "typescript": (min(MIN_JSON, N), 0),
            "python-mypy": (max(1, N // 20), 0), "c-cross": (N // 10, 0)}  # mypy and qemu: every 10th spec
    short = {k: f"{batch.count(k)} < {n} or {batch.count(k, multiplexed=True)} < {m} multiplexed" for k, (n, m) in want.items()
             if batch.count(k) < n or batch.count(k, multiplexed=True) < m}
    assert muxed >= N // 10, f"only {muxed} of {N} specs multiplex a message"
    assert not short, f"specs that reached each toolchain: {short} (a spec that fails check or gen reaches none); {summary}"


def test_make_fragment_runs_the_long_mode():
    proc = subprocess.run(["make", "-n", "test-any-spec", "N=3"], cwd=harness.ROOT, capture_output=True, text=True, check=False)
    assert proc.returncode == 0 and "tests/anyspec/run.py" in proc.stdout and "-n 3" in proc.stdout, proc.stdout + proc.stderr
