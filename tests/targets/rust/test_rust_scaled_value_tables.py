"""A value table on a scaled DBC signal (opendbc's vw_pq.dbc: ACS_Sollbeschl, factor 0.005, offset
-7.22, VAL_ 2046 "ADR_nicht_aktiv" 2047 "Fehler"): the Rust crate's getter gives the physical
value, as cantools, C and Python do, and encodes it back; the table's enum is for unscaled fields.
The crate is built from `canspec import` of the DBC, run by a small program, compared with cantools."""

from __future__ import annotations

import os
import subprocess

import cantools
from canspec.pipeline import compile_spec
from canspec.targets import registry
from canspec_cli import run_canspec
from repo_paths import ROOT
from rust_workspace import add_member, write_workspace

DBC = """VERSION ""
NS_ :
BS_:
BU_: ECU
BO_ 872 ACC_System: 8 ECU
 SG_ Mode : 0|2@1+ (1,0) [0|3] "" ECU
 SG_ Gain : 15|8@0- (0.5,10) [-54|73.5] "" ECU
 SG_ Sollbeschl : 24|11@1+ (0.005,-7.22) [-7.22|3.005] "m/s2" ECU
VAL_ 872 Mode 0 "off" 1 "on" ;
VAL_ 872 Gain 127 "max" ;
VAL_ 872 Sollbeschl 2046 "not_active" 2047 "fault" ;
"""
FRAMES = ["0000000000000000", "ffffffffffffffff", "017f0006000000ff", "0280e60700000000", "03c1d405a5a5a5a5"]
PROBE = """use acc::AccSystem;
use std::io::BufRead;
fn main() {
    for line in std::io::stdin().lock().lines() {
        let data: Vec<u8> = line.unwrap().as_bytes().chunks(2).map(|h| u8::from_str_radix(std::str::from_utf8(h).unwrap(), 16).unwrap()).collect();
        let msg = AccSystem::decode(&data).unwrap();
        let (gain, sollbeschl): (f64, f64) = (msg.gain(), msg.sollbeschl());
        let hex: String = match AccSystem::from_values(&msg.values()) {
            Ok(again) => again.encode().iter().map(|b| format!("{b:02x}")).collect(),
            Err(_) => String::from("refused"),
        };
        println!("{} {gain:?} {sollbeschl:?} {hex}", msg.mode().raw());
    }
}
"""


def test_scaled_value_table_fields_decode_and_encode_physical_values(tmp_path):
    (tmp_path / "acc.dbc").write_text(DBC, encoding="utf-8")
    proc = run_canspec("import", tmp_path / "acc.dbc", "-o", tmp_path / "spec")
    assert proc.returncode == 0, proc.stderr
    compiled = compile_spec(tmp_path / "spec", ["rust"])
    assert compiled.spec is not None, [p.format() for p in compiled.problems]
    root = tmp_path / "ws"
    member = add_member(registry()["rust"].render(compiled.spec), root, "acc", "scaledvt")
    (root / "probe" / "src").mkdir(parents=True)
    (root / "probe" / "Cargo.toml").write_text('[package]\nname = "probe"\nversion = "0.0.0"\nedition = "2021"\n\n'
                                               '[dependencies]\nacc = { path = "../acc/rust", package = "scaledvt-acc" }\n', encoding="utf-8")
    (root / "probe" / "src" / "main.rs").write_text(PROBE, encoding="utf-8")
    write_workspace(root, [member, "probe"])
    env = {**os.environ, "CARGO_TARGET_DIR": str(ROOT / "build" / "rust" / "target"), "CARGO_TERM_COLOR": "never"}
    env.pop("RUSTFLAGS", None)
    run = subprocess.run(["cargo", "run", "--offline", "--quiet", "-p", "probe"], cwd=root, env=env, input="\n".join(FRAMES) + "\n",
                         capture_output=True, text=True, check=False)
    assert run.returncode == 0, run.stderr[-6000:]
    msg = cantools.database.load_string(DBC, database_format="dbc").get_message_by_name("ACC_System")
    for hexdata, line in zip(FRAMES, run.stdout.splitlines(), strict=True):
        data = bytes.fromhex(hexdata)
        want = msg.decode(data, decode_choices=False)
        mode, gain, sollbeschl, again = line.split()
        assert (int(mode), float(gain), float(sollbeschl)) == (want["Mode"], want["Gain"], want["Sollbeschl"]), (hexdata, line)
        in_range = all(s.minimum <= want[s.name] <= s.maximum for s in msg.signals)
        assert again == (msg.encode(want, strict=False).hex() if in_range else "refused"), (hexdata, line)
