/* The ECU's main loop: every SysTick, one pass of the application. */
#include "board.h"
#include "ecu.h"

int main(void) {
    while (board_wait_tick()) {
        ecu_poll(board_millis());
    }
    return 0;
}
