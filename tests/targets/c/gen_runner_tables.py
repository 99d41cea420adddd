"""Write the per-message part of the C vector runner (runner_tables.h) for any spec: one check
function per message that names its struct fields and functions, the lookup of a case's
message, and the multi-frame text checks. The expected values all come from the line form of
the vectors file at run time (vectors_to_lines.py, which also works out from the spec's IR what
every encode and fixed-point decode must give); this only maps signal names to C code."""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[2] / "generator"))

from canspec.pipeline import compile_spec
from canspec.targets.c.messages import CMessage
from canspec.targets.c.model import CModel, CVin, build_model
from canspec.targets.c.signals import CSignal

# whose refusals a C test run applies: the C target's and those of the vectors it reads
C_TARGETS = ("c", "vectors")


def _bits(signed: bool, expr: str) -> str:
    """An integer's two's complement bits as uint64_t (what the runner compares)."""
    return f"(uint64_t)(int64_t){expr}" if signed else f"(uint64_t){expr}"


def _raw_bits(s: CSignal, expr: str) -> str:
    """A struct field's raw value as uint64_t: an integer's two's complement bits, a float's bit pattern."""
    if s.float is not None:
        return f"{'float' if s.float.narrows else 'double'}_bits({expr})"
    return _bits(s.sig.signed, expr)


def _from_raw(s: CSignal, expr: str) -> str:
    """A case's raw value (uint64_t) as the struct field's value."""
    if s.float is not None:
        return f"{'float' if s.float.narrows else 'double'}_of_bits({expr})"
    return f"({s.type}){expr}"


def _physical_checks(s: CSignal) -> list[str]:
    """Decode and encode of one data signal, both paths (where the header has them)."""
    name, signed = s.sig.name, int(s.sig.signed)
    out = ["    {", f'        const phys_t *ph = phys_of(vc, "{name}");', f"        {s.type} r = 0;", "        (void)r;", "        if (ph != NULL) {"]
    if s.float is not None:  # decode gives the float itself; encode what the reference codec gives (vectors_to_lines.py)
        out += [
            f"            bad += check_float_decode(vc, ph, {s.fn}_decode(s.{s.field}));",
            f"            st = (int){s.fn}_encode(ph->value, &r);",
            f"            bad += check_double_encode(vc, ph, st, {_raw_bits(s, 'r')}, 0);",
        ]
    if s.double is not None:
        out += [
            f"            bad += check_decode(vc, ph, {s.fn}_decode(s.{s.field}), {s.macro}_FACTOR);",
            f"            st = (int){s.fn}_encode(ph->value, &r);",
            f"            bad += check_double_encode(vc, ph, st, {_bits(s.sig.signed, 'r')}, {signed});",
        ]
    f = s.fixed
    if f is not None:
        fixed_signed = f.type != "uint64_t"
        # the input's bits as the fixed type: through int64_t where that is signed
        fixed_in = "ph->fixed_in" if not fixed_signed else "(int64_t)ph->fixed_in" if f.type == "int64_t" else f"({f.type})(int64_t)ph->fixed_in"
        out += [
            f"            bad += check_fixed_decode(vc, ph, {_bits(fixed_signed, f'{s.fn}_decode_fixed(s.{s.field})')}, {int(fixed_signed)});",
            "            if (ph->fixed_encode) {",
            f"                st = (int){s.fn}_encode_fixed({fixed_in}, &r);",
            f'                bad += check_encode(vc, ph, "fixed", st, {_bits(s.sig.signed, "r")}, ph->fixed_raw, {signed});',
            "            }",
        ]
    return out + ["        }", "    }"]


SENTINEL = "0xA5"  # every byte of a multiplexed message's struct before unpack / pack: what an absent field must keep


def _page_checks(cm: CMessage) -> list[str]:
    """A multiplexed message: each field the case holds is unpacked (and its `_is_present` says so);
    every other field still holds the sentinel bytes (unpack left it alone) and is absent."""
    out = []
    for s in cm.signals:
        if s.sig.mux is None:
            out.append(f'    bad += check_raw(vc, "{s.sig.name}", {_raw_bits(s, "s." + s.field)}, {int(s.sig.signed)});')
            continue
        name = s.sig.name
        out += [
            f'    if (find_raw(vc, "{name}", &rv)) {{',
            f'        bad += check_raw(vc, "{name}", {_raw_bits(s, "s." + s.field)}, {int(s.sig.signed)});',
            f'        if (!{s.fn}_is_present(&s)) bad += fail(vc, "{name}: in the case, but _is_present says absent");',
            "    } else {",
            f'        if (memcmp(&s.{s.field}, &sentinel.{s.field}, sizeof s.{s.field}) != 0) bad += fail(vc, "{name}: absent, but unpack overwrote it");',
            f'        if ({s.fn}_is_present(&s)) bad += fail(vc, "{name}: not in the case, but _is_present says present");',
            "    }",
        ]
    out += [f"    memset(&p, {SENTINEL}, sizeof p); /* an absent field is out of its range: pack must neither check nor write it */"]
    return out + [f'    if (find_raw(vc, "{s.sig.name}", &rv)) p.{s.field} = {_from_raw(s, "rv")};' for s in cm.signals]


def _message_check(c: CModel, cm: CMessage) -> list[str]:
    out = [f"static int check_{cm.name}(const vcase_t *vc) {{", f"    {cm.type} s, p;", f"    uint8_t buf[{max(1, cm.msg.dlc)}] = {{0}};",
           "    int bad = 0, st;"]
    mux = bool(cm.presence)
    out += [f"    {cm.type} sentinel;", "    uint64_t rv = 0;", f"    memset(&sentinel, {SENTINEL}, sizeof sentinel);"] if mux else []
    out += [
        f"    memset(&s, {SENTINEL if mux else 0}, sizeof s);",
        f"    st = (int){cm.fn}_unpack(&s, vc->data, vc->len);",
        '    if (st != 0) bad += fail(vc, "unpack returned %d", st);',
    ]
    if mux:
        out += _page_checks(cm)
    else:
        out += [f'    bad += check_raw(vc, "{s.sig.name}", {_raw_bits(s, "s." + s.field)}, {int(s.sig.signed)});' for s in cm.signals]
        out += ["    memset(&p, 0, sizeof p);"] + [f'    p.{s.field} = {_from_raw(s, f"raw_of(vc, {chr(34)}{s.sig.name}{chr(34)})")};' for s in cm.signals]
    out += [f"    st = (int){cm.fn}_pack(buf, sizeof buf, &p);", "    bad += check_bytes(vc, st, buf);"]
    if cm.msg.dlc > 0:  # a DLC-0 frame has no shorter buffer
        out += [
            f"    st = (int){cm.fn}_unpack(&s, vc->data, {cm.msg.dlc - 1}u);",
            f'    if (st != (int){c.macro}_ERR_LENGTH) bad += fail(vc, "short buffer gave %d", st);',
        ]
    for s in cm.signals:
        out += _physical_checks(s) if s.is_data else [f'    bad += check_identity(vc, "{s.sig.name}", {_bits(s.sig.signed, "s." + s.field)});']
    return out + ["    return bad;", "}", ""]


def _lookup(c: CModel) -> list[str]:
    """The message of a case's frame ID (its format is the message's: try both where it matters)."""
    out = ["static int runner_lookup(uint32_t frame_id, const char **name) {"]
    if c.format_arg:
        out += [f"    {c.msg_type} msg = {c.prefix}_lookup_id(frame_id, true);", f"    if (msg == {c.msg_none}) msg = {c.prefix}_lookup_id(frame_id, false);"]
    else:
        out += [f"    const {c.msg_type} msg = {c.prefix}_lookup_id(frame_id);"]
    out += [
        f"    const {c.prefix}_msg_info_t *info = {c.prefix}_msg_info(msg);",
        "    if (info == NULL) return -1;",
        "    *name = info->name;",
        "    return (int)msg;",
        "}",
        "",
    ]
    return out


def _text_check(c: CModel, v: CVin) -> list[str]:
    cm, dlc = v.cm, v.cm.msg.dlc
    return [
        f"        case {cm.index_const}: {{",
        f"            {cm.type} tmpl;",
        f"            static {v.type} rx;",
        f"            static uint8_t frames[{v.frames}][{dlc}];",
        f"            static char text[{v.capacity}];",
        "            int bad = 0, order, k, st;",
        f'            if (vt->nframes != (int){v.macro}_FRAMES) return fail_text(vt, "expected %d frames", (int){v.macro}_FRAMES);',
        f"            (void){cm.fn}_unpack(&tmpl, vt->frames[0], {dlc}u);",
        f"            st = (int){v.fn}_split(vt->text, strlen(vt->text), &tmpl, frames);",
        '            if (st != 0) bad += fail_text(vt, "split returned %d", st);',
        "            for (k = 0; k < vt->nframes; k++)",
        f'                if (memcmp(frames[k], vt->frames[k], {dlc}u) != 0) bad += fail_text(vt, "split frame %d differs", k);',
        "            for (order = 0; order < 2; order++) {",
        f"                {v.fn}_rx_init(&rx);",
        "                for (k = 0; k < vt->nframes; k++) {",
        "                    const int i = order ? vt->nframes - 1 - k : k;",
        f"                    if (k > 0 && {v.fn}_rx_get(&rx, text, sizeof text) != {c.macro}_ERR_INCOMPLETE)",
        '                        bad += fail_text(vt, "incomplete text not reported (order %d)", order);',
        f"                    st = (int){v.fn}_rx_feed(&rx, vt->frames[i], {dlc}u);",
        '                    if (st != 0) bad += fail_text(vt, "feed returned %d", st);',
        "                }",
        f"                st = (int){v.fn}_rx_get(&rx, text, sizeof text);",
        '                if (st != 0 || strcmp(text, vt->text) != 0) bad += fail_text(vt, "reassembled (order %d) status %d", order, st);',
        "            }",
        "            return bad;",
        "        }",
    ]


def tables(spec_path: str) -> str:
    compiled = compile_spec(spec_path, C_TARGETS)
    if compiled.spec is None:
        raise ValueError("\n".join(p.format() for p in compiled.problems))
    c = build_model(compiled.spec)
    out = [f'#include "{c.prefix}.h"', "", f"#define RUNNER_MESSAGES {len(c.messages)}", ""]
    out += _lookup(c)
    for cm in c.messages:
        out += _message_check(c, cm)
    out += ["typedef int (*check_fn)(const vcase_t *);", f"static const check_fn CHECKS[{max(1, len(c.messages))}] = {{"]
    out += [f"    check_{cm.name}," for cm in c.messages] or ["    NULL,"]
    out += [
        "};",
        "",
        "static int check_text(const vtext_t *vt) {",
        "    const char *name = NULL;",
        "    switch (runner_lookup((uint32_t)vt->frame_id, &name)) {",
    ]
    for v in c.vins:
        out += _text_check(c, v)
    out += ['        default: return fail_text(vt, "no multi-frame message has this ID");', "    }", "}"]
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    Path(sys.argv[2]).write_text(tables(sys.argv[1]), encoding="utf-8")
