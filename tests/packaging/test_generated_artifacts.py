"""The generated packages as distributable artifacts: `pip wheel` of generated/python (installed in
the release venv, it decodes and encodes every shared vector) and `cargo package` of generated/rust
(which verifies the packaged crate by building it; offline, with the crates .ci/setup fetched)."""

from __future__ import annotations

import json
import shutil
import tarfile
import zipfile

from release_env import ok, run, user_env
from repo_paths import GENERATED

VECTOR_CHECK = """
import json, sys
import kaiwo_gateway as k
bad, cases = [], json.load(open(sys.argv[1], encoding="utf-8"))["cases"]
for case in cases:
    data = bytes.fromhex(case["data"])
    if k.decode_raw(case["frame_id"], data) != case["raw"] or k.encode_raw(case["frame_id"], case["raw"]) != data:
        bad.append(case)
print(json.dumps({"checked": len(cases), "mismatches": len(bad), "first": bad[:3], "file": k.__file__}))
"""


def test_python_package_wheel(release_venv, tmp_path):
    shutil.copytree(GENERATED / "python", tmp_path / "src")
    ok(run([str(release_venv.bin / "python"), "-m", "pip", "wheel", "--quiet", "--no-deps", "-w", str(tmp_path / "wheels"), str(tmp_path / "src")],
           env=release_venv.env))
    wheel = next((tmp_path / "wheels").glob("kaiwo_gateway-2.0.5-*.whl"))
    shipped = {f"kaiwo_gateway/{p.name}" for p in (GENERATED / "python" / "kaiwo_gateway").iterdir() if p.is_file()}
    assert shipped - set(zipfile.ZipFile(wheel).namelist()) == set()
    ok(run([str(release_venv.bin / "python"), "-m", "pip", "install", "--quiet", "--no-deps", str(wheel)], env=release_venv.env))
    out = json.loads(ok(run([str(release_venv.bin / "python"), "-c", VECTOR_CHECK, str(GENERATED / "vectors" / "can.json")],
                            cwd=tmp_path, env=release_venv.env)).stdout)
    vectors = json.loads((GENERATED / "vectors" / "can.json").read_text(encoding="utf-8"))["cases"]
    assert out["checked"] == len(vectors) > 0 and out["mismatches"] == 0 and str(release_venv.root) in out["file"], out


def test_rust_crate_package(tmp_path):
    crate = tmp_path / "crate"
    shutil.copytree(GENERATED / "rust", crate)
    env = {**user_env(), "CARGO_TARGET_DIR": str(tmp_path / "target")}
    done = ok(run(["cargo", "package", "--offline"], cwd=crate, env=env))
    # The one warning: crates.io metadata only the protocol's owner can give (the crate is `publish = false`).
    warnings = [line for line in done.stderr.splitlines() if line.startswith(("warning", "error"))]
    assert warnings == ["warning: manifest has no license, license-file, documentation, homepage or repository"], done.stderr
    packaged = tmp_path / "target" / "package" / "kaiwo_gateway-2.0.5.crate"
    with tarfile.open(packaged) as tar:
        names = {n.split("/", 1)[1] for n in tar.getnames()}
    assert {"Cargo.toml", "Cargo.lock"} | {f"src/{p.name}" for p in (crate / "src").iterdir()} <= names, names
    assert "Verifying kaiwo_gateway v2.0.5" in done.stderr  # cargo built what it packaged

