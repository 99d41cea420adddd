/* A few text helpers over board_write: an ECU image has no room for printf. */
#ifndef LOG_H
#define LOG_H

#include <stdint.h>

void log_str(const char *s);
void log_u32(uint32_t v);
void log_i32(int32_t v);
void log_hex(uint32_t v, unsigned digits);
void log_end(void); /* ends the line and writes it */

#endif
