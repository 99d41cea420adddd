"""Decode reads a narrow field through a precomputed tuple (targets/python/fields.py, PyScale, up to 12 bits):
for every raw value of every such field, on the shipped spec (Intel) and the second benchmark spec (mostly
Motorola, pages), the decoded value is the reference codec's (reference/codec.py: raw × factor + offset
in doubles, exact ints for integer scaling), and of the same type."""

from __future__ import annotations

import pytest
from canspec.pipeline import compile_spec
from canspec.reference import codec
from canspec.targets import python as target

from targets.python import pkgpath
from targets.python.vector_runner import attr_names, load_package

SPECS = {
    "shipped": pkgpath.ROOT / "spec",
    "spec2": pkgpath.ROOT / "bench" / "motorola_fd",
}


def _table_fields(msg):
    """The fields decode may read from a table (within the budget): what fields.scale_value takes, decided here from the IR alone."""
    return [s for s in msg.data_signals if s.role == "data" and s.length <= 12 and not s.is_float and not s.decodes_to_enum
            and not s.is_multiplexer and (s.signed or s.factor != 1 or s.offset != 0)]


@pytest.fixture(scope="module", params=sorted(SPECS))
def case(request, tmp_path_factory):
    spec = compile_spec(SPECS[request.param], ["python"]).spec
    root = tmp_path_factory.mktemp(f"scale-{request.param}")
    for rel, data in target.render_python(spec).items():
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_bytes(data)
    (package,) = [p for p in (root / "python").iterdir() if (p / "__init__.py").is_file()]
    return spec.can, load_package(package)


def test_the_specs_have_what_is_tested():
    fields = [s for path in SPECS.values() for m in compile_spec(path, ["python"]).spec.can.messages for s in _table_fields(m)]
    assert any(s.signed for s in fields) and any(s.offset != 0 for s in fields), "signed and offset table fields"
    assert any(s.is_integer for s in fields) and any(not s.is_integer for s in fields), "int and float table fields"
    assert any(s.is_big_endian for s in fields) and any(not s.is_big_endian for s in fields), "both byte orders"


def test_every_raw_of_every_table_field_decodes_as_the_reference(case):
    can, pkg = case
    assert any(_table_fields(m) for m in can.messages)
    for msg in can.messages:
        names = attr_names(pkg.BY_ID[msg.frame_id])
        for sig in _table_fields(msg):
            page = {c.by: c.first for c in msg.mux_chain(sig)}  # the page that holds the field
            base = {s.name: 0 if s.raw_min <= 0 <= s.raw_max else s.raw_min for s in msg.present(page) if s.role != "checksum"} | page
            for raw in range(sig.raw_type_min, sig.raw_type_max + 1):
                data = codec.pack(msg, base | {sig.name: raw})
                got = getattr(pkg.decode(msg.frame_id, data), names[sig.name])
                want = codec.physical_number(sig, raw)
                assert got == want and type(got) is type(want), (msg.name, sig.name, raw, got, want)


def test_the_tables_keep_within_their_budget(monkeypatch):
    """A package's tables hold at most MAX_SCALE_ENTRIES entries together; the fields beyond it decode by arithmetic."""
    from canspec.targets.python import model

    spec = compile_spec(SPECS["spec2"], ["python"]).spec
    free = model.build_package(spec).scales
    monkeypatch.setattr(model, "MAX_SCALE_ENTRIES", 1500)
    capped = model.build_package(spec).scales
    assert sum(1 << sc.bits for sc in free) > 1500 >= sum(1 << sc.bits for sc in capped) > 0
    assert {sc.value for sc in capped} < {sc.value for sc in free}
