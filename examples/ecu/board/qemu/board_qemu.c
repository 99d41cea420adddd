/* The test bench's board: the ECU image runs as a Linux process under user-mode qemu-arm (the
 * core's exact Thumb code; qemu-arm has no Cortex-M peripherals), like tests/targets/c/cross/. It stands in
 * for the board support package: the SysTick is a simulated millisecond, the CAN controller's
 * receive interrupt fires for each frame the bench scripted for that millisecond, the transmit
 * mailbox and the text channel write lines to stdout. The bench script comes on stdin:
 *
 *   B t n id...          power-on at t ms, supervising the n frame IDs (hex) from then on
 *   F t id ext dlc data  a frame received at t (id, data in hex; ext 1 for a 29-bit ID)
 *   R t                  a diagnostic request at t, answered after that tick's pass
 *
 * in time order (modulo 2^32 from the last power-on). Startup paints the application's stack
 * and switches to it; at the end the untouched part gives the stack's high-water mark. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "board.h"
#include "can_queue.h"
#include "log.h"

#define STACK_BYTES 4096u
#define PAINT 0xC0FFEE55u

int main(void);

static uint32_t app_stack[STACK_BYTES / 4u] __attribute__((aligned(8)));

/* Linux ARM EABI system calls: number in r7, `svc 0` (compiled without a frame pointer). */
static long linux_call(long nr, long a, long b, long c) {
    register long r0 __asm__("r0") = a;
    register long r1 __asm__("r1") = b;
    register long r2 __asm__("r2") = c;
    register long r7 __asm__("r7") = nr;
    __asm__ volatile("svc 0" : "+r"(r0) : "r"(r1), "r"(r2), "r"(r7) : "memory");
    return r0;
}

enum { SYS_EXIT_GROUP = 248, SYS_READ = 3, SYS_WRITE = 4 };

void board_write(const char *text, size_t length) {
    while (length > 0u) {
        const long n = linux_call(SYS_WRITE, 1, (long)text, (long)length);
        if (n <= 0) {
            return;
        }
        text += n;
        length -= (size_t)n;
    }
}

/* ---- the bench script on stdin ---- */

static char in_buf[512];
static size_t in_len, in_pos;

static int next_char(void) {
    if (in_pos == in_len) {
        const long n = linux_call(SYS_READ, 0, (long)in_buf, (long)sizeof in_buf);
        if (n <= 0) {
            return -1;
        }
        in_len = (size_t)n;
        in_pos = 0u;
    }
    return (unsigned char)in_buf[in_pos++];
}

typedef struct {
    char kind; /* 'B', 'F', 'R', or 0 at the end of the script */
    uint32_t t;
    uint32_t id;
    uint32_t count; /* B: supervised IDs; F: data bytes */
    bool extended;
    uint32_t ids[8];
    uint8_t data[8];
} bench_line_t;

static bench_line_t next; /* the script's next line, read ahead */

static unsigned digit(int c) {
    if (c >= '0' && c <= '9') {
        return (unsigned)(c - '0');
    }
    if (c >= 'A' && c <= 'F') {
        return (unsigned)(c - 'A' + 10);
    }
    return (c >= 'a' && c <= 'f') ? (unsigned)(c - 'a' + 10) : 99u;
}

/* The next number on the line, in `base`; *c is the character after it. */
static uint32_t number(unsigned base, int *c) {
    uint32_t v = 0u;
    while (*c == ' ') {
        *c = next_char();
    }
    while (digit(*c) < base) {
        v = v * base + digit(*c);
        *c = next_char();
    }
    return v;
}

static void read_ahead(void) {
    int c = next_char();
    uint32_t i;
    next.kind = (c == 'B' || c == 'F' || c == 'R') ? (char)c : 0;
    if (next.kind == 0) {
        return;
    }
    c = next_char();
    next.t = number(10u, &c);
    if (next.kind == 'B') {
        next.count = number(10u, &c);
        for (i = 0u; i < next.count && i < 8u; i++) {
            next.ids[i] = number(16u, &c);
        }
    } else if (next.kind == 'F') {
        next.id = number(16u, &c);
        next.extended = number(10u, &c) != 0u;
        next.count = number(10u, &c);
        while (c == ' ') {
            c = next_char();
        }
        for (i = 0u; i < next.count && i < 8u; i++) {
            const unsigned hi = digit(c);
            c = next_char();
            next.data[i] = (uint8_t)((hi << 4) | digit(c));
            c = next_char();
        }
    }
    while (c != '\n' && c != -1) {
        c = next_char();
    }
}

/* ---- the board ---- */

static uint32_t now;
static bool powered;

uint32_t board_millis(void) {
    return now;
}

void board_can_transmit(uint32_t id, const uint8_t *data, uint8_t dlc) {
    uint8_t i;
    log_str("TX t=");
    log_u32(now);
    log_str(" id=");
    log_hex(id, 8u);
    log_str(" data=");
    for (i = 0u; i < dlc; i++) {
        log_hex(data[i], 2u);
    }
    log_end();
}

/* The receive interrupts of this millisecond, in the script's order. */
static void deliver(void) {
    while (next.kind == 'F' && next.t == now) {
        can_rx_isr(next.id, next.extended, next.data, (uint8_t)next.count, now);
        read_ahead();
    }
}

bool board_wait_tick(void) {
    while (next.kind == 'R' && next.t == now && powered) { /* after the pass at `now` */
        ecu_report(now);
        read_ahead();
    }
    if (next.kind == 'B') { /* a power cycle: the clock restarts where the script says */
        now = next.t;
        powered = true;
        ecu_power_on(now, next.ids, next.count < 8u ? next.count : 8u);
        read_ahead();
        deliver();
        return true;
    }
    if (next.kind == 0 || !powered) {
        return false;
    }
    if ((int32_t)(next.t - now) <= 0) { /* a line behind the clock: the script is out of order */
        log_str("BENCH line out of time order at t=");
        log_u32(next.t);
        log_end();
        return false;
    }
    now++;
    deliver();
    return true;
}

/* ---- startup ---- */

static uint32_t stack_used(void) {
    uint32_t i = 0u;
    while (i < STACK_BYTES / 4u && app_stack[i] == PAINT) {
        i++;
    }
    return STACK_BYTES - 4u * i;
}

void board_start(void) __attribute__((noreturn, used));
void board_start(void) {
    uint32_t i;
    int status;
    for (i = 0u; i < STACK_BYTES / 4u; i++) {
        app_stack[i] = PAINT;
    }
    read_ahead();
    /* main() on the painted stack, as a reset handler starts it on the one the linker placed */
    __asm__ volatile("mov r4, sp\n\t"
                     "mov sp, %1\n\t"
                     "bl main\n\t"
                     "mov sp, r4\n\t"
                     "mov %0, r0\n"
                     : "=r"(status)
                     : "r"(&app_stack[STACK_BYTES / 4u])
                     : "r0", "r1", "r2", "r3", "r4", "r12", "lr", "memory", "cc");
    log_str("STACK used=");
    log_u32(stack_used());
    log_str(" size=");
    log_u32(STACK_BYTES);
    log_end();
    for (;;) {
        (void)linux_call(SYS_EXIT_GROUP, status, 0, 0);
    }
}

__attribute__((naked, noreturn)) void _start(void) {
    __asm__ volatile("bl board_start\n");
}
