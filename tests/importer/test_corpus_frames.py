"""Random frames on imported corpus files (issue 25 item 4): each frame decoded by the generated
Python package and by `canspec decode` (a candump log, JSON output) must give what cantools gives
reading the *source* DBC — raw values exactly, physical values to a double's rounding — for every
field the import kept. Frames are random bytes of each message's length (checksums not verified:
random data fails them, and the check is not what is compared here)."""

from __future__ import annotations

import importlib
import json
import math
import random
import sys

import pytest
from canspec.targets.python import TARGET as PYTHON
from canspec_cli import run_canspec

from importer.corpus import import_one, one_signal, opendbc_files

SAMPLE = ("chrysler_cusw.dbc", "mazda_2017.dbc", "gwm_haval_h6_phev_2024.dbc", "ford_lincoln_base_pt.dbc", "toyota_nodsu_pt.dbc")
FRAMES_PER_MESSAGE = 8


def _frames(spec, seed: int) -> list[tuple[int, bool, bool, bytes]]:
    rng = random.Random(seed)
    return [(m.frame_id, m.is_extended, m.is_fd, rng.randbytes(m.dlc)) for m in spec.can.messages for _ in range(FRAMES_PER_MESSAGE) if m.dlc]


def _candump(frames) -> str:
    lines = []
    for i, (frame_id, extended, fd, data) in enumerate(frames):
        ident = f"{frame_id:08X}" if extended else f"{frame_id:03X}"
        lines.append(f"({i / 1000:.6f}) can0 {ident}#{'#1' if fd else ''}{data.hex().upper()}")
    return "\n".join(lines) + "\n"


@pytest.fixture(scope="module", params=SAMPLE)
def case(request, tmp_path_factory):
    path = next(p for p in opendbc_files() if p.name == request.param)
    root = tmp_path_factory.mktemp(path.stem)
    imported = import_one(path, root / "spec")
    assert imported.spec is not None, imported.problems[:3]
    for name, data in PYTHON.render(imported.spec).items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_bytes(data)
    package = next(p.parent.name for p in (root / "python").glob("*/messages.py"))
    sys.path.insert(0, str(root / "python"))
    try:
        module = importlib.import_module(package)
    finally:
        sys.path.remove(str(root / "python"))
    frames = _frames(imported.spec, seed=len(path.name))
    return imported, module, frames, root


def _expected(imported, frame_id: int, data: bytes) -> tuple[dict[str, int], dict[str, float]]:
    """cantools on the source DBC, each field alone (a source message may hold a signal that leaves
    its frame, which the import left out): raw and physical values of the fields the spec kept."""
    source = imported.loaded.db.get_message_by_frame_id(frame_id)
    msg = next(m for m in imported.spec.can.messages if m.frame_id == frame_id)
    by_dbc = {imported.loaded.renamed.get(s.name, s.name): s.name for s in source.signals}
    raw, phys = {}, {}
    for sig in msg.data_signals:
        alone = one_signal(source, by_dbc[sig.dbc_name])
        raw[sig.name] = alone.decode(data, decode_choices=False, scaling=False)[alone.signals[0].name]
        phys[sig.name] = alone.decode(data, decode_choices=False, scaling=True)[alone.signals[0].name]
    return raw, phys


def _attribute(obj, name: str) -> str:
    """The generated attribute of a field: its name, or with trailing underscores where that is a
    keyword or builtin (targets/python/naming.py)."""
    while not hasattr(obj, name) and len(name) < 80:
        name += "_"
    return name


def _same(a: float, b: float) -> bool:
    return (math.isnan(a) and math.isnan(b)) or math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-12)


def test_the_generated_python_decodes_as_cantools_does(case) -> None:
    imported, module, frames, _ = case
    bad = []
    for frame_id, _, _, data in frames:
        raw, phys = _expected(imported, frame_id, data)
        got_raw = module.decode_raw(frame_id, data, verify_checksum=False)
        got = module.decode(frame_id, data, verify_checksum=False)
        for name, value in raw.items():
            ours = getattr(got, _attribute(got, name))
            ours = float(getattr(ours, "value", ours))
            if got_raw[name] != value or not _same(ours, float(phys[name])):
                bad.append(f"0x{frame_id:X} {data.hex()} {name}: raw {got_raw[name]} / {ours!r}, cantools {value} / {phys[name]!r}")
    assert not bad, f"{len(bad)} differences of {len(frames)} frames, first:\n" + "\n".join(bad[:8])


def test_canspec_decode_decodes_as_cantools_does(case) -> None:
    imported, _, frames, root = case
    log = root / "random.log"
    log.write_text(_candump(frames), encoding="utf-8")
    proc = run_canspec("decode", log, "--spec", next((root / "spec").glob("*.yaml")), "--format", "json")
    rows = [json.loads(line) for line in proc.stdout.splitlines()]
    assert len(rows) == len(frames), proc.stderr[-2000:]
    labels = {(m.frame_id, s.name): {lb.name: lb.raw for lb in s.labels} for m in imported.spec.can.messages for s in m.data_signals}
    bad = []
    for (frame_id, _, _, data), row in zip(frames, rows, strict=True):
        raw, phys = _expected(imported, frame_id, data)
        for name, value in row["signals"].items():
            if isinstance(value, str):  # a value label's name: its raw value
                ok = labels[(frame_id, name)][value] == raw[name]
            else:
                ok = _same(float(value), float(phys[name]))
            if not ok:
                bad.append(f"0x{frame_id:X} {data.hex()} {name}: {value!r}, cantools raw {raw[name]} / {phys[name]!r}")
        if set(row["signals"]) != set(raw):
            bad.append(f"0x{frame_id:X}: fields {sorted(row['signals'])} != {sorted(raw)}")
    assert not bad, f"{len(bad)} differences of {len(frames)} frames, first:\n" + "\n".join(bad[:8])
