"""A Rust user's project, as the README's Rust section describes it: the crate generated with the
release wheel's `canspec` into the project, a path dependency (the README's Cargo.toml lines),
`cargo build --offline`. The application decodes and re-encodes every shared vector."""

from __future__ import annotations

import json
import math
import shutil

from readme_snippets import block
from release_env import ok, run, user_env
from repo_paths import GENERATED, SPEC

MAIN_RS = r"""
use kaiwo_gateway::Messages;
use std::io::BufRead;

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02X}")).collect()
}

fn main() {
    for line in std::io::stdin().lock().lines() {
        let line = line.unwrap();
        let (id, data) = line.split_once(' ').unwrap();
        let id = u32::from_str_radix(id, 16).unwrap();
        let data: Vec<u8> = (0..data.len()).step_by(2).map(|i| u8::from_str_radix(&data[i..i + 2], 16).unwrap()).collect();
        match Messages::decode(id, &data) {
            Ok(Messages::AutocarEpsCommand(m)) => println!("{} {}", hex(&m.encode()), m.steering_angle_cmd()),
            Ok(m) => println!("{}", hex(&m.encode())),
            Err(e) => println!("error {e:?}"),
        }
    }
}
"""


def test_cargo_project_depends_on_the_generated_crate(release_venv, tmp_path):
    app = tmp_path / "app"
    shutil.copytree(SPEC, app / "spec")
    commands = [line for line in block("# the crate, in your repository: generated/rust/ (Cargo.toml, src/; no dependencies by default)", "sh").splitlines()
                if not line.startswith("#")]
    assert commands == ["canspec gen spec -o generated -t rust"], commands
    ok(run(commands[0], cwd=app, env=release_venv.env))
    dependency = block("# Cargo.toml of your application", "toml")
    (app / "Cargo.toml").write_text('[package]\nname = "ecu_app"\nversion = "0.1.0"\nedition = "2021"\n\n' + dependency, encoding="utf-8")
    (app / "src").mkdir()
    (app / "src" / "main.rs").write_text(MAIN_RS, encoding="utf-8")
    env = {**user_env(), "CARGO_TARGET_DIR": str(tmp_path / "target")}
    ok(run(["cargo", "build", "--offline", "--quiet"], cwd=app, env=env))

    cases = json.loads((GENERATED / "vectors" / "can.json").read_text(encoding="utf-8"))["cases"]
    feed = "".join(f"{c['frame_id']:X} {c['data']}\n" for c in cases)
    done = ok(run([str(tmp_path / "target" / "debug" / "ecu_app")], cwd=app, env=env, stdin=feed))
    lines = done.stdout.splitlines()
    assert len(lines) == len(cases) > 0
    for case, line in zip(cases, lines):
        data, *physical = line.split()
        assert data == case["data"].upper(), (case, line)
        if case["message"] == "autocar_eps_command" and case["kind"] != "tie":  # a tie's physical is the encoder's input, between two steps
            # the decoded double, within rounding of the decimal the vector states (exactness: tests/targets/rust/)
            assert len(physical) == 1 and math.isclose(float(physical[0]), case["physical"]["steering_angle_cmd"], abs_tol=1e-9), (case, line)

