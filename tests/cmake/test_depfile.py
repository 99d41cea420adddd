"""`canspec gen --depfile`: a Makefile rule whose target is the output's manifest and whose
inputs are every file the spec's compile read, parsed back here as Make reads it."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

from canspec import depfile
from repo_paths import CANSPEC_ENV, ROOT, SPEC

BUNDLE_PARTS = ["canspec.yaml", "can/gateway.yaml", "can/value_tables.yaml", "json/remote_driving.yaml", "history/changelog.yaml"]
SCHEMA = SPEC / "schema" / "canspec-spec.v1.schema.json"


def parse(text: str) -> tuple[str, list[str]]:
    """A depfile as Make reads it: continuation lines joined, `\\ ` an escaped space."""
    target, rest = re.split(r"(?<!\\):", text.replace("\\\n", " "), maxsplit=1)
    words = re.findall(r"(?:\\.|[^\s\\])+", rest)
    return _unescape(target.strip()), [_unescape(w) for w in words]


def _unescape(word: str) -> str:
    return re.sub(r"\\(.)", r"\1", word).replace("$$", "$")


def copy_spec(dest: Path, errata: bool) -> Path:
    for rel in BUNDLE_PARTS + (["ERRATA.md"] if errata else []):
        (dest / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(SPEC / rel, dest / rel)
    return dest


def gen(spec: Path, out: Path, dep: Path, cwd: Path) -> subprocess.CompletedProcess:  # type: ignore[type-arg]
    cmd = [sys.executable, "-m", "canspec", "gen", str(spec), "-o", str(out), "--target", "c", "--depfile", str(dep)]
    return subprocess.run(cmd, cwd=cwd, env=CANSPEC_ENV, capture_output=True, text=True, timeout=300, check=False)


def test_depfile_lists_every_file_the_spec_read(tmp_path):
    spec = copy_spec(tmp_path / "my spec", errata=True)  # a space: escaped as Make and Ninja read it
    out, dep = tmp_path / "out", tmp_path / "deps" / "gw.d"
    r = gen(spec / "canspec.yaml", out, dep, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    target, inputs = parse(dep.read_text(encoding="utf-8"))
    assert target == str(out / ".canspec-manifest.json")
    expected = {str(spec / rel) for rel in BUNDLE_PARTS + ["ERRATA.md"]}
    expected.add(str(Path(os.path.realpath(SCHEMA))))
    assert {os.path.realpath(p) for p in inputs} == {os.path.realpath(p) for p in expected}
    assert all(os.path.isabs(p) for p in inputs)


def test_depfile_leaves_out_an_absent_errata_and_touches_the_manifest(tmp_path):
    spec = copy_spec(tmp_path / "spec", errata=False)
    out, dep = tmp_path / "out", tmp_path / "gw.d"
    assert gen(spec, out, dep, cwd=ROOT).returncode == 0
    _, inputs = parse(dep.read_text(encoding="utf-8"))
    assert not any(Path(p).name == "ERRATA.md" for p in inputs)
    manifest, header = out / ".canspec-manifest.json", out / "c" / "kaiwo_gateway.h"
    before = manifest.stat().st_mtime_ns, header.stat().st_mtime_ns
    time.sleep(0.05)
    assert gen(spec, out, dep, cwd=ROOT).returncode == 0
    assert manifest.stat().st_mtime_ns > before[0]  # the build system's mark moves
    assert header.stat().st_mtime_ns == before[1]  # unchanged bytes: nothing recompiles


def test_no_depfile_on_a_spec_error(tmp_path):
    spec = copy_spec(tmp_path / "spec", errata=False)
    (spec / "can/value_tables.yaml").write_text("value_tables: [\n", encoding="utf-8")
    r = gen(spec, tmp_path / "out", tmp_path / "gw.d", cwd=ROOT)
    assert r.returncode == 1 and "value_tables.yaml:" in r.stderr and "Traceback" not in r.stderr
    assert not (tmp_path / "gw.d").exists()


def test_escape_round_trips_through_the_parser():
    odd = Path("/a b/c#d/$e.yaml")
    target, inputs = parse(depfile.rule(Path("/out/m.json"), []))
    assert target == "/out/m.json" and inputs == []
    assert parse(f"t: {depfile.escape(str(odd))}\n")[1] == [str(odd)]


def test_a_depfile_that_cannot_be_written_stops_before_any_output_changes(tmp_path):
    """The depfile is written first: when its path is a directory, gen fails and every earlier
    output keeps its bytes (the message says so, and it is true)."""
    spec = copy_spec(tmp_path / "spec", errata=False)
    out = tmp_path / "out"
    assert gen(spec, out, tmp_path / "gw.d", cwd=ROOT).returncode == 0
    header = out / "c" / "kaiwo_gateway.h"
    header.write_text("/* an older header */\n", encoding="utf-8")
    (tmp_path / "a_dir").mkdir()
    r = gen(spec, out, tmp_path / "a_dir", cwd=ROOT)
    assert r.returncode == 1 and "Traceback" not in r.stderr
    assert f"canspec gen: cannot write {tmp_path / 'a_dir'}: is a directory; previous files left unchanged" in r.stderr, r.stderr
    assert header.read_text(encoding="utf-8") == "/* an older header */\n"
    assert not list((tmp_path).glob(".a_dir.*")) and not list((tmp_path / "a_dir").iterdir())
