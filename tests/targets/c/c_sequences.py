"""The C sequence runner: every sequence of a sequence-vectors file (vectors/sequences.json)
through the generated C receive monitor and multi-frame text reassembly, step by step.

    python3 tests/targets/c/c_sequences.py [SEQUENCES] [--spec SPEC] [--headers DIR] [--build DIR] [--cc CC]

Writes seq_tables.h (the spec's names: its monitor, message indexes, fault-code functions, text
assemblers) and the line form of the file (C has no JSON parser), builds seq_runner.c strict and
under ASan/UBSan, and runs it: exit 0 when every step agrees.

Lines: `S id tolerance valid_after n idx...` a sequence; `A t` start (supervise its messages);
`F t frame_id ext hex faults recovered msg state codes...` a frame (faults comma-separated or `-`,
its message's index and state after it, or -1 and `-` for an unknown ID; codes in the C fault tables' order); `K t n idx... states... codes...` a
check; `Z stats... unknown` the end (8 counts per message); `T id text_index` a text sequence;
`X hex result text` a text step (text `-` null, `!` invalid, else hex).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
sys.path.insert(0, str(ROOT / "generator"))
sys.path.insert(0, str(HERE))

from canspec.pipeline import compile_spec
from canspec.targets.c.model import CModel, build_model
from cbuild import C_TARGETS, SANITIZE, STRICT, compile_c, run

STATS = ("frames", "accepted", "length_errors", "checksum_errors", "counter_repeats", "counter_jumps", "lost_frames", "timeouts")
RESULTS = {"ok": "OK", "length": "ERR_LENGTH", "checksum": "ERR_CHECKSUM", "index": "ERR_INDEX", "inconsistent": "ERR_INCONSISTENT"}
FLAGS = ("unknown_id", "length", "checksum", "counter_jump", "counter_repeat", "timeout")


def tables(c: CModel) -> str:
    """seq_tables.h: the runner's view of one spec's headers."""
    p, m = c.prefix, c.macro
    out = [f'#include "{p}.h"', "", f"typedef {p}_monitor_t seq_monitor_t;", f"#define SEQ_MESSAGES {len(c.messages)}"]
    out += [f"#define SEQ_FLAG_{f.upper()} {m}_RX_{f.upper()}" for f in FLAGS] + [f"#define SEQ_FLAG_RECOVERED {m}_RX_RECOVERED"]
    out += [f"#define SEQ_FAULT_TABLES {len(c.fault_tables)}", ""]
    out += ["static const char *seq_state_name(uint8_t s) {",
            f"    return s == {m}_RX_NO_DATA ? \"no_data\" : s == {m}_RX_INIT ? \"init\" : s == {m}_RX_VALID ? \"valid\" : \"invalid\";", "}", ""]
    out += ["static uint32_t seq_dropped; /* frames of the other ID format, dropped before the monitor */", ""]
    out += ["static void seq_init(seq_monitor_t *mon, unsigned tolerance, unsigned valid_after) {", f"    {p}_monitor_init(mon);", "    seq_dropped = 0u;",
            "    mon->counter_tolerance = (uint8_t)tolerance;", "    mon->valid_after = (uint8_t)valid_after;", "}", ""]
    out += ["static void seq_start(seq_monitor_t *mon, int msg, uint32_t t) {", f"    {p}_monitor_expect(mon, ({c.msg_type})msg, t, 0u);", "}", ""]
    # A protocol of one ID format has a C API without the format: its caller drops a frame of the
    # other format (no message of the protocol), which the runner counts as the unknown frame it is.
    ext = "ext != 0, " if c.format_arg else ""
    sole = (
        []
        if c.format_arg
        else [f"    if (ext != {int(any(m.is_extended for m in c.can.messages))}) {{", "        seq_dropped++;", "        return SEQ_FLAG_UNKNOWN_ID;", "    }"]
    )
    out += ["static uint32_t seq_frame(seq_monitor_t *mon, uint32_t id, int ext, const uint8_t *data, size_t n, uint32_t t) {",
            *sole, f"    return {p}_monitor_on_frame(mon, id, {ext}data, n, t, NULL);", "}", ""]
    out += ["static uint32_t seq_check(seq_monitor_t *mon, uint32_t t) {", f"    return {p}_monitor_check(mon, t);", "}", ""]
    out += ["static long seq_code(const seq_monitor_t *mon, int table) {", "    switch (table) {"]
    out += [f"        case {i}: return (long){ft.fn}(mon);" for i, ft in enumerate(c.fault_tables)]
    out += ["        default: (void)mon; return -1;", "    }", "}", ""]
    out += ["static int seq_status(const char *name) {"]
    out += [f"    if (strcmp(name, \"{k}\") == 0) return (int){m}_{v};" for k, v in RESULTS.items()]
    out += ["    return 999;", "}", ""]
    out += _texts(c)
    return "\n".join(out) + "\n"


def _texts(c: CModel) -> list[str]:
    out = ["typedef union {"] + [f"    {v.type} t{i};" for i, v in enumerate(c.vins)] + ["    int unused_;", "} seq_text_t;", ""]
    out += ["static void seq_text_init(seq_text_t *rx, int which) {", "    switch (which) {"]
    out += [f"        case {i}: {v.fn}_rx_init(&rx->t{i}); break;" for i, v in enumerate(c.vins)]
    out += ["        default: (void)rx; break;", "    }", "}", ""]
    out += ["static int seq_text_feed(seq_text_t *rx, int which, const uint8_t *data, size_t n) {", "    switch (which) {"]
    out += [f"        case {i}: return (int){v.fn}_rx_feed(&rx->t{i}, data, n);" for i, v in enumerate(c.vins)]
    out += ["        default: (void)rx; (void)data; (void)n; return 999;", "    }", "}", ""]
    out += ["/* 1: complete and valid (text in out), 0: incomplete, -1: complete but invalid */",
            "static int seq_text_get(const seq_text_t *rx, int which, char *out, size_t cap) {", "    switch (which) {"]
    for i, v in enumerate(c.vins):
        out += [f"        case {i}:", f"            if (!{v.fn}_rx_complete(&rx->t{i})) return 0;",
                f"            return {v.fn}_rx_get(&rx->t{i}, out, cap) == {c.macro}_OK ? 1 : -1;"]
    out += ["        default: (void)rx; (void)out; (void)cap; return 0;", "    }", "}"]
    return out


def lines(doc: dict, c: CModel) -> str:
    index = {cm.msg.name: i for i, cm in enumerate(c.messages)}
    table_names = [ft.enum.table for ft in c.fault_tables]
    out = []
    for seq in doc["monitor"]:
        msgs = seq["messages"]
        out.append(f"S {seq['id']} {seq['params']['counter_tolerance']} {seq['params']['valid_after']} {len(msgs)} " + " ".join(str(index[n]) for n in msgs))
        for step in seq["steps"]:
            e = step.get("expect", {})
            codes = " ".join(str(e["codes"][t]) for t in table_names) if e else ""
            if step["action"] == "start":
                out.append(f"A {step['t']}")
            elif step["action"] == "frame":
                faults = ",".join(e["faults"]) or "-"
                msg = index[e["message"]] if e["message"] is not None else -1
                out.append(f"F {step['t']} {step['frame_id']} {int(step['extended'])} {step['data'] or '-'} {faults} "
                           f"{int(e['recovered'])} {msg} {e['state'] or '-'} {codes}")
            else:
                states = " ".join(e["states"][n] for n in msgs)
                out.append(f"K {step['t']} {len(e['timeouts'])} " + " ".join(str(index[n]) for n in e["timeouts"]) + f" {states} {codes}")
        stats = " ".join(str(seq["end"]["stats"][n][k]) for n in msgs for k in STATS)
        out.append(f"Z {stats} {seq['end']['unknown_frames']}")
    vins = {v.cm.msg.name: i for i, v in enumerate(c.vins)}
    for seq in doc["texts"]:
        out.append(f"T {seq['id']} {vins[seq['message']]}")
        for step in seq["steps"]:
            text = step["expect"]["text"]
            shown = "-" if text is None else "!" if text is False else (text.encode("ascii").hex().upper() or "=")
            out.append(f"X {step['data'] or '-'} {step['expect']['result']} {shown}")
    return "\n".join(out) + "\n"


def run_sequences(sequences: Path, spec: Path, headers: Path, build: Path, cc: str = "gcc", sanitize: bool = True) -> tuple[int, str]:
    """Build and run the runner: (exit code, its output)."""
    compiled = compile_spec(spec, C_TARGETS)
    if compiled.spec is None or compiled.spec.can is None:
        return 1, "no CAN protocol in the spec"
    c = build_model(compiled.spec)
    build.mkdir(parents=True, exist_ok=True)
    (build / "seq_tables.h").write_text(tables(c), encoding="utf-8")
    data = build / "sequences.lines.txt"
    data.write_text(lines(json.loads(sequences.read_text(encoding="utf-8")), c), encoding="ascii")
    exe = build / "seq_runner"
    flags = ["-std=c99", "-O1", "-g", *STRICT, *(SANITIZE if sanitize else [])]
    compile_c(cc, [HERE / "seq_runner.c"], exe, flags, [headers, build])
    proc = run([str(exe), str(data)])
    return proc.returncode, proc.stdout + proc.stderr


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sequences", nargs="?", type=Path, default=ROOT / "generated" / "vectors" / "sequences.json")
    ap.add_argument("--spec", type=Path, default=ROOT / "spec")
    ap.add_argument("--headers", type=Path, default=ROOT / "generated" / "c")
    ap.add_argument("--build", type=Path, default=ROOT / "build" / "c-sequences")
    ap.add_argument("--cc", default="gcc")
    args = ap.parse_args()
    code, output = run_sequences(args.sequences, args.spec, args.headers, args.build, args.cc)
    sys.stdout.write(output)
    return code


if __name__ == "__main__":
    sys.exit(main())
