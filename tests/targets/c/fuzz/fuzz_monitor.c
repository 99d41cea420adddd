/* libFuzzer: the receive monitor on arbitrary traffic. Records of 12 bytes: message pick (or a
 * raw ID when bit 7 is set), time step (2 bytes), length, 8 data bytes. Frame counts grow by at
 * most one a frame, states stay in range, fault codes stay in their tables, a timed-out message
 * is reported as code 07 at least. */
#include <stdint.h>
#include <string.h>

#include "kaiwo_gateway.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    kaiwo_gateway_monitor_t mon;
    uint32_t now = 0;
    size_t at;
    int i;
    kaiwo_gateway_monitor_init(&mon);
    for (i = 0; i < (int)KAIWO_GATEWAY_MSG_COUNT; i += 2) {
        kaiwo_gateway_monitor_expect(&mon, (kaiwo_gateway_msg_t)i, now, (uint32_t)i % 4u);
    }
    for (at = 0; at + 12 <= size; at += 12) {
        const uint8_t *r = data + at;
        uint32_t id;
        uint32_t before_rx = 0, after_rx = 0, ev;
        kaiwo_gateway_unmanned_entry_fault_t code;
        if (r[0] & 0x80u) {
            id = (uint32_t)r[1] << 24 | (uint32_t)r[2] << 16 | (uint32_t)r[3] << 8 | r[4];
        } else {
            id = kaiwo_gateway_msg_info((kaiwo_gateway_msg_t)(r[0] % KAIWO_GATEWAY_MSG_COUNT))->frame_id;
        }
        now += (uint32_t)r[1] | (uint32_t)r[2] << 8;
        for (i = 0; i < (int)KAIWO_GATEWAY_MSG_COUNT; i++) before_rx += mon.msgs[i].frames;
        ev = kaiwo_gateway_monitor_on_frame(&mon, id, r + 4, r[3] % 10u, now, NULL);
        ev |= kaiwo_gateway_monitor_check(&mon, now);
        for (i = 0; i < (int)KAIWO_GATEWAY_MSG_COUNT; i++) after_rx += mon.msgs[i].frames;
        if (after_rx < before_rx || after_rx > before_rx + 1u) __builtin_trap();
        if (ev & ~0x7Fu) __builtin_trap();
        for (i = 0; i < (int)KAIWO_GATEWAY_MSG_COUNT; i++) {
            if (mon.msgs[i].state > KAIWO_GATEWAY_RX_INVALID || mon.msgs[i].accepted > mon.msgs[i].frames) __builtin_trap();
        }
        code = kaiwo_gateway_monitor_unmanned_entry_fault(&mon);
        if (kaiwo_gateway_unmanned_entry_fault_name((uint32_t)code) == NULL) __builtin_trap();
        for (i = 0; i < (int)KAIWO_GATEWAY_MSG_COUNT; i++) {
            if (mon.msgs[i].timed_out && (int)code == 0) __builtin_trap();
        }
        (void)kaiwo_gateway_monitor_remote_entry_fault(&mon);
    }
    return 0;
}
