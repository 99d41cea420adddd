"""What a cantools user writes for canspec's integer-only physical API (bench_cross's like for like).

`cantools generate_c_source --no-floating-point-numbers` converts nothing: it emits only
`<msg>_<sig>_is_in_range(raw)`. A user who needs canspec's `*_decode_fixed` / `*_encode_fixed`
writes, per signal, the conversion around it -- plainly, as below: physical × 10^k from raw by one
multiply and add; raw from physical × 10^k by a range check, `(v - fo) / ff` rounded half away from
zero with C's `/`, a check that the result fits the raw type, then cantools' `is_in_range`.
Signals whose integer path needs 64 bits are left out (a plain user would reach for `int64_t`
division, a helper call on both cores); the shipped spec has none.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[4]


def fixed_user_source(spec: Path, dbc: Path) -> tuple[str, list[str]]:
    """(the C source, its function names) for every signal canspec gives a 32-bit integer path."""
    sys.path.insert(0, str(ROOT / "generator"))
    import cantools
    from cantools.database.can.c_source import camel_to_snake_case

    from canspec.pipeline import compile_spec
    from canspec.targets.c.names import CNames
    from canspec.targets.c.physical import fixed_path
    from canspec.targets.dbc.naming import signal_names

    can = compile_spec(spec, ["c", "dbc"]).spec.can  # type: ignore[union-attr]  # only the benchmarked targets check the spec
    names = CNames.of(can)
    dbc_names = signal_names(can)  # the DBC target's naming: what cantools' C is generated from
    db = cantools.database.load_file(str(dbc), strict=False)
    out = [f'#include "{dbc.stem}.h"', "#include <stdint.h>"]
    fns: list[str] = []
    for m in can.messages:
        dm = db.get_message_by_frame_id(m.frame_id)
        by_spec = {spec: camel_to_snake_case(dbc_name) for (msg, spec), dbc_name in dbc_names.items() if msg == m.name}
        for s in m.data_signals:
            fixed = fixed_path(names, s) if s.role == "data" else None
            if fixed is None or fixed.type != "int32_t":
                continue
            stem = f"{dbc.stem}_{camel_to_snake_case(dm.name)}_{by_spec[s.name]}"
            fn = f"ux_{camel_to_snake_case(dm.name)}_{by_spec[s.name]}"
            out += _signal_functions(s, fixed.scale, stem, fn)
            fns += [f"{fn}_decode_fixed", f"{fn}_encode_fixed"]
    return "\n".join(out) + "\n", fns


def _signal_functions(s, scale: int, stem: str, fn: str) -> list[str]:  # type: ignore[no-untyped-def]
    ff, fo = int(s.factor * scale), int(s.offset * scale)
    lo, hi = -(-s.check_min * scale // 1), s.check_max * scale // 1  # the documented range × 10^k, inward
    t = f"{'int' if s.signed else 'uint'}{s.storage_bits}_t"
    q = "(n >= 0) ? ((n + h) / d) : -((h - n) / d)"
    sign = "" if ff > 0 else "-"
    return [
        f"int32_t {fn}_decode_fixed({t} raw);",
        f"int32_t {fn}_decode_fixed({t} raw) {{ return ((int32_t)raw * {ff}) + {fo}; }}",
        f"int {fn}_encode_fixed(int32_t v, {t} *raw);",
        f"int {fn}_encode_fixed(int32_t v, {t} *raw) {{",
        "    const int32_t d = " + str(abs(ff)) + ", h = " + str(abs(ff) // 2) + ";",
        "    int32_t n, q;",
        f"    if ((v < {int(lo)}) || (v > {int(hi)})) {{ return -1; }}",
        f"    n = {sign}(v - ({fo}));",
        f"    q = {q};",
        f"    if ((q < {s.raw_type_min}) || (q > {s.raw_type_max}) || !{stem}_is_in_range(({t})q)) {{ return -1; }}",
        f"    *raw = ({t})q;",
        "    return 0;",
        "}",
    ]
