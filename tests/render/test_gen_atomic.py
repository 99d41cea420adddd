"""Issue 9, nothing lost: generation that fails midway — a template error, a full disk, a killed
process — leaves the previous output directory byte-for-byte as it was, and the next run
recovers (staging leftovers removed). Plus the exit codes of `canspec gen --check`."""

from __future__ import annotations

import errno
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from canspec_cli import ROOT, assert_no_traceback, canspec_env, run_canspec

TMP_PREFIX = ".canspec-tmp-"


def snapshot(out: Path) -> dict[str, bytes]:
    return {p.relative_to(out).as_posix(): p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file()}


def leftovers(out: Path) -> list[str]:
    return [p.name for p in out.rglob(f"{TMP_PREFIX}*")]


@pytest.fixture
def previous(tmp_path: Path) -> Path:
    """A copy of the repository's generated/ (what a user has before running gen)."""
    out = tmp_path / "generated"
    # What canspec wrote (per its manifest), not what tests and builds leave beside it
    # (__pycache__, cargo's Cargo.lock).
    manifest = json.loads((ROOT / "generated" / ".canspec-manifest.json").read_text(encoding="utf-8"))
    for rel in [*manifest["files"], ".canspec-manifest.json"]:
        (out / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / "generated" / rel, out / rel)
    (out / "USER_NOTES.txt").write_text("not canspec's: must survive every run\n")
    return out


@pytest.fixture
def edited_spec(tmp_path: Path) -> Path:
    """The shipped spec with one edited description: every generated file's header changes."""
    spec = tmp_path / "spec"
    shutil.copytree(ROOT / "spec", spec)
    can = spec / "can" / "gateway.yaml"
    text = can.read_text(encoding="utf-8")
    assert "Gateway Communication Protocol" in text
    can.write_text(text.replace("Gateway Communication Protocol", "Gateway Communication Protocol (edited)", 1), encoding="utf-8")
    return spec


@pytest.fixture
def expected(edited_spec: Path, tmp_path: Path) -> dict[str, bytes]:
    """What a clean run on the edited spec produces."""
    out = tmp_path / "clean"
    proc = run_canspec("gen", edited_spec, "-o", out)
    assert proc.returncode == 0, proc.stderr
    return snapshot(out)


def gen_in_process(*args: str | Path) -> int:
    from canspec import cli

    return cli.main(["gen", *map(str, args)])


def changed(previous: Path, expected: dict[str, bytes]) -> list[str]:
    """Files a run on the edited spec must rewrite (every file whose header names the spec hash)."""
    before = snapshot(previous)
    return [rel for rel, data in expected.items() if before.get(rel) != data]


def test_edited_spec_rewrites_the_outputs(previous: Path, expected: dict[str, bytes]) -> None:
    """Guard for the tests below: the edit must leave several files to write, so that failing
    after the first, second or last one is a failure midway."""
    assert set(expected) <= set(snapshot(previous)) | {".canspec-manifest.json"}
    assert len(changed(previous, expected)) >= 3


@pytest.mark.parametrize("breakage", ["{% for x in %}\n", "{{ spec.no_such_field }}\n"], ids=["syntax", "undefined"])
def test_template_error_leaves_output_untouched(
    breakage: str, previous: Path, edited_spec: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from canspec import resources
    from canspec.render import environment as render

    templates = tmp_path / "templates"
    shutil.copytree(resources.templates_dir(), templates)
    victim = templates / "dbc" / "protocol.dbc.j2"  # rendered on every run
    victim.write_text(victim.read_text(encoding="utf-8") + breakage, encoding="utf-8")  # fails at the very end
    monkeypatch.setattr(resources, "templates_dir", lambda: templates)
    render.environment.cache_clear()
    before = snapshot(previous)
    try:
        assert gen_in_process(edited_spec, "-o", previous) == 1
    finally:
        render.environment.cache_clear()
    err = capsys.readouterr().err
    assert "template error" in err and "nothing written" in err and "Traceback" not in err, err
    assert snapshot(previous) == before


@pytest.mark.parametrize("fail_at", [1, 2, "last"])
def test_full_disk_while_staging_leaves_output_untouched(
    fail_at: int | str, previous: Path, edited_spec: Path, expected: dict[str, bytes], monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    before = snapshot(previous)
    calls = {"n": 0}
    real_fsync = os.fsync
    limit = len(changed(previous, expected)) if fail_at == "last" else fail_at

    def fsync(fd: int) -> None:
        calls["n"] += 1
        if calls["n"] >= limit:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        real_fsync(fd)

    monkeypatch.setattr(os, "fsync", fsync)
    assert gen_in_process(edited_spec, "-o", previous) == 1
    err = capsys.readouterr().err
    assert "No space left on device" in err and "previous files left unchanged" in err, err
    assert calls["n"] >= limit  # files are staged by several threads: those already started finish
    assert snapshot(previous) == before and not leftovers(previous)
    monkeypatch.setattr(os, "fsync", real_fsync)
    assert gen_in_process(edited_spec, "-o", previous) == 0
    after = snapshot(previous)
    assert {k: v for k, v in after.items() if k != "USER_NOTES.txt"} == expected


def _limit_file_size() -> None:
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # get EFBIG instead of being killed
    resource.setrlimit(resource.RLIMIT_FSIZE, (64 * 1024, 64 * 1024))


def test_file_size_limit_in_a_real_process(previous: Path, edited_spec: Path) -> None:
    """A real write failure (RLIMIT_FSIZE → EFBIG) in a real `canspec gen` process."""
    before = snapshot(previous)
    assert max(len(v) for v in before.values()) > 64 * 1024, "some output must exceed the limit"
    proc = subprocess.run(
        [sys.executable, "-m", "canspec", "gen", str(edited_spec), "-o", str(previous)],
        env=canspec_env(),
        capture_output=True,
        text=True,
        preexec_fn=_limit_file_size,
        timeout=300,
        check=False,
    )
    assert_no_traceback(proc)
    assert proc.returncode == 1 and "File too large" in proc.stderr and "previous files left unchanged" in proc.stderr, proc.stderr
    assert snapshot(previous) == before and not leftovers(previous)


def test_real_full_disk_on_tmpfs(edited_spec: Path, tmp_path: Path) -> None:
    """A genuinely full file system, where we may mount one (root on Linux)."""
    mnt = tmp_path / "mnt"
    mnt.mkdir()
    total = sum(map(len, snapshot(ROOT / "generated").values()))
    size_kib = total * 3 // 2 // 1024  # room for the old files, not for old + staged new ones
    if (
        os.geteuid() != 0
        or subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size_kib}k", "tmpfs", str(mnt)], capture_output=True, check=False).returncode != 0
    ):
        pytest.skip("cannot mount a small tmpfs here (needs root); the monkeypatched and RLIMIT tests cover ENOSPC/EFBIG")
    try:
        out = mnt / "generated"
        shutil.copytree(ROOT / "generated", out)
        before = snapshot(out)
        proc = run_canspec("gen", edited_spec, "-o", out)
        assert_no_traceback(proc)
        assert proc.returncode == 1 and "No space left on device" in proc.stderr, proc.stderr
        assert snapshot(out) == before and not leftovers(out)
    finally:
        subprocess.run(["umount", str(mnt)], check=True)


# A test-only shim: run the real CLI, but SIGKILL the process at the N-th call of `hook`.
KILL_SHIM = """
import os, signal, sys
hook, n = sys.argv[1], int(sys.argv[2])
real = getattr(os, hook)
calls = [0]
def killer(*a, **k):
    result = real(*a, **k)
    calls[0] += 1
    if calls[0] >= n:
        os.kill(os.getpid(), signal.SIGKILL)
    return result
setattr(os, hook, killer)
from canspec.cli import main
sys.exit(main(sys.argv[3:]))
"""


def run_killed(hook: str, n: int, *args: str | Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", KILL_SHIM, hook, str(n), "gen", *map(str, args)], env=canspec_env(), capture_output=True, text=True, timeout=300, check=False
    )


def test_killed_while_staging_leaves_output_untouched_and_rerun_recovers(previous: Path, edited_spec: Path, expected: dict[str, bytes]) -> None:
    before = snapshot(previous)
    proc = run_killed("fsync", 1, edited_spec, "-o", previous)  # killed after the first file is staged
    assert proc.returncode == -signal.SIGKILL, proc.stderr
    assert leftovers(previous), "the kill should leave a staged file behind (else this test proves nothing)"
    files = {k: v for k, v in snapshot(previous).items() if not Path(k).name.startswith(TMP_PREFIX)}
    assert files == before
    proc = run_canspec("gen", edited_spec, "-o", previous)
    assert proc.returncode == 0, proc.stderr
    assert not leftovers(previous)
    assert {k: v for k, v in snapshot(previous).items() if k != "USER_NOTES.txt"} == expected


def test_killed_while_renaming_leaves_only_whole_files(previous: Path, edited_spec: Path, expected: dict[str, bytes]) -> None:
    """Between the first and last rename the directory mixes old and new files (there is no
    atomic multi-file rename); but every file is whole — old or new, never torn — the manifest
    (renamed last) still describes the old run, and a rerun completes the new one."""
    before = snapshot(previous)
    proc = run_killed("replace", 1, edited_spec, "-o", previous)
    assert proc.returncode == -signal.SIGKILL, proc.stderr
    now = {k: v for k, v in snapshot(previous).items() if not Path(k).name.startswith(TMP_PREFIX)}
    assert set(now) == set(before)
    assert all(now[k] in (before[k], expected.get(k)) for k in now)
    assert now[".canspec-manifest.json"] == before[".canspec-manifest.json"]
    assert run_canspec("gen", edited_spec, "-o", previous).returncode == 0
    assert not leftovers(previous)
    assert {k: v for k, v in snapshot(previous).items() if k != "USER_NOTES.txt"} == expected


def test_gen_check_exit_codes(previous: Path) -> None:
    spec = ROOT / "spec"
    ok = run_canspec("gen", spec, "-o", previous, "--check")
    assert ok.returncode == 0 and "up to date" in ok.stderr, ok.stderr + ok.stdout
    before = snapshot(previous)

    victim = next(p for p in sorted(previous.rglob("*")) if p.is_file() and p.suffix in (".dbc", ".json") and not p.name.startswith("."))
    victim.write_bytes(victim.read_bytes() + b"\n")
    stale = run_canspec("gen", spec, "-o", previous, "--check")
    assert stale.returncode == 1 and f"stale: {victim}" in stale.stdout and "1 file(s) out of date" in stale.stderr, stale.stdout + stale.stderr
    assert snapshot(previous)[victim.relative_to(previous).as_posix()] != before[victim.relative_to(previous).as_posix()]  # --check wrote nothing

    victim.unlink()
    missing = run_canspec("gen", spec, "-o", previous, "--check")
    assert missing.returncode == 1 and f"missing: {victim}" in missing.stdout, missing.stdout

    assert run_canspec("gen", spec, "-o", previous).returncode == 0
    assert snapshot(previous) == before

    # A file an earlier run generated for a target this run no longer produces is "extra".
    manifest = previous / ".canspec-manifest.json"
    data = json.loads(manifest.read_text())
    data["files"]["dbc/retired.dbc"] = {"sha256": "0" * 64, "target": "dbc"}
    manifest.write_text(json.dumps(data))
    (previous / "dbc" / "retired.dbc").write_text("old output\n")
    extra = run_canspec("gen", spec, "-o", previous, "--check")
    assert extra.returncode == 1 and f"extra: {previous / 'dbc' / 'retired.dbc'}" in extra.stdout, extra.stdout
    assert run_canspec("gen", spec, "-o", previous).returncode == 0
    assert not (previous / "dbc" / "retired.dbc").exists() and snapshot(previous) == before

    empty = previous.parent / "empty"
    none = run_canspec("gen", spec, "-o", empty, "--check")
    assert none.returncode == 1 and not empty.exists() and none.stdout.count("missing: ") == len(before) - 1, none.stdout


def test_manifest_entries_outside_the_output_are_never_removed(tmp_path: Path) -> None:
    """gen removes the files its manifest says an earlier run wrote; the manifest is a plain file,
    so an entry that leaves the output directory (`..`, an absolute path, a symbolic link out) is
    ignored, never followed."""
    spec = ROOT / "tests" / "fixtures" / "valid" / "minimal_can.yaml"
    out, victim, elsewhere = tmp_path / "out", tmp_path / "victim.txt", tmp_path / "elsewhere"
    assert run_canspec("gen", spec, "-o", out, "-t", "dbc").returncode == 0
    victim.write_text("not canspec's\n")
    elsewhere.mkdir()
    (elsewhere / "x.dbc").write_text("not canspec's either\n")
    (out / "link").symlink_to(elsewhere, target_is_directory=True)
    manifest = json.loads((out / ".canspec-manifest.json").read_text(encoding="utf-8"))
    for rel in ("../victim.txt", str(victim), "dbc/../../victim.txt", "link/x.dbc"):
        manifest["files"][rel] = {"sha256": "0" * 64, "target": "dbc"}
    (out / ".canspec-manifest.json").write_text(json.dumps(manifest), encoding="utf-8")
    proc = run_canspec("gen", spec, "-o", out, "-t", "dbc")
    assert_no_traceback(proc)
    assert proc.returncode == 0 and "0 removed" in proc.stderr, proc.stderr
    assert victim.read_text() == "not canspec's\n" and (elsewhere / "x.dbc").exists()
    assert all(rel.startswith("dbc/") for rel in json.loads((out / ".canspec-manifest.json").read_text(encoding="utf-8"))["files"])


@pytest.mark.parametrize("target, rel", [("docs", "docs/mkdocs.nav.yml"), ("vectors", "vectors/can.json")])
def test_gen_never_replaces_a_file_the_spec_reads(tmp_path: Path, target: str, rel: str) -> None:
    """A spec file that sits where a target writes (here, named like the output) stays as it was."""
    spec = tmp_path / "out" / rel
    spec.parent.mkdir(parents=True)
    shutil.copy(ROOT / "tests" / "fixtures" / "valid" / "minimal_can.yaml", spec)
    before = snapshot(tmp_path / "out")
    proc = run_canspec("gen", spec, "-o", tmp_path / "out", "-t", target)
    assert_no_traceback(proc)
    assert proc.returncode == 1
    assert f"canspec gen: {tmp_path / 'out' / rel} is a file the spec reads, and this run would overwrite it" in proc.stderr, proc.stderr
    assert snapshot(tmp_path / "out") == before


def test_a_failed_run_leaves_no_folders_behind(tmp_path: Path) -> None:
    """Where one output cannot be placed (a file stands where the python/ folder goes), the run
    fails and the folders it had made for the other targets are gone again, the output folder too."""
    out = tmp_path / "new" / "out"
    out.mkdir(parents=True)
    (out / "python").write_text("in the way\n")
    proc = run_canspec("gen", "-o", out)
    assert_no_traceback(proc)
    assert proc.returncode == 1 and "previous files left unchanged" in proc.stderr, proc.stderr
    assert sorted(p.name for p in out.iterdir()) == ["python"]
    (out / "python").unlink()
    out.rmdir()
    proc = run_canspec("gen", "-o", out / "deeper", "-t", "dbc")  # missing parents are made as before
    assert proc.returncode == 0 and (out / "deeper" / ".canspec-manifest.json").is_file(), proc.stderr


def test_an_unreadable_manifest_is_said_and_replaced(tmp_path: Path) -> None:
    """Without a readable manifest gen cannot know which files an earlier run wrote: it says so,
    removes nothing, and writes a good manifest again."""
    spec = ROOT / "tests" / "fixtures" / "valid" / "minimal_can.yaml"
    out = tmp_path / "out"
    assert run_canspec("gen", spec, "-o", out, "-t", "dbc").returncode == 0
    (out / ".canspec-manifest.json").write_text("{not json", encoding="utf-8")
    proc = run_canspec("gen", spec, "-o", out, "-t", "dbc")
    assert proc.returncode == 0, proc.stderr
    assert (f"canspec gen: warning: {out / '.canspec-manifest.json'} cannot be read as canspec's manifest: files an earlier run wrote "
            "and this one does not are left in place") in proc.stderr, proc.stderr
    assert "dbc/fixture.dbc" in json.loads((out / ".canspec-manifest.json").read_text(encoding="utf-8"))["files"]
