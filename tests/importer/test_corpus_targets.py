"""Imported corpus specs through every target's own checks (issue 25 item 4, "on a sample"): the
anyspec harness's stages — C strict (gcc and clang, C and C++) and its vector runner, Python (ruff,
mypy) and its vector runner, cantools reading the generated DBC against the vectors, Rust clippy
and its vector tests — on three opendbc files chosen for what they hold: Motorola fields and
IDs without the extended flag (chrysler_cusw), names starting with a digit (mazda_2017), CAN FD
frames of 64 bytes (gwm_haval_h6_phev_2024). Also: the imported spec's vectors against cantools
reading the *source* DBC."""

from __future__ import annotations

from pathlib import Path

import pytest
from anyspec import harness

from importer.corpus import import_one, one_signal, opendbc_files

SAMPLE = ("chrysler_cusw.dbc", "mazda_2017.dbc", "gwm_haval_h6_phev_2024.dbc")


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    files = {p.name: p for p in opendbc_files()}
    out, top = [], tmp_path_factory.mktemp("corpus")  # one root: the Rust workspace's members lie below it
    for name in SAMPLE:
        root = top / Path(name).stem
        imported = import_one(files[name], root / "spec")
        assert not imported.problems, imported.problems[:5]
        (entry,) = (p.name for p in (root / "spec").glob("*.yaml"))
        job = harness.Job(Path(name).stem, None, str(root / "spec"), entry, str(root / "out"), [], {}, mypy=True)
        out.append((imported, harness.run_spec(job)))
    harness.stage_rust([r for _, r in out], top)
    return out


@pytest.mark.parametrize("index", range(len(SAMPLE)), ids=SAMPLE)
def test_every_target_passes_its_own_checks(results, index: int) -> None:
    _, res = results[index]
    assert set(res.generated) >= {"c", "python", "rust", "dbc", "vectors"}, res.generated
    assert {"c", "python", "cantools", "rust"} <= set(res.checked), res.checked
    assert not res.failures, "\n".join(f"{f.target} / {f.stage}: {f.message[:800]}" for f in res.failures)


@pytest.mark.parametrize("index", range(len(SAMPLE)), ids=SAMPLE)
def test_the_vectors_agree_with_the_source(results, index: int) -> None:
    """Each vector's frame decodes in cantools, reading the source DBC's signal definitions, to the
    vector's raw values."""
    import json

    imported, res = results[index]
    source, spec = imported.loaded.db, imported.spec.can
    placeholder = {v: k for k, v in imported.loaded.renamed.items()}
    cases = json.loads((Path(res.out_dir) / "vectors" / "can.json").read_text(encoding="utf-8"))["cases"]
    assert cases
    decoders: dict[tuple[str, str], object] = {}
    for case in cases:
        msg = spec.message(case["message"])
        theirs = source.get_message_by_frame_id(msg.frame_id)
        data = bytes.fromhex(case["data"])
        for sig in msg.data_signals:
            key = (msg.name, sig.name)
            if key not in decoders:
                decoders[key] = one_signal(theirs, placeholder.get(sig.dbc_name, sig.dbc_name))
            (value,) = decoders[key].decode(data, decode_choices=False, scaling=False).values()  # type: ignore[attr-defined]
            assert value == case["raw"][sig.name], (case["message"], sig.name, case["kind"])
