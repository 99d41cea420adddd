"""Write the per-message part of the C vector runner (runner_tables.h) from the IR: one check
function per message that names its struct fields and functions. The expected values all
come from the vectors file at run time; this only maps signal names to C code."""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "generator"))

from canspec.pipeline import compile_spec
from canspec.targets.c.model import build_model


def tables(spec_path: str) -> str:
    compiled = compile_spec(spec_path)
    assert compiled.spec is not None, [p.format() for p in compiled.problems]
    c = build_model(compiled.spec)
    out = [f'#include "{c.prefix}.h"', "",
           "/* runner.c names the spec's lookup functions through these (any prefix). */",
           f"typedef {c.prefix}_msg_t runner_msg_t;",
           f"typedef {c.prefix}_msg_info_t runner_msg_info_t;",
           f"#define runner_lookup_id {c.prefix}_lookup_id",
           f"#define runner_msg_info {c.prefix}_msg_info", ""]
    for cm in c.messages:
        out.append(f"static int check_{cm.name}(const vcase_t *vc) {{")
        out.append(f"    {cm.type} s, p;")
        out.append("    uint8_t buf[8];")
        out.append("    int bad = 0;")
        out.append("    memset(&s, 0, sizeof s);")
        out.append(f"    int st = (int){cm.fn}_unpack(&s, vc->data, vc->len);")
        out.append("    if (st != 0) bad += fail(vc, \"unpack returned %d\", st);")
        for s in cm.signals:
            out.append(f"    bad += check_raw(vc, \"{s.sig.name}\", (int64_t)s.{s.field});")
        out.append("    memset(&p, 0, sizeof p);")
        for s in cm.signals:
            out.append(f"    p.{s.field} = ({s.type})raw_of(vc, \"{s.sig.name}\");")
        out.append(f"    st = (int){cm.fn}_pack(buf, sizeof buf, &p);")
        out.append("    bad += check_bytes(vc, st, buf);")
        out.append(f"    st = (int){cm.fn}_unpack(&s, vc->data, {cm.msg.dlc - 1}u);")
        out.append(f"    if (st != (int){c.macro}_ERR_LENGTH) bad += fail(vc, \"short buffer gave %d\", st);")
        for s in cm.signals:
            name = s.sig.name
            if not s.is_data:
                out.append(f"    bad += check_identity(vc, \"{name}\", (int64_t)s.{s.field});")
                continue
            out.append("    {")
            out.append(f"        {s.type} r = 0;")
            out.append(f"        {s.fixed_type} fx = 0;")
            out.append(f"        const phys_t *ph = phys_of(vc, \"{name}\");")
            out.append("        if (ph != NULL) {")
            if s.has_double:
                out.append(f"            bad += check_decode(vc, ph, {s.fn}_decode(s.{s.field}), {s.macro}_FACTOR);")
            out.append("            if (encodable(vc)) {")
            if s.has_double:
                out.append(f"                st = (int){s.fn}_encode(ph->value, &r);")
                out.append("                bad += check_encode(vc, ph, \"double\", st, (int64_t)r);")
            out.append(f"                if (scaled(ph, {s.scale_int}, &fx)) {{")
            out.append(f"                    st = (int){s.fn}_encode_fixed(fx, &r);")
            out.append("                    bad += check_encode(vc, ph, \"fixed\", st, (int64_t)r);")
            out.append("                } else {")
            out.append("                    bad += fail(vc, \"%s: physical %s is not a multiple of 1/%d\", ph->name, ph->text, " + str(s.scale_int) + ");")
            out.append("                }")
            out.append("            }")
            out.append(f"            if (!is_tie(vc) && scaled(ph, {s.scale_int}, &fx)) {{")
            out.append(f"                bad += check_fixed_decode(vc, ph, (int64_t){s.fn}_decode_fixed(s.{s.field}), (int64_t)fx);")
            out.append("            }")
            out.append("        }")
            out.append("    }")
        out.append("    return bad;")
        out.append("}")
        out.append("")
    out.append("typedef int (*check_fn)(const vcase_t *);")
    out.append(f"static const check_fn CHECKS[{c.macro}_MSG_COUNT] = {{")
    for cm in c.messages:
        out.append(f"    check_{cm.name},")
    out.append("};")
    out.append("")
    out.append("static int check_text(const vtext_t *vt) {")
    out.append(f"    switch ({c.prefix}_lookup_id(vt->frame_id)) {{")
    for v in c.vins:
        cm = v.cm
        out.append(f"        case {cm.index_const}: {{")
        out.append(f"            {cm.type} tmpl;")
        out.append(f"            {v.type} rx;")
        out.append(f"            uint8_t frames[{v.frames}][{cm.msg.dlc}];")
        out.append("            char text[256];")
        out.append("            int bad = 0, order, k, st;")
        out.append(f"            if (vt->nframes != (int){v.macro}_FRAMES) return fail_text(vt, \"expected %d frames\", (int){v.macro}_FRAMES);")
        out.append(f"            (void){cm.fn}_unpack(&tmpl, vt->frames[0], 8u);")
        out.append(f"            st = (int){v.fn}_split(vt->text, strlen(vt->text), &tmpl, frames);")
        out.append("            if (st != 0) bad += fail_text(vt, \"split returned %d\", st);")
        out.append("            for (k = 0; k < vt->nframes; k++)")
        out.append(f"                if (memcmp(frames[k], vt->frames[k], {cm.msg.dlc}u) != 0) bad += fail_text(vt, \"split frame %d differs\", k);")
        out.append("            for (order = 0; order < 2; order++) {")
        out.append(f"                {v.fn}_rx_init(&rx);")
        out.append("                for (k = 0; k < vt->nframes; k++) {")
        out.append("                    const int i = order ? vt->nframes - 1 - k : k;")
        out.append(f"                    if (k > 0 && {v.fn}_rx_get(&rx, text, sizeof text) != {c.macro}_ERR_INCOMPLETE) bad += fail_text(vt, \"incomplete text not reported (order %d)\", order);")
        out.append(f"                    st = (int){v.fn}_rx_feed(&rx, vt->frames[i], 8u);")
        out.append("                    if (st != 0) bad += fail_text(vt, \"feed returned %d\", st);")
        out.append("                }")
        out.append(f"                st = (int){v.fn}_rx_get(&rx, text, sizeof text);")
        out.append("                if (st != 0 || strcmp(text, vt->text) != 0) bad += fail_text(vt, \"reassembled (order %d) status %d\", order, st);")
        out.append("            }")
        out.append("            return bad;")
        out.append("        }")
    out.append("        default: return fail_text(vt, \"no multi-frame message has this ID\");")
    out.append("    }")
    out.append("}")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    Path(sys.argv[2]).write_text(tables(sys.argv[1]), encoding="utf-8")
