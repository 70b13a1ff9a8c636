/* knobs.c: parses the render settings of a command line into rt_params with integers only (rt-float, rt-fixed and the ARM intro alike). */
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

int knobs_int(const char *s, const char **end, long lo, long hi, long *out)
{
    long v = 0;
    const char *p = s;
    if (*p < '0' || *p > '9')
        return -1;
    while (*p >= '0' && *p <= '9') {
        v = v * 10 + (*p - '0');
        if (v > hi)
            return -1;
        p++;
    }
    if (v < lo)
        return -1;
    if (end)
        *end = p;
    else if (*p)
        return -1;
    *out = v;
    return 0;
}

int knobs_decimal(const char *s, int decimals, long max, long *out)
{
    const char *p;
    long whole, frac = 0, scale = 1;
    for (int i = 0; i < decimals; i++)
        scale *= 10;
    if (knobs_int(s, &p, 0, max / scale, &whole) != 0)
        return -1;
    if (*p == '.') {
        int digits = 0;
        p++;
        while (*p >= '0' && *p <= '9' && digits < decimals) {
            frac = frac * 10 + (*p - '0');
            digits++;
            p++;
        }
        if (digits == 0 || *p)
            return -1;
        while (digits++ < decimals)
            frac *= 10;
    } else if (*p) {
        return -1;
    }
    long total = whole * scale + frac;
    if (total > max)
        return -1;
    *out = total;
    return 0;
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

/* Index of option opt in knobs_table, KNOBS_NOPTS for --mode, -1 for any other. */
static int knobs_find(const char *opt)
{
    for (int i = 0; i < KNOBS_NOPTS; i++)
        if (knobs_eq(opt, knobs_table[i].name))
            return i;
    return knobs_eq(opt, "--mode") ? KNOBS_NOPTS : -1;
}

int knobs_is_option(const char *opt) { return knobs_find(opt) >= 0; }

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
    const struct knobs_opt *o = &knobs_table[i];
    *expected = o->expected;
    /* grid: a power of two */
    if (knobs_decimal(val, o->decimals, o->hi, &n) != 0 || n < o->lo ||
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
                       .octaves = k->octaves};
}
