"""What the valid fixtures exercise, through the generated C API, with the values worked out
by hand from each fixture: lookups by ID and format, event-driven messages in the receive
monitor, checksums of short frames, renamed and escaped names, the fault function of a table
named like the runtime, 64-bit fields at their limits, the 2^52 branch of the rounding rule,
a negative factor, value tables beyond a C enum."""

from __future__ import annotations

from pathlib import Path

import cbuild
import pytest
import speccheck
from canspec.pipeline import compile_spec

VALID = Path(__file__).resolve().parents[2] / "fixtures" / "valid"

MIXED = r"""
#include <stdio.h>
#include "mixed_bus.h"
#ifdef MIXED_BUS_NODE_ALIVE_CYCLE_MS
#error "an event-driven message has no period"
#endif
#ifdef MIXED_BUS_NODE_REPORT_PGN
#error "no J1939 on this bus"
#endif
int main(void) {
    uint8_t f[8] = {0};
    mixed_bus_any_t any;
    mixed_bus_monitor_t mon;
    const mixed_bus_msg_info_t *alive = mixed_bus_msg_info(MIXED_BUS_MSG_NODE_ALIVE);
    if (mixed_bus_lookup_id(0x123u, false) != MIXED_BUS_MSG_HOST_COMMAND || mixed_bus_lookup_id(0x123u, true) != MIXED_BUS_MSG_NONE) return 1;
    if (mixed_bus_lookup_id(0x124u, true) != MIXED_BUS_MSG_NODE_REPORT || mixed_bus_lookup_id(0x124u, false) != MIXED_BUS_MSG_NONE) return 2;
    if (mixed_bus_unpack_any(&any, 0x124u, false, f, 8) != MIXED_BUS_ERR_UNKNOWN_ID) return 3;
    if (mixed_bus_unpack_any(&any, 0x124u, true, f, 4) != MIXED_BUS_OK || any.msg != MIXED_BUS_MSG_NODE_REPORT) return 4;
    if (alive == NULL || alive->cycle_ms != 0u || !alive->is_extended || mixed_bus_msg_info(MIXED_BUS_MSG_HOST_COMMAND)->is_extended) return 5;
    mixed_bus_monitor_init(&mon);
    mixed_bus_monitor_expect(&mon, MIXED_BUS_MSG_NODE_ALIVE, 0u, 0u);
    mixed_bus_monitor_expect(&mon, MIXED_BUS_MSG_NODE_REPORT, 0u, 0u); /* every 20 ms: 3 cycles = 60 ms */
    if (mixed_bus_monitor_check(&mon, 60u) != 0u) return 6;
    if (mixed_bus_monitor_check(&mon, 61u) != MIXED_BUS_RX_TIMEOUT || !mixed_bus_monitor_timed_out(&mon, MIXED_BUS_MSG_NODE_REPORT)) return 7;
    if (mixed_bus_monitor_check(&mon, 4000000000u) != 0u || mixed_bus_monitor_timed_out(&mon, MIXED_BUS_MSG_NODE_ALIVE)) return 8;
    /* after a timeout: valid again after MIXED_BUS_MONITOR_VALID_AFTER (2) accepted frames */
    if (mixed_bus_monitor_on_frame(&mon, 0x124u, true, f, 4, 4000000001u, NULL) != 0u
        || mixed_bus_monitor_state(&mon, MIXED_BUS_MSG_NODE_REPORT) != MIXED_BUS_RX_INVALID) return 9;
    if (mixed_bus_monitor_on_frame(&mon, 0x124u, true, f, 4, 4000000021u, NULL) != MIXED_BUS_RX_RECOVERED) return 10;
    if (mixed_bus_monitor_on_frame(&mon, 0x124u, false, f, 4, 4000000022u, NULL) != MIXED_BUS_RX_UNKNOWN_ID) return 11;
    puts("api ok");
    return 0;
}
"""

SHORT = r"""
#include <stdio.h>
#include "small_frames.h"
int main(void) {
    small_frames_status_msg_t s = small_frames_status_msg_init(), t;
    small_frames_ping_t p = small_frames_ping_init(), q;
    small_frames_monitor_t mon;
    uint8_t f[3];
    s.state = SMALL_FRAMES_STATUS_VALUES_BUSY; /* bits 0..1 */
    s.counter = 5u;                             /* bits 2..5 */
    s.int_ = -2;                                /* byte 1 */
    if (small_frames_status_msg_pack(f, 3u, &s) != SMALL_FRAMES_OK) return 1;
    if (f[0] != 0x15u || f[1] != 0xFEu || f[2] != (0x15u ^ 0xFEu)) return 2; /* byte 2: XOR of bytes 0 and 1 */
    if (small_frames_status_msg_unpack(&t, f, 3u) != SMALL_FRAMES_OK || t.int_ != -2 || t.checksum != 0xEBu) return 3;
    if (small_frames_status_msg_unpack(&t, f, 2u) != SMALL_FRAMES_ERR_LENGTH) return 4;
    f[1] ^= 0x10u;
    if (small_frames_status_msg_unpack(&t, f, 3u) != SMALL_FRAMES_ERR_CHECKSUM) return 5;
    p.class_ = 3u;
    p.counter = 1u;
    p.xor_ = 0xAu;
    if (small_frames_ping_pack(f, 2u, &p) != SMALL_FRAMES_OK || f[0] != 0xA7u || f[1] != 0xA7u) return 6;
    if (small_frames_ping_unpack(&q, f, 2u) != SMALL_FRAMES_OK || q.xor_ != 0xAu || small_frames_ping_counter_next(3u) != 0u) return 7;
    small_frames_monitor_init(&mon);
    small_frames_monitor_expect(&mon, SMALL_FRAMES_MSG_STATUS_MSG, 0u, 0u); /* every 20 ms */
    if (small_frames_monitor_monitor_values(&mon) != SMALL_FRAMES_MONITOR_VALUES_NONE) return 8;
    (void)small_frames_monitor_check(&mon, 100u);
    if (small_frames_monitor_monitor_values(&mon) != SMALL_FRAMES_MONITOR_VALUES_MESSAGE_TIMEOUT) return 9;
    if (small_frames_status_values_name(2u) == NULL || small_frames_monitor_values_name(1u) == NULL) return 10;
    puts("api ok");
    return 0;
}
"""

WIDE = r"""
#include <stdio.h>
#include <string.h>
#include "wide_bus.h"
int main(void) {
    uint8_t f[8];
    uint64_t u;
    int64_t i;
    uint16_t level;
    wide_bus_odometer_t o = wide_bus_odometer_init(), o2;
    wide_bus_position_t p = wide_bus_position_init(), p2;
    o.total = UINT64_MAX;
    if (wide_bus_odometer_pack(f, 8u, &o) != WIDE_BUS_OK || f[0] != 0xFFu || f[7] != 0xFFu) return 1;
    if (wide_bus_odometer_unpack(&o2, f, 8u) != WIDE_BUS_OK || o2.total != UINT64_MAX) return 2;
    if (wide_bus_odometer_total_encode_fixed(UINT64_MAX, &u) != WIDE_BUS_OK || u != UINT64_MAX
        || wide_bus_odometer_total_decode_fixed(u) != UINT64_MAX) return 3;
    if (wide_bus_position_x_encode_fixed(INT64_MIN, &i) != WIDE_BUS_OK || i != INT64_MIN) return 4;
    p.x = INT64_MIN;
    if (wide_bus_position_pack(f, 8u, &p) != WIDE_BUS_OK || f[7] != 0x80u || f[0] != 0u) return 5;
    if (wide_bus_position_unpack(&p2, f, 8u) != WIDE_BUS_OK || p2.x != INT64_MIN) return 6;
    /* 64 bits × 2: the physical values exceed 64-bit integers, so the double path holds them */
    if (wide_bus_energy_total_encode(1e19, &u) != WIDE_BUS_OK || u != UINT64_C(5000000000000000000)) return 7;
    if (wide_bus_energy_total_encode(-1.0, &u) != WIDE_BUS_ERR_RANGE || wide_bus_energy_total_encode(-0.4, &u) != WIDE_BUS_ERR_RANGE) return 8;
    /* 2^52 + 1 is a double; q + 0.5 is not (it rounds to even): from 2^52 on q is the raw value */
    if (wide_bus_meter_ticks_encode(4503599627370497.0, &u) != WIDE_BUS_OK || u != UINT64_C(4503599627370497)) return 9;
    /* level = raw × -0.5 + 100: 99.75 is halfway between raw 0 and 1 and rounds away from zero */
    if (wide_bus_meter_level_encode(99.75, &level) != WIDE_BUS_OK || level != 1u) return 10;
    if (wide_bus_meter_level_encode_fixed(9975, &level) != WIDE_BUS_OK || level != 1u || WIDE_BUS_METER_LEVEL_FIXED_SCALE != 100) return 11;
    if (wide_bus_meter_level_encode(100.25, &level) != WIDE_BUS_ERR_RANGE || wide_bus_meter_level_decode(2047u) != -923.5) return 12;
    if (WIDE_BUS_MARKER_WRAPPED != UINT64_C(4294967296) || strcmp(wide_bus_marker_name(WIDE_BUS_MARKER_WRAPPED), "wrapped") != 0) return 13;
    if (WIDE_BUS_SIGN_NEGATIVE != -1 || strcmp(wide_bus_sign_name(-1), "negative") != 0) return 14;
    puts("api ok");
    return 0;
}
"""


@pytest.mark.parametrize("fixture,main", [("mixed_id_formats", MIXED), ("short_frames_and_names", SHORT), ("wide_and_scaled_fields", WIDE)])
@pytest.mark.parametrize("strategy", ["3", "0"])
def test_fixture_api(tmp_path, fixture, main, strategy):
    spec = compile_spec(VALID / f"{fixture}.yaml").spec
    headers, _ = speccheck.generate_c(spec, tmp_path / "out")
    prefix = next(headers.glob("*_common.h")).name.removesuffix("_common.h")
    src = tmp_path / "main.c"
    src.write_text(main, encoding="utf-8")
    exe = tmp_path / "api"
    cbuild.compile_c("gcc", [src], exe, ["-std=c99", "-O2", *cbuild.STRICT, f"-D{prefix.upper()}_STRATEGY={strategy}"], [headers])
    proc = cbuild.run([str(exe)])
    assert proc.returncode == 0 and "api ok" in proc.stdout, (proc.returncode, proc.stdout, proc.stderr)
