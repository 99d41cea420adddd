/* The C sequence runner: replays the line form of vectors/sequences.json (tests/targets/c/c_sequences.py)
 * through the generated receive monitor and text reassembly, comparing every step. Any spec:
 * its names come from seq_tables.h. Prints "c sequences: ..., N mismatches"; exit 1 on any. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "seq_tables.h"

#define MAX_SEQ_MESSAGES 8
#define MAX_LINE 4096

static int mismatches;
static int monitor_steps;
static int text_steps;
static int sequence_id;

static void fail(const char *what, const char *line) {
    mismatches++;
    if (mismatches <= 30) {
        printf("  sequence %d: %s: %s", sequence_id, what, line);
    }
}

static size_t hex_bytes(const char *hex, uint8_t *out, size_t cap) {
    size_t n = 0;
    if (strcmp(hex, "-") == 0) {
        return 0;
    }
    while (hex[0] != '\0' && hex[1] != '\0' && n < cap) {
        unsigned v;
        if (sscanf(hex, "%2x", &v) != 1) {
            break;
        }
        out[n++] = (uint8_t)v;
        hex += 2;
    }
    return n;
}

static uint32_t flags_of(const char *names) {
    uint32_t flags = 0;
    char buf[256];
    char *tok;
    if (strcmp(names, "-") == 0) {
        return 0;
    }
    strncpy(buf, names, sizeof buf - 1);
    buf[sizeof buf - 1] = '\0';
    for (tok = strtok(buf, ","); tok != NULL; tok = strtok(NULL, ",")) {
        flags |= strcmp(tok, "unknown_id") == 0       ? SEQ_FLAG_UNKNOWN_ID
                 : strcmp(tok, "length") == 0         ? SEQ_FLAG_LENGTH
                 : strcmp(tok, "checksum") == 0       ? SEQ_FLAG_CHECKSUM
                 : strcmp(tok, "counter_jump") == 0   ? SEQ_FLAG_COUNTER_JUMP
                 : strcmp(tok, "counter_repeat") == 0 ? SEQ_FLAG_COUNTER_REPEAT
                 : strcmp(tok, "timeout") == 0        ? SEQ_FLAG_TIMEOUT
                                                      : 0x80000000u;
    }
    return flags;
}

/* The fault codes at `*rest` (one per C fault table) against the monitor's; advances `*rest`. */
static int codes_differ(const seq_monitor_t *mon, char **rest) {
    int t;
    int bad = 0;
    for (t = 0; t < SEQ_FAULT_TABLES; t++) {
        char *end;
        const long want = strtol(*rest, &end, 10);
        *rest = end;
        bad |= want != seq_code(mon, t);
    }
    return bad;
}

int main(int argc, char **argv) {
    static seq_monitor_t mon;
    static seq_text_t rx;
    static char line[MAX_LINE];
    int seq_msgs[MAX_SEQ_MESSAGES];
    int nmsgs = 0;
    int which = -1;
    int sequences = 0;
    int texts = 0;
    FILE *f;
    if (argc != 2 || (f = fopen(argv[1], "r")) == NULL) {
        fprintf(stderr, "usage: seq_runner LINES\n");
        return 2;
    }
    while (fgets(line, sizeof line, f) != NULL) {
        char *rest = line + 2;
        if (line[0] == 'S') {
            unsigned tol, valid_after;
            int n, i, used;
            sscanf(rest, "%d %u %u %d%n", &sequence_id, &tol, &valid_after, &n, &used);
            rest += used;
            nmsgs = n < MAX_SEQ_MESSAGES ? n : MAX_SEQ_MESSAGES;
            for (i = 0; i < nmsgs; i++) {
                seq_msgs[i] = (int)strtol(rest, &rest, 10);
            }
            seq_init(&mon, tol, valid_after);
            sequences++;
        } else if (line[0] == 'A') {
            const uint32_t t = (uint32_t)strtoul(rest, NULL, 10);
            int i;
            for (i = 0; i < nmsgs; i++) {
                seq_start(&mon, seq_msgs[i], t);
            }
            monitor_steps++;
        } else if (line[0] == 'F') {
            unsigned long t, id;
            int ext, recovered, msg, used;
            char hex[160], faults[128], state[16];
            uint8_t data[72]; /* a CAN FD frame (64 bytes) and one more: a frame too long */
            size_t n;
            uint32_t got, want;
            sscanf(rest, "%lu %lu %d %159s %127s %d %d %15s%n", &t, &id, &ext, hex, faults, &recovered, &msg, state, &used);
            rest += used;
            n = hex_bytes(hex, data, sizeof data);
            got = seq_frame(&mon, (uint32_t)id, ext, data, n, (uint32_t)t);
            want = flags_of(faults) | (recovered ? SEQ_FLAG_RECOVERED : 0u);
            monitor_steps++;
            if (got != want) {
                fail("event flags differ", line);
            } else if (msg >= 0 && strcmp(seq_state_name(mon.msgs[msg].state), state) != 0) {
                fail("state differs", line);
            }
            if (codes_differ(&mon, &rest)) {
                fail("fault codes differ", line);
            }
        } else if (line[0] == 'K') {
            static int was_out[SEQ_MESSAGES + 1];
            int n, i, m, used;
            const uint32_t t = (uint32_t)strtoul(rest, &rest, 10);
            for (m = 0; m < SEQ_MESSAGES; m++) {
                was_out[m] = mon.msgs[m].timed_out;
            }
            (void)seq_check(&mon, t);
            sscanf(rest, "%d%n", &n, &used);
            rest += used;
            for (i = 0; i < n; i++) {
                const int idx = (int)strtol(rest, &rest, 10);
                if (was_out[idx] || !mon.msgs[idx].timed_out) {
                    fail("expected timeout missing", line);
                }
                was_out[idx] = 1; /* accounted for */
            }
            for (m = 0; m < SEQ_MESSAGES; m++) {
                if (!was_out[m] && mon.msgs[m].timed_out) {
                    fail("unexpected timeout", line);
                }
            }
            for (i = 0; i < nmsgs; i++) {
                char state[16];
                sscanf(rest, "%15s%n", state, &used);
                rest += used;
                if (strcmp(seq_state_name(mon.msgs[seq_msgs[i]].state), state) != 0) {
                    fail("state differs", line);
                }
            }
            if (codes_differ(&mon, &rest)) {
                fail("fault codes differ", line);
            }
            monitor_steps++;
        } else if (line[0] == 'Z') {
            int i;
            for (i = 0; i < nmsgs; i++) {
                const seq_monitor_t *mm = &mon;
                const uint32_t got[8] = {mm->msgs[seq_msgs[i]].frames, mm->msgs[seq_msgs[i]].accepted, mm->msgs[seq_msgs[i]].length_errors,
                                         mm->msgs[seq_msgs[i]].checksum_errors, mm->msgs[seq_msgs[i]].counter_repeats,
                                         mm->msgs[seq_msgs[i]].counter_jumps, mm->msgs[seq_msgs[i]].lost_frames, mm->msgs[seq_msgs[i]].timeouts};
                int k;
                for (k = 0; k < 8; k++) {
                    if ((uint32_t)strtoul(rest, &rest, 10) != got[k]) {
                        fail("statistics differ", line);
                    }
                }
            }
            if ((uint32_t)strtoul(rest, &rest, 10) != mon.unknown_ids + seq_dropped) {
                fail("unknown-ID count differs", line);
            }
        } else if (line[0] == 'T') {
            sscanf(rest, "%d %d", &sequence_id, &which);
            seq_text_init(&rx, which);
            texts++;
        } else if (line[0] == 'X') {
            char hex[160], result[32], text[256], got_text[256];
            uint8_t data[72]; /* a CAN FD frame (64 bytes) and one more: a frame too long */
            size_t n;
            int got;
            sscanf(rest, "%159s %31s %255s", hex, result, text);
            n = hex_bytes(hex, data, sizeof data);
            if (seq_text_feed(&rx, which, data, n) != seq_status(result)) {
                fail("feed result differs", line);
            }
            got = seq_text_get(&rx, which, got_text, sizeof got_text);
            if (strcmp(text, "-") == 0 ? got != 0 : strcmp(text, "!") == 0 ? got != -1 : got != 1) {
                fail("completeness differs", line);
            } else if (got == 1) {
                char want[256];
                const size_t len = strcmp(text, "=") == 0 ? 0 : hex_bytes(text, (uint8_t *)want, sizeof want - 1);
                want[len] = '\0';
                if (strcmp(want, got_text) != 0) {
                    fail("text differs", line);
                }
            }
            text_steps++;
        }
    }
    fclose(f);
    printf("c sequences: %d monitor sequences (%d steps), %d text sequences (%d steps), %d mismatches\n", sequences, monitor_steps, texts, text_steps,
           mismatches);
    return mismatches != 0;
}
