/* libFuzzer: unpack of every message. Byte 0 picks the message, the rest is the frame (any
 * length). A decoded frame must pack again, and pack(unpack(pack(unpack(x)))) == pack(unpack(x)). */
#include <stdint.h>
#include <string.h>

#include "kaiwo_gateway.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    kaiwo_gateway_any_t a, b;
    uint8_t one[64] = {0}, two[64] = {0}; /* any frame, CAN FD's 64 bytes too */
    const kaiwo_gateway_msg_info_t *info;
    kaiwo_gateway_status_t st;
    if (size < 1) return 0;
    info = kaiwo_gateway_msg_info((kaiwo_gateway_msg_t)(data[0] % KAIWO_GATEWAY_MSG_COUNT));
    st = kaiwo_gateway_unpack_any(&a, info->frame_id, data + 1, size - 1);
    if (size - 1 < info->dlc) {
        if (st != KAIWO_GATEWAY_ERR_LENGTH) __builtin_trap();
        return 0;
    }
    if (st != KAIWO_GATEWAY_OK && st != KAIWO_GATEWAY_ERR_CHECKSUM) __builtin_trap();
    if (st == KAIWO_GATEWAY_ERR_CHECKSUM && !info->has_checksum) __builtin_trap();
    if (kaiwo_gateway_pack_any(one, sizeof one, &a) != KAIWO_GATEWAY_OK) __builtin_trap();
    if (kaiwo_gateway_unpack_any(&b, info->frame_id, one, sizeof one) != KAIWO_GATEWAY_OK) __builtin_trap();
    if (kaiwo_gateway_pack_any(two, sizeof two, &b) != KAIWO_GATEWAY_OK) __builtin_trap();
    if (memcmp(one, two, sizeof one) != 0) __builtin_trap();
    return 0;
}
