"""The release: `python -m build` gives an sdist and a wheel; the sdist builds the same wheel as the
tree; in an empty virtual environment the wheel's `canspec` generates every target from a spec
outside the repository, checks, diffs, and names the extra a command needs."""

from __future__ import annotations

import json
import re
import shutil
import tomllib
import zipfile
from pathlib import Path

import pytest
import yaml

from repo_paths import GENERATED, ROOT, SPEC

# Not rendered by `canspec gen`: the lock files are committed beside the generated crates by hand.
NOT_GENERATED = {"rust/Cargo.lock", "json/rust/remote_driving/Cargo.lock"}


def _members(wheel: Path) -> dict[str, bytes]:
    with zipfile.ZipFile(wheel) as z:
        return {name: z.read(name) for name in z.namelist()}


def _tree(root: Path) -> dict[str, bytes]:
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


def test_sdist_builds_the_wheel_the_tree_builds(dist):
    from_sdist, direct = _members(dist.wheel), _members(dist.direct_wheel)
    assert sorted(from_sdist) == sorted(direct)
    assert [n for n in direct if from_sdist[n] != direct[n]] == []
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    assert dist.wheel.name == f"canspec-{project['version']}-py3-none-any.whl"
    # The data the commands read without a checkout: the shipped spec (with its history and
    # schema) and every template, file for file.
    shipped = {f"canspec/_data/spec/{k}" for k in _tree(SPEC)} | {f"canspec/_data/templates/{k}" for k in _tree(ROOT / "templates")}
    assert shipped - set(direct) == set()
    metadata = direct[f"canspec-{project['version']}.dist-info/METADATA"].decode()
    assert sorted(re.findall(r"^Provides-Extra: (\S+)$", metadata, re.MULTILINE)) == sorted(project["optional-dependencies"])


def test_version_names_the_schema_versions(release_venv, tmp_path):
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    schemas = sorted(int(m.group(1)) for p in (SPEC / "schema").iterdir() if (m := re.fullmatch(r"canspec-spec\.v(\d+)\.schema\.json", p.name)))
    assert schemas, "spec/schema/ holds no schema"
    out = release_venv.canspec("--version", cwd=tmp_path)
    assert out.returncode == 0 and out.stdout == f"canspec {project['version']} (reads spec schema_version {', '.join(map(str, schemas))})\n", out


@pytest.fixture(scope="module")
def user_spec(tmp_path_factory) -> Path:
    """A copy of the shipped spec in a folder that knows nothing of the repository."""
    work = tmp_path_factory.mktemp("user")
    shutil.copytree(SPEC, work / "spec")
    return work


def test_every_target_from_a_spec_outside_the_repo(release_venv, user_spec):
    ok = release_venv.canspec("gen", "spec", "-o", "out", cwd=user_spec)
    assert ok.returncode == 0, ok.stderr
    expected = {k: v for k, v in _tree(GENERATED).items() if k not in NOT_GENERATED}
    got = _tree(user_spec / "out")
    assert sorted(got) == sorted(expected)
    assert [k for k in expected if got[k] != expected[k]] == []
    check = release_venv.canspec("gen", "spec", "-o", "out", "--check", cwd=user_spec)
    assert check.returncode == 0 and f"{len(expected)} file(s) up to date" in check.stderr, check.stderr


def test_check_accepts_the_spec_and_refuses_a_broken_one(release_venv, user_spec, tmp_path):
    ok = release_venv.canspec("check", str(user_spec / "spec"), cwd=tmp_path)
    assert ok.returncode == 0 and "kaiwo_gateway 2.0.5: ok" in ok.stderr, ok.stderr
    broken = tmp_path / "spec"
    shutil.copytree(user_spec / "spec", broken)
    gateway = broken / "can" / "gateway.yaml"
    gateway.write_text(gateway.read_text(encoding="utf-8").replace("cycle_ms: 20", "cycle_ms: twenty", 1), encoding="utf-8")
    bad = release_venv.canspec("check", "spec", cwd=tmp_path)
    assert bad.returncode == 1 and re.search(r"spec/can/gateway\.yaml:\d+:\d+: error: .*cycle_ms", bad.stderr), bad.stderr
    assert "Traceback" not in bad.stderr
    # A user's own protocol: a renamed copy of the shipped one.
    shutil.copytree(user_spec / "spec", tmp_path / "own")
    bundle = tmp_path / "own" / "canspec.yaml"
    bundle.write_text(bundle.read_text(encoding="utf-8").replace("name: kaiwo_gateway", "name: my_gateway"), encoding="utf-8")
    own = release_venv.canspec("check", "own", cwd=tmp_path)
    assert own.returncode == 0 and "my_gateway 2.0.5: ok" in own.stderr, own.stderr


def test_diff_of_two_revisions_is_the_change_record(release_venv, user_spec):
    """The document's own change record (spec/history/changelog.yaml, 2.0.5) is the oracle."""
    out = release_venv.canspec("diff", "spec/history/v2.0.4", "spec", "--format", "json", cwd=user_spec)
    assert out.returncode == 0, out.stderr
    record = yaml.safe_load((SPEC / "history" / "changelog.yaml").read_text(encoding="utf-8"))
    newest = next(v for v in record["versions"] if v["version"] == "2.0.5")
    declared = sorted((c["kind"], f"0x{c['message']:08X}", c["signal"]) for item in newest["items"] for c in item["changes"])
    assert sorted((c["kind"], c["frame_id"], c["signal"]) for c in json.loads(out.stdout)["changes"]) == declared
    gate = release_venv.canspec("diff", "spec/history/v2.0.4", "spec", "--fail-on", "compatible", cwd=user_spec)
    assert gate.returncode == 1, gate


@pytest.mark.parametrize(("args", "extra", "status"), [
    (["decode", "drive.log"], "logs", 2),
    (["decode", "drive.log", "--report"], "logs", 2),
    (["plot", "drive.log", "accel_cmd", "-o", "drive.png"], "logs", 2),
    (["simulate", "--node", "AUTOCAR", "--duration", "0.1"], "logs", 2),
    (["pdf", "-o", "handbook.pdf"], "pdf", 1),
    (["import", "bus.dbc", "-o", "imported"], "import", 2),
])
def test_a_command_names_the_extra_it_needs(release_venv, tmp_path, args, extra, status):
    (tmp_path / "drive.log").write_text("(1.000000) can0 1801B0A0#0000000000000000\n", encoding="ascii")
    out = release_venv.canspec(*args, cwd=tmp_path)
    assert out.returncode == status, out
    assert f"pip install 'canspec[{extra}]'" in out.stderr and "Traceback" not in out.stderr + out.stdout, out.stderr


def test_import_the_generated_dbc(import_venv, tmp_path):
    dbc = GENERATED / "dbc" / "kaiwo_gateway.dbc"
    imported = import_venv.canspec("import", str(dbc), "-o", str(tmp_path / "imported"), cwd=tmp_path)
    assert imported.returncode == 0, imported.stderr
    assert import_venv.canspec("check", "imported", cwd=tmp_path).returncode == 0
    again = import_venv.canspec("gen", "imported", "-o", "out", "-t", "dbc", cwd=tmp_path)
    assert again.returncode == 0, again.stderr
    back = import_venv.canspec("diff", str(dbc), str(next((tmp_path / "out" / "dbc").glob("*.dbc"))), "--fail-on", "any", cwd=tmp_path)
    assert back.returncode == 0, back.stdout + back.stderr
