/* libFuzzer: dispatch by frame ID. Bytes 0..3 are a 29-bit ID (bit 31 of byte 3 picks a known
 * ID instead), the rest the frame. Lookups must agree with each other and with J1939 decomposition. */
#include <stdint.h>
#include <string.h>

#include "kaiwo_gateway.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    uint32_t id;
    kaiwo_gateway_any_t any;
    kaiwo_gateway_msg_t found[KAIWO_GATEWAY_MSG_COUNT];
    kaiwo_gateway_j1939_id_t j;
    kaiwo_gateway_msg_t msg;
    size_t n, i;
    int hit = 0;
    if (size < 4) return 0;
    id = (uint32_t)data[0] | (uint32_t)data[1] << 8 | (uint32_t)data[2] << 16 | (uint32_t)data[3] << 24;
    if (id & 0x80000000u) {
        id = kaiwo_gateway_msg_info((kaiwo_gateway_msg_t)(data[0] % KAIWO_GATEWAY_MSG_COUNT))->frame_id;
    }
    id &= KAIWO_GATEWAY_J1939_ID_MASK;
    msg = kaiwo_gateway_lookup_id(id);
    if (kaiwo_gateway_unpack_any(&any, id, data + 4, size - 4) == KAIWO_GATEWAY_ERR_UNKNOWN_ID) {
        if (msg != KAIWO_GATEWAY_MSG_NONE || any.msg != KAIWO_GATEWAY_MSG_NONE) __builtin_trap();
    } else if (any.msg != msg || kaiwo_gateway_msg_info(msg)->frame_id != id) {
        __builtin_trap();
    }
    j = kaiwo_gateway_j1939_decompose(id);
    if (kaiwo_gateway_j1939_compose(j.priority, j.pgn, j.sa, j.da) != id) __builtin_trap();
    n = kaiwo_gateway_lookup_pgn(j.pgn, found, KAIWO_GATEWAY_MSG_COUNT);
    if (n > (size_t)KAIWO_GATEWAY_MSG_COUNT) __builtin_trap();
    for (i = 0; i < n; i++) {
        if (kaiwo_gateway_msg_info(found[i])->pgn != j.pgn) __builtin_trap();
        hit |= found[i] == msg;
    }
    if (msg != KAIWO_GATEWAY_MSG_NONE && !hit) __builtin_trap();
    if (msg != KAIWO_GATEWAY_MSG_NONE && kaiwo_gateway_lookup_id_any_priority(id) != msg) __builtin_trap();
    return 0;
}
