/* The CAN driver's receive queue: the controller's receive interrupt pushes each frame, the
 * application drains them in its main loop. One producer (the interrupt), one consumer (the
 * main loop): each side writes only its own index, so neither needs to mask interrupts. */
#ifndef CAN_QUEUE_H
#define CAN_QUEUE_H

#include <stdbool.h>
#include <stdint.h>

#define CAN_QUEUE_LENGTH 16u /* a power of two: the indexes wrap by masking */

typedef struct {
    uint32_t id;
    uint32_t stamp_ms; /* when the interrupt took it off the controller */
    uint8_t dlc;
    bool extended;
    uint8_t data[8];
} can_frame_t;

/* Called by the board's CAN receive interrupt; a full queue drops the frame and counts it. */
void can_rx_isr(uint32_t id, bool extended, const uint8_t *data, uint8_t dlc, uint32_t now_ms);

/* The main loop's side: the oldest frame, false when the queue is empty. */
bool can_rx_pop(can_frame_t *out);

/* Empties the queue (at power-on). */
void can_queue_reset(void);

uint32_t can_rx_overruns(void);

#endif
