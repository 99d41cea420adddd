/* canspec C vector runner: reads the line form of a vectors file (tests/targets/c/vectors_to_lines.py)
 * and checks every case against the generated headers of any spec: unpack → raw values,
 * pack(raw) → bytes, short buffer → length error, decode → physical within half a step,
 * encode(physical) → raw in double and in fixed point, fixed decode → the exact scaled physical
 * value; multi-frame text split and reassembly in both orders. The per-message part
 * (runner_tables.h, from tests/targets/c/gen_runner_tables.py) names the spec's structs and functions.
 * Every expected value comes with the lines (the encodes' results and the exact fixed-point
 * values from the spec's IR): the runner only compares integers of at most 64 bits, so it
 * builds for 32-bit cores too. Prints the number of cases checked; exits 1 on any mismatch. */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_SIGNALS 64
#define NAME_CAP 160
#define TEXT_CAP 96
#define NUM_CAP 24 /* a 64-bit integer in decimal, sign and terminator included */

/* The checks: a spec without data signals, counters, multi-frame texts, ... calls only some. */
#define MAYBE_UNUSED __attribute__((unused))

typedef struct {
    char name[NAME_CAP];
    double value;
    char text[TEXT_CAP];
    int rule; /* 1: the shared rule's result for this double is known (`rule_raw`, or a refusal) */
    int rule_refuses;
    uint64_t rule_raw;
    int fixed;            /* 1: the fixed-point expectations below are known */
    uint64_t fixed_value; /* decode_fixed(raw): raw × factor × 10^k + offset × 10^k, exactly */
    int text_agrees;      /* 0: the physical text is not that value / 10^k */
    int fixed_encode;     /* 1: encode_fixed(fixed_in) must give fixed_raw */
    uint64_t fixed_in, fixed_raw;
} phys_t;

typedef struct {
    unsigned long line;
    unsigned long frame_id;
    char kind[32];
    char message[NAME_CAP];
    uint8_t data[64];
    size_t len;
    int nraw, nphys;
    char raw_names[MAX_SIGNALS][NAME_CAP];
    uint64_t raw_values[MAX_SIGNALS]; /* two's complement bits of the raw value */
    phys_t phys[MAX_SIGNALS];
} vcase_t;

typedef struct {
    unsigned long line;
    unsigned long frame_id;
    char *text;
    int nframes;
    uint8_t (*frames)[64];
} vtext_t;

MAYBE_UNUSED static int fail(const vcase_t *vc, const char *fmt, ...) {
    va_list ap;
    fprintf(stderr, "line %lu: %s (%s) mismatch: ", vc->line, vc->message, vc->kind);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    return 1;
}

MAYBE_UNUSED static int fail_text(const vtext_t *vt, const char *fmt, ...) {
    va_list ap;
    fprintf(stderr, "line %lu: text \"%s\": ", vt->line, vt->text);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    return 1;
}

/* The number 64 bits denote (two's complement where signed) as decimal text, for messages. */
MAYBE_UNUSED static const char *num_text(uint64_t bits, int is_signed, char buf[NUM_CAP]) {
    if (is_signed) {
        snprintf(buf, NUM_CAP, "%lld", (long long)(int64_t)bits);
    } else {
        snprintf(buf, NUM_CAP, "%llu", (unsigned long long)bits);
    }
    return buf;
}

MAYBE_UNUSED static int find_raw(const vcase_t *vc, const char *name, uint64_t *out) {
    for (int i = 0; i < vc->nraw; i++) {
        if (strcmp(vc->raw_names[i], name) == 0) {
            *out = vc->raw_values[i];
            return 1;
        }
    }
    return 0;
}

MAYBE_UNUSED static uint64_t raw_of(const vcase_t *vc, const char *name) {
    uint64_t v = 0;
    (void)find_raw(vc, name, &v);
    return v;
}

MAYBE_UNUSED static const phys_t *phys_of(const vcase_t *vc, const char *name) {
    for (int i = 0; i < vc->nphys; i++) {
        if (strcmp(vc->phys[i].name, name) == 0) return &vc->phys[i];
    }
    return NULL;
}

MAYBE_UNUSED static int check_raw(const vcase_t *vc, const char *name, uint64_t got, int is_signed) {
    uint64_t want;
    char a[NUM_CAP], b[NUM_CAP];
    if (!find_raw(vc, name, &want)) return fail(vc, "%s: no raw value in the case", name);
    if (got != want) return fail(vc, "%s: unpacked raw %s, expected %s", name, num_text(got, is_signed, a), num_text(want, is_signed, b));
    return 0;
}

MAYBE_UNUSED static int check_identity(const vcase_t *vc, const char *name, uint64_t raw) {
    const phys_t *ph = phys_of(vc, name);
    if (ph != NULL && ph->value != (double)raw) return fail(vc, "%s: physical %s, raw %llu", name, ph->text, (unsigned long long)raw);
    return 0;
}

MAYBE_UNUSED static int check_bytes(const vcase_t *vc, int st, const uint8_t *buf) {
    if (st != 0) return fail(vc, "pack returned %d", st);
    for (size_t i = 0; i < vc->len; i++) {
        if (buf[i] != vc->data[i]) return fail(vc, "packed byte %u is %02X, expected %02X", (unsigned)i, buf[i], vc->data[i]);
    }
    return 0;
}

MAYBE_UNUSED static int check_decode(const vcase_t *vc, const phys_t *ph, double got, double factor) {
    const double tol = fabs(factor) / 2.0 + 1e-9 * (fabs(ph->value) > 1.0 ? fabs(ph->value) : 1.0);
    if (!(fabs(got - ph->value) <= tol)) return fail(vc, "%s: decoded %.17g, expected %s", ph->name, got, ph->text);
    return 0;
}

MAYBE_UNUSED static int check_encode(const vcase_t *vc, const phys_t *ph, const char *path, int st, uint64_t got, uint64_t want, int is_signed) {
    char a[NUM_CAP], b[NUM_CAP];
    if (st != 0) return fail(vc, "%s: %s encode of %s returned %d (expected raw %s)", ph->name, path, ph->text, st, num_text(want, is_signed, b));
    if (got != want) return fail(vc, "%s: %s encode of %s gave %s, expected %s", ph->name, path, ph->text, num_text(got, is_signed, a), num_text(want, is_signed, b));
    return 0;
}

/* The double encode of the case's physical value: what the shared rule gives for that double. */
MAYBE_UNUSED static int check_double_encode(const vcase_t *vc, const phys_t *ph, int st, uint64_t got, int is_signed) {
    char a[NUM_CAP];
    if (!ph->rule) return fail(vc, "%s: the lines give no double encode result (convert them with the spec)", ph->name);
    if (!ph->rule_refuses) return check_encode(vc, ph, "double", st, got, ph->rule_raw, is_signed);
    if (st == 0) return fail(vc, "%s: double encode of %s gave %s; the rule refuses it", ph->name, ph->text, num_text(got, is_signed, a));
    return 0;
}

/* decode_fixed(raw) must give the exact scaled value the lines give, and the case's physical
 * text must be that value (where a double holds it to the digit: vectors_to_lines.py decides). */
MAYBE_UNUSED static int check_fixed_decode(const vcase_t *vc, const phys_t *ph, uint64_t got, int is_signed) {
    char a[NUM_CAP], b[NUM_CAP];
    if (!ph->fixed) return fail(vc, "%s: the lines give no fixed-point expectation (convert them with the spec)", ph->name);
    if (got != ph->fixed_value) return fail(vc, "%s: fixed decode %s, expected %s", ph->name, num_text(got, is_signed, a), num_text(ph->fixed_value, is_signed, b));
    if (!ph->text_agrees) return fail(vc, "%s: physical %s is not raw × factor + offset = %s / 10^k", ph->name, ph->text, num_text(ph->fixed_value, is_signed, b));
    return 0;
}

/* A float field's bit pattern and back (memcpy: the one conversion C defines for every pattern). */
MAYBE_UNUSED static uint64_t float_bits(float f) {
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    return b;
}

MAYBE_UNUSED static uint64_t double_bits(double d) {
    uint64_t b;
    memcpy(&b, &d, sizeof b);
    return b;
}

MAYBE_UNUSED static float float_of_bits(uint64_t bits) {
    const uint32_t b = (uint32_t)bits;
    float f;
    memcpy(&f, &b, sizeof f);
    return f;
}

MAYBE_UNUSED static double double_of_bits(uint64_t bits) {
    double d;
    memcpy(&d, &bits, sizeof d);
    return d;
}

/* A float field decodes to the value the case's text reads as: the same double (-0 apart from 0),
 * or NaN for NaN. */
MAYBE_UNUSED static int check_float_decode(const vcase_t *vc, const phys_t *ph, double got) {
    if (isnan(ph->value) ? !isnan(got) : double_bits(got) != double_bits(ph->value)) return fail(vc, "%s: decoded %.17g, expected %s", ph->name, got, ph->text);
    return 0;
}

#include "runner_tables.h"

static int hex_bytes(const char *hex, uint8_t *out, size_t cap, size_t *len) {
    size_t n = strlen(hex), i;
    if (strcmp(hex, "-") == 0) {
        *len = 0;
        return 1;
    }
    if (n % 2 != 0 || n / 2 > cap) return 0;
    for (i = 0; i < n / 2; i++) {
        unsigned v;
        if (sscanf(hex + 2 * i, "%2x", &v) != 1) return 0;
        out[i] = (uint8_t)v;
    }
    *len = n / 2;
    return 1;
}

static uint64_t parse_raw(const char *text) {
    return text[0] == '-' ? (uint64_t)strtoll(text, NULL, 10) : (uint64_t)strtoull(text, NULL, 10);
}

/* A number of the lines, or `-` (none): whether there is one. */
static int optional_raw(const char *text, uint64_t *out) {
    if (strcmp(text, "-") == 0) return 0;
    *out = parse_raw(text);
    return 1;
}

/* P <signal> <physical> [<double> [<fixed> <agrees> <fixed in> <fixed raw>]] (vectors_to_lines.py) */
static int parse_physical(const char *line, phys_t *ph) {
    char rule[NUM_CAP], fixed[NUM_CAP], agrees[NUM_CAP], in[NUM_CAP], raw[NUM_CAP];
    const int n = sscanf(line, "P %159s %95s %23s %23s %23s %23s %23s", ph->name, ph->text, rule, fixed, agrees, in, raw);
    if (n < 2 || (n > 3 && n != 7)) return 0;
    ph->value = strtod(ph->text, NULL);
    ph->rule = n >= 3;
    ph->rule_refuses = ph->rule && !optional_raw(rule, &ph->rule_raw);
    ph->fixed = n == 7;
    if (ph->fixed) {
        ph->fixed_value = parse_raw(fixed);
        ph->text_agrees = strcmp(agrees, "1") == 0;
        ph->fixed_encode = optional_raw(in, &ph->fixed_in) && optional_raw(raw, &ph->fixed_raw);
    }
    return 1;
}

static int parse_text_line(char *line, unsigned long lineno, vtext_t *vt) {
    char *tok;
    int field = 0;
    size_t n;
    memset(vt, 0, sizeof *vt);
    vt->line = lineno;
    for (tok = strtok(line + 2, " "); tok != NULL; tok = strtok(NULL, " "), field++) {
        if (field == 0) {
            vt->frame_id = strtoul(tok, NULL, 10);
        } else if (field == 1) {
            vt->text = calloc(strlen(tok) / 2 + 1, 1);
            if (vt->text == NULL || !hex_bytes(tok, (uint8_t *)vt->text, strlen(tok) / 2 + 1, &n)) return 0;
        } else if (field == 2) {
            vt->nframes = atoi(tok);
            vt->frames = calloc((size_t)(vt->nframes > 0 ? vt->nframes : 1), sizeof *vt->frames);
            if (vt->frames == NULL) return 0;
        } else if (field - 3 < vt->nframes) {
            if (!hex_bytes(tok, vt->frames[field - 3], sizeof vt->frames[0], &n)) return 0;
        }
    }
    return field == vt->nframes + 3 && vt->text != NULL;
}

/* The next line of `fh` into *buf (grown as needed), without its newline; 0 at the end. ISO C:
 * newlib (the Cortex-M builds) does not declare POSIX getline. */
static int read_line(FILE *fh, char **buf, size_t *cap) {
    size_t len = 0;
    for (;;) {
        if (*cap - len < 2) {
            const size_t bigger = *cap != 0u ? 2u * *cap : 256u;
            char *grown = realloc(*buf, bigger);
            if (grown == NULL) return 0;
            *buf = grown;
            *cap = bigger;
        }
        if (fgets(*buf + len, (int)(*cap - len), fh) == NULL) return len > 0;
        len += strlen(*buf + len);
        if (len > 0 && (*buf)[len - 1] == '\n') {
            (*buf)[len - 1] = '\0';
            return 1;
        }
    }
}

int main(int argc, char **argv) {
    static vcase_t vc;
    char *line = NULL;
    size_t cap = 0;
    FILE *fh;
    unsigned long lineno = 0, cases = 0, texts = 0, failures = 0, in_case = 0;
    if (argc != 2) {
        fprintf(stderr, "usage: %s VECTORS.txt\n", argv[0]);
        return 2;
    }
    fh = fopen(argv[1], "r");
    if (fh == NULL) {
        perror(argv[1]);
        return 2;
    }
    while (read_line(fh, &line, &cap)) {
        char hex[256], num[TEXT_CAP];
        lineno++;
        if (line[0] == 'C') {
            memset(&vc, 0, sizeof vc);
            vc.line = lineno;
            if (sscanf(line, "C %lu %31s %255s %159s", &vc.frame_id, vc.kind, hex, vc.message) != 4 || !hex_bytes(hex, vc.data, sizeof vc.data, &vc.len)) {
                fprintf(stderr, "line %lu: malformed case\n", lineno);
                return 2;
            }
            in_case = 1;
        } else if (line[0] == 'R' && in_case && vc.nraw < MAX_SIGNALS) {
            if (sscanf(line, "R %159s %95s", vc.raw_names[vc.nraw], num) == 2) vc.raw_values[vc.nraw++] = parse_raw(num);
        } else if (line[0] == 'P' && in_case && vc.nphys < MAX_SIGNALS) {
            if (!parse_physical(line, &vc.phys[vc.nphys++])) {
                fprintf(stderr, "line %lu: malformed physical value\n", lineno);
                return 2;
            }
        } else if (line[0] == 'E' && in_case) {
            const char *msg_name = NULL;
            const int msg = runner_lookup((uint32_t)vc.frame_id, &msg_name);
            cases++;
            in_case = 0;
            if (msg < 0 || strcmp(msg_name, vc.message) != 0) {
                failures += (unsigned long)fail(&vc, "frame ID 0x%08lX is not message %s", vc.frame_id, vc.message);
            } else {
                failures += (unsigned long)CHECKS[msg](&vc);
            }
        } else if (line[0] == 'V') {
            vtext_t vt;
            if (!parse_text_line(line, lineno, &vt)) {
                fprintf(stderr, "line %lu: malformed multi-frame text\n", lineno);
                return 2;
            }
            texts++;
            failures += (unsigned long)check_text(&vt);
            free(vt.text);
            free(vt.frames);
        }
    }
    free(line);
    fclose(fh);
    printf("c runner: %lu cases, %lu multi-frame texts checked, %lu mismatches\n", cases, texts, failures);
    return failures == 0 && (cases > 0 || RUNNER_MESSAGES == 0) ? 0 : 1;
}
