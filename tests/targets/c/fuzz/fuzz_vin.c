/* libFuzzer: VIN reassembly from arbitrary frame sequences (records of 1 length byte + 8 data
 * bytes). Whatever arrives, a text that comes out is printable ASCII of at most 17 characters,
 * and splitting it again and reassembling gives the same text. */
#include <stdint.h>
#include <string.h>

#include "kaiwo_gateway.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    kaiwo_gateway_device_id_text_rx_t rx, again;
    kaiwo_gateway_device_id_t tmpl;
    uint8_t frames[KAIWO_GATEWAY_DEVICE_ID_TEXT_FRAMES][8];
    char text[32], text2[32];
    size_t at, len, i;
    kaiwo_gateway_device_id_text_rx_init(&rx);
    for (at = 0; at + 9 <= size; at += 9) {
        const kaiwo_gateway_status_t st = kaiwo_gateway_device_id_text_rx_feed(&rx, data + at + 1, data[at] % 10u);
        if (st != KAIWO_GATEWAY_OK && st != KAIWO_GATEWAY_ERR_LENGTH && st != KAIWO_GATEWAY_ERR_INDEX && st != KAIWO_GATEWAY_ERR_INCONSISTENT) __builtin_trap();
    }
    if (kaiwo_gateway_device_id_text_rx_get(&rx, text, (size % 20u) + 1u) != KAIWO_GATEWAY_OK) return 0;
    len = strlen(text);
    if (len > KAIWO_GATEWAY_DEVICE_ID_TEXT_LENGTH) __builtin_trap();
    for (i = 0; i < len; i++) {
        if (text[i] < 0x20 || text[i] > 0x7E) __builtin_trap();
    }
    tmpl = rx.first;
    if (kaiwo_gateway_device_id_text_split(text, len, &tmpl, frames) != KAIWO_GATEWAY_OK) __builtin_trap();
    kaiwo_gateway_device_id_text_rx_init(&again);
    for (i = KAIWO_GATEWAY_DEVICE_ID_TEXT_FRAMES; i-- > 0;) {
        if (kaiwo_gateway_device_id_text_rx_feed(&again, frames[i], 8u) != KAIWO_GATEWAY_OK) __builtin_trap();
    }
    if (kaiwo_gateway_device_id_text_rx_get(&again, text2, sizeof text2) != KAIWO_GATEWAY_OK || strcmp(text, text2) != 0) __builtin_trap();
    return 0;
}
