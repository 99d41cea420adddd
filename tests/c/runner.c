/* canspec C vector runner: reads the line form of a vectors file (tests/c/vectors_to_lines.py)
 * and checks every case against the generated headers of any spec: unpack → raw values,
 * pack(raw) → bytes, short buffer → length error, decode → physical within half a step,
 * encode(physical) → raw in double and in fixed point, fixed decode → the exact scaled physical
 * value; multi-frame text split and reassembly in both orders. The per-message part
 * (runner_tables.h, from tests/c/gen_runner_tables.py) names the spec's structs and functions;
 * the fixed-point expectations are exact integer arithmetic on the spec's own factor and
 * offset (128-bit). Prints the number of cases checked; exits 1 on any mismatch. */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_SIGNALS 64
#define NAME_CAP 160
#define TEXT_CAP 96

/* The checks: a spec without data signals, counters, multi-frame texts, ... calls only some. */
#define MAYBE_UNUSED __attribute__((unused))

__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;

typedef struct {
    char name[NAME_CAP];
    double value;
    char text[TEXT_CAP];
    int rule;          /* 1: the shared rule's result for this double is known (`rule_raw`, or a refusal) */
    int rule_refuses;
    uint64_t rule_raw;
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
    uint8_t (*frames)[8];
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

/* A 128-bit integer as decimal text (for messages). */
MAYBE_UNUSED static const char *i128_text(i128 v, char *buf) {
    char tmp[48];
    int n = 0, neg = v < 0;
    u128 u = neg ? (u128)0 - (u128)v : (u128)v;
    do {
        tmp[n++] = (char)('0' + (int)(u % 10u));
        u /= 10u;
    } while (u != 0u);
    if (neg) tmp[n++] = '-';
    for (int i = 0; i < n; i++) buf[i] = tmp[n - 1 - i];
    buf[n] = '\0';
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

/* raw_only: a physical encode must refuse it; beyond_double: its physical values do not survive
 * doubles (decode and raw pack only). */
MAYBE_UNUSED static int encodable(const vcase_t *vc) { return strcmp(vc->kind, "raw_only") != 0 && strcmp(vc->kind, "beyond_double") != 0; }
MAYBE_UNUSED static int is_tie(const vcase_t *vc) { return strcmp(vc->kind, "tie") == 0; }

/* The raw value's bits as the number they denote. */
MAYBE_UNUSED static i128 raw_number(uint64_t bits, int is_signed) { return is_signed ? (i128)(int64_t)bits : (i128)bits; }

MAYBE_UNUSED static int check_raw(const vcase_t *vc, const char *name, uint64_t got, int is_signed) {
    uint64_t want;
    char a[48], b[48];
    if (!find_raw(vc, name, &want)) return fail(vc, "%s: no raw value in the case", name);
    if (got != want) return fail(vc, "%s: unpacked raw %s, expected %s", name, i128_text(raw_number(got, is_signed), a), i128_text(raw_number(want, is_signed), b));
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
    char a[48], b[48];
    if (st != 0) return fail(vc, "%s: %s encode of %s returned %d (expected raw %s)", ph->name, path, ph->text, st, i128_text(raw_number(want, is_signed), b));
    if (got != want) return fail(vc, "%s: %s encode of %s gave %s, expected %s", ph->name, path, ph->text, i128_text(raw_number(got, is_signed), a), i128_text(raw_number(want, is_signed), b));
    return 0;
}

/* The double encode of the case's physical value: what the shared rule gives for that double
 * when the lines say (on every case), else the case's raw value (physical-encodable cases). */
MAYBE_UNUSED static int check_double_encode(const vcase_t *vc, const phys_t *ph, int st, uint64_t got, uint64_t raw, int is_signed) {
    char a[48];
    if (!ph->rule) return encodable(vc) ? check_encode(vc, ph, "double", st, got, raw, is_signed) : 0;
    if (!ph->rule_refuses) return check_encode(vc, ph, "double", st, got, ph->rule_raw, is_signed);
    if (st == 0) return fail(vc, "%s: double encode of %s gave %s; the rule refuses it", ph->name, ph->text, i128_text(raw_number(got, is_signed), a));
    return 0;
}

/* The decimal text of a physical value times `scale`, exactly, when that is an integer. */
MAYBE_UNUSED static int scaled_text(const char *text, i128 scale, i128 *out) {
    i128 mant = 0, div = 1;
    int neg = 0, exp10 = 0, frac = 0, digits = 0;
    const char *p = text;
    if (*p == '-') {
        neg = 1;
        p++;
    }
    for (; *p; p++) {
        if (*p >= '0' && *p <= '9') {
            if (++digits > 30) return 0;
            mant = mant * 10 + (*p - '0');
            exp10 -= frac;
        } else if (*p == '.') {
            frac = 1;
        } else if (*p == 'e' || *p == 'E') {
            exp10 += atoi(p + 1);
            break;
        } else {
            return 0;
        }
    }
    if (exp10 > 18 || exp10 < -36) return 0;
    mant *= scale;
    for (; exp10 > 0; exp10--) mant *= 10;
    for (; exp10 < 0; exp10++) div *= 10;
    if (mant % div != 0) return 0;
    *out = (neg ? -1 : 1) * (mant / div);
    return 1;
}

/* num / den rounded half away from zero, exactly (den != 0): the rule's exact form. */
MAYBE_UNUSED static i128 div_round_exact(i128 num, i128 den) {
    if (den < 0) {
        num = -num;
        den = -den;
    }
    const i128 a = num < 0 ? -num : num;
    i128 q = a / den;
    if (2 * (a % den) >= den) q++;
    return num < 0 ? -q : q;
}

/* The fixed-point input an encode check feeds, and the raw value it must give: the exact
 * scaled physical value of the case's raw value, or a tie as written with its exact rounding
 * (half away from zero) when the text is exactly halfway between two steps (a tie of a wide
 * field may be written as a nearby double). 0: no fixed encode check. */
MAYBE_UNUSED static int fixed_input(const vcase_t *vc, const phys_t *ph, uint64_t raw, int is_signed, i128 scale, i128 ff, i128 fo, i128 *in, uint64_t *want) {
    const i128 step = ff < 0 ? -ff : ff;
    if (!encodable(vc)) return 0;
    if (!is_tie(vc)) {
        *in = raw_number(raw, is_signed) * ff + fo;
        *want = raw;
        return 1;
    }
    if (!scaled_text(ph->text, scale, in)) return 0;
    const i128 twice = 2 * (*in - fo) % (2 * step);
    if (twice != step && twice != -step) return 0;
    *want = (uint64_t)div_round_exact(*in - fo, ff);
    return 1;
}

/* Significant decimal digits of an integer. */
MAYBE_UNUSED static int significant_digits(i128 v) {
    int n = 0;
    if (v < 0) v = -v;
    while (v != 0 && v % 10 == 0) v /= 10;
    for (; v != 0; v /= 10) n++;
    return n;
}

/* decode_fixed(raw) must be raw × ff + fo exactly, and the case's physical text must be that
 * value / scale wherever a double holds it to the digit (at most 15 significant digits: the
 * vectors write the shortest text of the nearest double). */
MAYBE_UNUSED static int check_fixed_decode(const vcase_t *vc, const phys_t *ph, i128 got, uint64_t raw, int is_signed, i128 scale, i128 ff, i128 fo) {
    const i128 want = raw_number(raw, is_signed) * ff + fo;
    i128 from_text;
    char a[48], b[48];
    if (got != want) return fail(vc, "%s: fixed decode %s, expected %s", ph->name, i128_text(got, a), i128_text(want, b));
    if (!is_tie(vc) && significant_digits(want) <= 15 && (!scaled_text(ph->text, scale, &from_text) || from_text != want))
        return fail(vc, "%s: physical %s × %s is not raw × factor + offset = %s", ph->name, ph->text, i128_text(scale, a), i128_text(want, b));
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

static int parse_text_line(char *line, unsigned long lineno, vtext_t *vt) {
    char *tok, *save = NULL;
    int field = 0;
    size_t n;
    memset(vt, 0, sizeof *vt);
    vt->line = lineno;
    for (tok = strtok_r(line + 2, " ", &save); tok != NULL; tok = strtok_r(NULL, " ", &save), field++) {
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
            if (!hex_bytes(tok, vt->frames[field - 3], 8, &n)) return 0;
        }
    }
    return field == vt->nframes + 3 && vt->text != NULL;
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
    while (getline(&line, &cap, fh) != -1) {
        char hex[256], name[NAME_CAP], num[TEXT_CAP];
        lineno++;
        line[strcspn(line, "\n")] = '\0';
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
            char rule[TEXT_CAP];
            const int n = sscanf(line, "P %159s %95s %95s", name, num, rule);
            if (n >= 2) {
                phys_t *ph = &vc.phys[vc.nphys++];
                strcpy(ph->name, name);
                strcpy(ph->text, num);
                ph->value = strtod(num, NULL);
                ph->rule = n == 3;
                ph->rule_refuses = n == 3 && strcmp(rule, "-") == 0;
                ph->rule_raw = n == 3 && !ph->rule_refuses ? parse_raw(rule) : 0u;
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
