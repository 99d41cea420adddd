/* The application's entry from the main loop (board.h holds what the board calls in it). */
#ifndef ECU_H
#define ECU_H

#include <stdint.h>

/* One pass at tick now_ms: drain the receive queue, supervise timeouts, send what is due. */
void ecu_poll(uint32_t now_ms);

#endif
