/* canspec C vector runner: reads the line form of a vectors file (tests/c/vectors_to_lines.py)
 * and checks every case against the generated headers: unpack → raw values, pack(raw) → bytes,
 * short buffer → length error, decode → physical within half a step, encode(physical) → raw in
 * double and in fixed point, fixed decode → exact scaled physical; multi-frame text split and
 * reassembly in both orders. Prints the number of cases checked; exits 1 on any mismatch. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <stdint.h>

#define MAX_SIGNALS 64

typedef struct {
    char name[64];
    double value;
    char text[64];
} phys_t;

typedef struct {
    unsigned long line;
    unsigned long frame_id;
    char kind[32];
    char message[64];
    uint8_t data[64];
    size_t len;
    int nraw, nphys;
    char raw_names[MAX_SIGNALS][64];
    long long raw_values[MAX_SIGNALS];
    phys_t phys[MAX_SIGNALS];
} vcase_t;

typedef struct {
    unsigned long line;
    unsigned long frame_id;
    char text[256];
    int nframes;
    uint8_t frames[8][8];
} vtext_t;

static int fail(const vcase_t *vc, const char *fmt, ...) {
    va_list ap;
    fprintf(stderr, "line %lu: %s (%s) %s: ", vc->line, vc->message, vc->kind, "mismatch");
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    return 1;
}

static int fail_text(const vtext_t *vt, const char *fmt, ...) {
    va_list ap;
    fprintf(stderr, "line %lu: text \"%s\": ", vt->line, vt->text);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    return 1;
}

static int find_raw(const vcase_t *vc, const char *name, long long *out) {
    int i;
    for (i = 0; i < vc->nraw; i++) {
        if (strcmp(vc->raw_names[i], name) == 0) {
            *out = vc->raw_values[i];
            return 1;
        }
    }
    return 0;
}

static long long raw_of(const vcase_t *vc, const char *name) {
    long long v = 0;
    (void)find_raw(vc, name, &v);
    return v;
}

static const phys_t *phys_of(const vcase_t *vc, const char *name) {
    int i;
    for (i = 0; i < vc->nphys; i++) {
        if (strcmp(vc->phys[i].name, name) == 0) return &vc->phys[i];
    }
    return NULL;
}

static int encodable(const vcase_t *vc) { return strcmp(vc->kind, "raw_only") != 0; }
static int is_tie(const vcase_t *vc) { return strcmp(vc->kind, "tie") == 0; }

static int check_raw(const vcase_t *vc, const char *name, int64_t got) {
    long long want;
    if (!find_raw(vc, name, &want)) return fail(vc, "%s: no raw value in the case", name);
    if ((long long)got != want) return fail(vc, "%s: unpacked raw %lld, expected %lld", name, (long long)got, want);
    return 0;
}

static int check_identity(const vcase_t *vc, const char *name, int64_t raw) {
    const phys_t *ph = phys_of(vc, name);
    if (ph != NULL && ph->value != (double)raw) return fail(vc, "%s: physical %s, raw %lld", name, ph->text, (long long)raw);
    return 0;
}

static int check_bytes(const vcase_t *vc, int st, const uint8_t *buf) {
    size_t i;
    if (st != 0) return fail(vc, "pack returned %d", st);
    for (i = 0; i < vc->len; i++) {
        if (buf[i] != vc->data[i]) return fail(vc, "packed byte %u is %02X, expected %02X", (unsigned)i, buf[i], vc->data[i]);
    }
    return 0;
}

static int check_decode(const vcase_t *vc, const phys_t *ph, double got, double factor) {
    const double tol = fabs(factor) / 2.0 + 1e-9 * (fabs(ph->value) > 1.0 ? fabs(ph->value) : 1.0);
    if (!(fabs(got - ph->value) <= tol)) return fail(vc, "%s: decoded %.17g, expected %s", ph->name, got, ph->text);
    return 0;
}

static int check_encode(const vcase_t *vc, const phys_t *ph, const char *path, int st, int64_t got) {
    long long want;
    if (!find_raw(vc, ph->name, &want)) return fail(vc, "%s: no raw value", ph->name);
    if (st != 0) return fail(vc, "%s: %s encode of %s returned %d", ph->name, path, ph->text, st);
    if ((long long)got != want) return fail(vc, "%s: %s encode of %s gave %lld, expected %lld", ph->name, path, ph->text, (long long)got, want);
    return 0;
}

static int check_fixed_decode(const vcase_t *vc, const phys_t *ph, int64_t got, int64_t want) {
    if (got != want) return fail(vc, "%s: fixed decode %lld, expected %lld (%s)", ph->name, (long long)got, (long long)want, ph->text);
    return 0;
}

/* The decimal text of a physical value times `scale`, exactly, when it is an integer. */
static int scaled_text(const char *text, long long scale, long long *out) {
    long long mant = 0, div = 1;
    int neg = 0, exp10 = 0, frac = 0, digits = 0;
    const char *p = text;
    if (*p == '-') { neg = 1; p++; }
    for (; *p; p++) {
        if (*p >= '0' && *p <= '9') {
            if (++digits > 18) return 0;
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
    mant *= scale;
    for (; exp10 > 0; exp10--) mant *= 10;
    for (; exp10 < 0; exp10++) div *= 10;
    if (mant % div != 0) return 0;
    *out = (neg ? -1 : 1) * (mant / div);
    return 1;
}

#define scaled(ph, scale, out) scaled_into((ph), (scale), (void *)(out), sizeof *(out))
static int scaled_into(const phys_t *ph, long long scale, void *out, size_t size) {
    long long v;
    if (!scaled_text(ph->text, scale, &v)) return 0;
    if (size == sizeof(int32_t)) {
        if (v < INT32_MIN || v > INT32_MAX) return 0;
        *(int32_t *)out = (int32_t)v;
    } else {
        *(int64_t *)out = (int64_t)v;
    }
    return 1;
}

#include "runner_tables.h"

static int hex_bytes(const char *hex, uint8_t *out, size_t cap, size_t *len) {
    size_t n = strlen(hex), i;
    if (n % 2 != 0 || n / 2 > cap) return 0;
    for (i = 0; i < n / 2; i++) {
        unsigned v;
        if (sscanf(hex + 2 * i, "%2x", &v) != 1) return 0;
        out[i] = (uint8_t)v;
    }
    *len = n / 2;
    return 1;
}

int main(int argc, char **argv) {
    static char line[4096];
    static vcase_t vc;
    static vtext_t vt;
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
    while (fgets(line, sizeof line, fh) != NULL) {
        char hex[256], name[64], num[64];
        lineno++;
        line[strcspn(line, "\n")] = '\0';
        if (line[0] == 'C') {
            memset(&vc, 0, sizeof vc);
            vc.line = lineno;
            if (sscanf(line, "C %lu %31s %255s %63s", &vc.frame_id, vc.kind, hex, vc.message) != 4 ||
                !hex_bytes(hex, vc.data, sizeof vc.data, &vc.len)) {
                fprintf(stderr, "line %lu: malformed case\n", lineno);
                return 2;
            }
            in_case = 1;
        } else if (line[0] == 'R' && in_case && vc.nraw < MAX_SIGNALS) {
            if (sscanf(line, "R %63s %lld", vc.raw_names[vc.nraw], &vc.raw_values[vc.nraw]) == 2) vc.nraw++;
        } else if (line[0] == 'P' && in_case && vc.nphys < MAX_SIGNALS) {
            if (sscanf(line, "P %63s %63s", name, num) == 2) {
                phys_t *ph = &vc.phys[vc.nphys++];
                strcpy(ph->name, name);
                strcpy(ph->text, num);
                ph->value = strtod(num, NULL);
            }
        } else if (line[0] == 'E' && in_case) {
            const runner_msg_t msg = runner_lookup_id((uint32_t)vc.frame_id);
            const runner_msg_info_t *info = runner_msg_info(msg);
            cases++;
            in_case = 0;
            if (info == NULL || strcmp(info->name, vc.message) != 0) {
                failures += (unsigned long)fail(&vc, "frame ID 0x%08lX is not message %s", vc.frame_id, vc.message);
            } else {
                failures += (unsigned long)CHECKS[msg](&vc);
            }
        } else if (line[0] == 'V') {
            char *tok, *save = NULL;
            int field = 0;
            memset(&vt, 0, sizeof vt);
            vt.line = lineno;
            for (tok = strtok_r(line + 2, " ", &save); tok != NULL; tok = strtok_r(NULL, " ", &save), field++) {
                size_t n;
                if (field == 0) vt.frame_id = strtoul(tok, NULL, 10);
                else if (field == 1) {
                    uint8_t tb[255];
                    if (strcmp(tok, "-") != 0 && hex_bytes(tok, tb, sizeof tb, &n)) memcpy(vt.text, tb, n);
                } else if (field == 2) vt.nframes = atoi(tok);
                else if (field - 3 < 8) (void)hex_bytes(tok, vt.frames[field - 3], 8, &n);
            }
            texts++;
            failures += (unsigned long)check_text(&vt);
        }
    }
    fclose(fh);
    printf("c runner: %lu cases, %lu multi-frame texts checked, %lu mismatches\n", cases, texts, failures);
    return failures == 0 && cases > 0 ? 0 : 1;
}
