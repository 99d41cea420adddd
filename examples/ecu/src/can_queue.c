#include "can_queue.h"

#include <string.h>

static can_frame_t queue[CAN_QUEUE_LENGTH];
static volatile uint32_t head; /* written by the interrupt only */
static volatile uint32_t tail; /* written by the main loop only */
static volatile uint32_t overruns;

void can_rx_isr(uint32_t id, bool extended, const uint8_t *data, uint8_t dlc, uint32_t now_ms) {
    const uint32_t h = head;
    can_frame_t *slot;
    if ((uint32_t)(h - tail) >= CAN_QUEUE_LENGTH) {
        overruns++;
        return;
    }
    slot = &queue[h & (CAN_QUEUE_LENGTH - 1u)];
    slot->id = id;
    slot->extended = extended;
    slot->dlc = (dlc <= 8u) ? dlc : 8u;
    slot->stamp_ms = now_ms;
    (void)memcpy(slot->data, data, slot->dlc);
    head = h + 1u; /* publish after the slot is written */
}

bool can_rx_pop(can_frame_t *out) {
    const uint32_t t = tail;
    if (t == head) {
        return false;
    }
    *out = queue[t & (CAN_QUEUE_LENGTH - 1u)];
    tail = t + 1u;
    return true;
}

void can_queue_reset(void) {
    tail = head;
    overruns = 0u;
}

uint32_t can_rx_overruns(void) {
    return overruns;
}
