/* knobs.c: the render settings of a command line as rt_params, and the number syntax of command lines and scene files, with integers only and no libc (rt-float, rt-fixed, rt-edges and the boards alike). */
#include <stddef.h>

#include "knobs.h"
#include "noise.h"

/* No libc here: the ARM image links none of its string functions. */
static int knobs_eq(const char *a, const char *b)
{
    while (*a && *a == *b)
        a++, b++;
    return *a == *b;
}

int knobs_scan(const char *s, int len, knobs_num *n)
{
    const char *e = s;
    if (len < 0)
        while (*e)
            e++;
    else
        e = s + len;
    int digits = 0;
    *n = (knobs_num){.frac_pow10 = 1};
    if (s < e && *s == '-') {
        n->neg = 1;
        s++;
    }
    for (; s < e && *s >= '0' && *s <= '9'; s++, digits++)
        n->whole = n->whole < KNOBS_BIG / 10 ? n->whole * 10 + (*s - '0') : KNOBS_BIG;
    if (s < e && *s == '.') {
        for (s++; s < e && *s >= '0' && *s <= '9'; s++, n->decimals++)
            if (n->decimals < 9) {
                n->frac = n->frac * 10 + (*s - '0');
                n->frac_pow10 *= 10;
            }
        if (n->decimals == 0)
            return -1;
    }
    return digits > 0 && s == e ? 0 : -1;
}

int knobs_number(const char *s, int len, int decimals, long lo, long hi, long *out)
{
    knobs_num n;
    if (knobs_scan(s, len, &n) != 0)
        return KNOBS_NUM_SYNTAX;
    if (n.decimals > decimals)
        return KNOBS_NUM_DECIMALS;
    long scale = 1;
    for (int i = 0; i < decimals; i++)
        scale *= 10;
    long bound = (hi > -lo ? hi : -lo) / scale; /* beyond it: out of range, before overflow */
    if (n.whole > bound)
        return KNOBS_NUM_RANGE;
    long frac = n.frac;
    for (int i = n.decimals; i < decimals; i++)
        frac *= 10;
    long v = n.whole * scale + frac;
    v = n.neg ? -v : v;
    if (v < lo || v > hi)
        return KNOBS_NUM_RANGE;
    *out = v;
    return KNOBS_NUM_OK;
}

/* The numeric settings: option, what its value must be, bounds (in 1/10^decimals), and where
 * it goes. The messages name the limits. */
_Static_assert(RT_MAX_DEPTH == 8 && RT_NOISE_MAX_OCTAVES == 8 && RT_GRID_MAX == 16 &&
                   KNOBS_SCALE == 10000,
               "knobs_table's messages and bounds state the limits");
static const struct knobs_opt {
    const char *name, *expected;
    int32_t lo, hi;
    int decimals; /* 0 or KNOBS_DECIMALS */
    size_t field; /* offset of an int32_t in knobs */
} knobs_table[] = {
    {"--depth", "expected a recursion limit in 0..8", 0, RT_MAX_DEPTH, 0, offsetof(knobs, depth)},
    {"--grid", "expected a square size of 2, 4, 8 or 16", 2, RT_GRID_MAX, 0, offsetof(knobs, grid)},
    {"--threshold", "expected a number in 0..1 with at most 4 decimals", 0, KNOBS_SCALE,
     KNOBS_DECIMALS, offsetof(knobs, threshold)},
    {"--min-contrib", "expected a number in 0..1 with at most 4 decimals", 0, KNOBS_SCALE,
     KNOBS_DECIMALS, offsetof(knobs, min_contrib)},
    {"--octaves", "expected a number of noise octaves in 1..8", 1, RT_NOISE_MAX_OCTAVES, 0,
     offsetof(knobs, octaves)},
};
#define KNOBS_NOPTS (int)(sizeof knobs_table / sizeof *knobs_table)

_Static_assert(KNOBS_NOPTS + 2 == KNOBS_COUNT, "KNOBS_COUNT: the table, --mode and --footprint");

/* Index of option opt in knobs_table, KNOBS_NOPTS for --mode, KNOBS_NOPTS + 1 for
 * --footprint, -1 for any other. */
static int knobs_find(const char *opt)
{
    for (int i = 0; i < KNOBS_NOPTS; i++)
        if (knobs_eq(opt, knobs_table[i].name))
            return i;
    if (knobs_eq(opt, "--footprint"))
        return KNOBS_NOPTS + 1;
    return knobs_eq(opt, "--mode") ? KNOBS_NOPTS : -1;
}

int knobs_index(const char *opt) { return knobs_find(opt); }

int knobs_parse(knobs *k, const char *opt, const char *val, const char **expected)
{
    int i = knobs_find(opt);
    long n;
    if (i < 0)
        return 0;
    if (i == KNOBS_NOPTS) {
        *expected = "expected full, adaptive or probe";
        if (knobs_eq(val, "full"))
            k->mode = RT_MODE_FULL;
        else if (knobs_eq(val, "adaptive"))
            k->mode = RT_MODE_ADAPTIVE;
        else if (knobs_eq(val, "probe"))
            k->mode = RT_MODE_PROBE;
        else
            return -1;
        return 1;
    }
    if (i == KNOBS_NOPTS + 1) {
        *expected = "expected on or off";
        if (knobs_eq(val, "on"))
            k->footprint = 1;
        else if (knobs_eq(val, "off"))
            k->footprint = 0;
        else
            return -1;
        return 1;
    }
    const struct knobs_opt *o = &knobs_table[i];
    *expected = o->expected;
    /* grid: a power of two */
    if (knobs_number(val, -1, o->decimals, o->lo, o->hi, &n) != KNOBS_NUM_OK ||
        (o->field == offsetof(knobs, grid) && (n & (n - 1)) != 0))
        return -1;
    *(int32_t *)(void *)((char *)k + o->field) = (int32_t)n;
    return 1;
}
rt_params knobs_params(const knobs *k, int scene_depth)
{
    return (rt_params){.depth = k->depth >= 0 ? k->depth : scene_depth,
                       .min_contrib = r_from_ratio(k->min_contrib, KNOBS_SCALE),
                       .mode = k->mode,
                       .grid = k->grid,
                       .threshold = r_from_ratio(k->threshold, KNOBS_SCALE),
                       .octaves = k->octaves,
                       .footprint = k->footprint};
}
