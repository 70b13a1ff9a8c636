/* fuzz_knobs.c: libFuzzer harness: the render settings' parser (knobs.c, the desktop programs' and the boards' settings) and its number syntax, against a reference reading of the digits. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "knobs.h"
#include "noise.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void fk_fail(const char *what, const char *s, long a, long b)
{
    fprintf(stderr, "fuzz_knobs: %s: '%s' (%ld, %ld)\n", what, s, a, b);
    abort();
}

/* The number syntax of knobs.h read independently: optional '-', digits, optionally '.' and
 * digits. Returns 0 and the value in units of 10^-decimals when it has that syntax and at most
 * `decimals` decimals; -1 for another syntax, -2 for more decimals, -3 for a value beyond any
 * bound (2^40). */
static int fk_reference(const char *s, int decimals, long long *out)
{
    int neg = *s == '-', digits = 0, frac = 0, big = 0;
    long long v = 0;
    s += neg;
    for (; *s >= '0' && *s <= '9'; s++, digits++)
        if (!big && (v = v * 10 + (*s - '0')) > (1LL << 40))
            big = 1;
    if (!digits)
        return -1;
    if (*s == '.') {
        for (s++; *s >= '0' && *s <= '9'; s++, frac++)
            if (!big && frac < decimals)
                v = v * 10 + (*s - '0');
        if (!frac)
            return -1;
    }
    if (*s)
        return -1;
    if (frac > decimals)
        return -2;
    if (big)
        return -3;
    for (int i = frac; i < decimals; i++)
        v *= 10;
    *out = neg ? -v : v;
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 3 || size > 256)
        return 0;
    char s[260];
    memcpy(s, data + 2, size - 2);
    s[size - 2] = 0;
    if (strlen(s) != size - 2)
        return 0; /* command-line words hold no NUL */

    /* knobs_number with bounds and decimals from the first two bytes */
    static const long bounds[8] = {0, 1, 8, 16, 255, 3600000, 999999999, -999999999};
    int decimals = data[0] % 6;
    long lo = bounds[data[1] & 7], hi = bounds[(data[1] >> 3) & 7];
    if (lo > hi) {
        long t = lo;
        lo = hi;
        hi = t;
    }
    long out = 12345;
    int r = knobs_number(s, -1, decimals, lo, hi, &out);
    long long ref = 0;
    int rr = fk_reference(s, decimals, &ref);
    if (r == KNOBS_NUM_OK) {
        if (out < lo || out > hi)
            fk_fail("knobs_number out of its bounds", s, out, decimals);
        if (rr != 0 || ref != out)
            fk_fail("knobs_number differs from the reference", s, out, (long)ref);
    } else {
        if (out != 12345)
            fk_fail("knobs_number set *out on a refusal", s, out, r);
        if (r == KNOBS_NUM_SYNTAX && rr != -1)
            fk_fail("knobs_number refused the syntax of a number", s, rr, decimals);
        if (r == KNOBS_NUM_DECIMALS && rr != -2)
            fk_fail("knobs_number counted decimals the reference does not", s, rr, decimals);
        if (r == KNOBS_NUM_RANGE && !(rr == -3 || (rr == 0 && (ref < lo || ref > hi))))
            fk_fail("knobs_number refused a number within its bounds", s, (long)ref, rr);
        if (rr == 0 && ref >= lo && ref <= hi)
            fk_fail("knobs_number refused what the reference accepts", s, (long)ref, r);
    }

    /* a setting: the words `OPT VALUE`, split at the first blank (as --opt=value and the
     * boards' --opt value reach knobs_parse) */
    char *sp = strchr(s, ' ');
    if (!sp)
        return 0;
    *sp = 0;
    const char *opt = s, *val = sp + 1;
    static const knobs defaults = KNOBS_DEFAULTS;
    knobs k = defaults, before = defaults;
    const char *expected = NULL;
    int p = knobs_parse(&k, opt, val, &expected);
    int idx = knobs_index(opt);
    if ((p == 0) != (idx < 0) || idx >= KNOBS_COUNT)
        fk_fail("knobs_parse and knobs_index disagree", opt, p, idx);
    if (p <= 0 && memcmp(&k, &before, sizeof k) != 0)
        fk_fail("a refused setting changed the settings", opt, p, 0);
    if (p < 0 && (!expected || strncmp(expected, "expected ", 9) != 0 || strchr(expected, '\n')))
        fk_fail("a refusal without its one-line 'expected ...'", opt, p, 0);
    if (p == 1) {
        int changed = 0;
        const int32_t *a = &k.depth, *b = &before.depth;
        for (size_t i = 0; i < sizeof k / sizeof(int32_t); i++)
            changed += a[i] != b[i];
        if (changed > 1)
            fk_fail("one setting changed more than one field", opt, changed, 0);
        if (k.depth < -1 || k.depth > RT_MAX_DEPTH || k.octaves < 0 ||
            k.octaves > RT_NOISE_MAX_OCTAVES || k.threshold < 0 || k.threshold > KNOBS_SCALE ||
            k.min_contrib < 0 || k.min_contrib > KNOBS_SCALE ||
            (k.footprint != 0 && k.footprint != 1) ||
            (k.grid != 2 && k.grid != 4 && k.grid != 8 && k.grid != 16) ||
            (k.mode != RT_MODE_FULL && k.mode != RT_MODE_ADAPTIVE && k.mode != RT_MODE_PROBE))
            fk_fail("an accepted setting out of range", opt, k.depth, k.grid);
        rt_params prm = knobs_params(&k, 5);
        if (prm.depth < 0 || prm.depth > RT_MAX_DEPTH)
            fk_fail("knobs_params' depth", opt, prm.depth, 0);
    }
    return 0;
}
