#include "log.h"

#include "board.h"

static char line[160];
static unsigned used;

static void put(char c) {
    if (used < sizeof line) {
        line[used++] = c;
    }
}

void log_str(const char *s) {
    while (*s != '\0') {
        put(*s++);
    }
}

void log_u32(uint32_t v) {
    char digits[10];
    unsigned n = 0u;
    do {
        digits[n++] = (char)('0' + (v % 10u));
        v /= 10u;
    } while (v != 0u);
    while (n > 0u) {
        put(digits[--n]);
    }
}

void log_i32(int32_t v) {
    if (v < 0) {
        put('-');
        log_u32(0u - (uint32_t)v);
    } else {
        log_u32((uint32_t)v);
    }
}

void log_hex(uint32_t v, unsigned digits) {
    while (digits-- > 0u) {
        put("0123456789ABCDEF"[(v >> (4u * digits)) & 0xFu]);
    }
}

void log_end(void) {
    put('\n');
    board_write(line, used);
    used = 0u;
}
