/* What the application needs from its board support package: a 1 ms tick, a CAN controller's
 * transmit mailbox and a text channel. board/qemu/ implements it for the test bench (user-mode
 * qemu-arm); a real board maps it onto SysTick, its CAN peripheral and a UART. */
#ifndef BOARD_H
#define BOARD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Sleeps until the next SysTick (the CAN receive interrupt may run meanwhile); false when the
 * board powers off. */
bool board_wait_tick(void);

/* Milliseconds since an arbitrary point, wrapping at 2^32. */
uint32_t board_millis(void);

void board_can_transmit(uint32_t id, const uint8_t *data, uint8_t dlc);

void board_write(const char *text, size_t length);

/* The board calls these in the application: at power-on (`supervised`: the frame IDs of the
 * command sources fitted to this vehicle) and on a diagnostic request for the monitor's state. */
void ecu_power_on(uint32_t now_ms, const uint32_t *supervised, size_t count);
void ecu_report(uint32_t now_ms);

#endif
