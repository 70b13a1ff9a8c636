/* knobs.h: the render settings a command line can change (depth, mode, grid, threshold, min-contrib, octaves, footprint), parsed without floating point; shared by rt-float/rt-fixed and the ARM intro. */
#ifndef FIXRAY_KNOBS_H
#define FIXRAY_KNOBS_H

#include "rt.h"

/* --threshold and --min-contrib are kept in units of 1/KNOBS_SCALE (at most 4 decimals), so
 * both builds start from the same integers. */
#define KNOBS_DECIMALS 4
#define KNOBS_SCALE 10000

typedef struct knobs {
    int32_t depth;                  /* --depth: recursion limit, -1 = the scene's */
    int32_t mode;                   /* --mode: enum rt_mode */
    int32_t grid;                   /* --grid: 2, 4, 8 or 16 */
    int32_t threshold, min_contrib; /* --threshold, --min-contrib, in 1/KNOBS_SCALE */
    int32_t octaves;                /* --octaves: cap on noise octaves, 0 = the scene's */
    int32_t footprint;              /* --footprint on|off: 1 = octaves by pixel footprint */
} knobs;

/* The defaults of `render` (README): RT_DEFAULT_THRESHOLD and RT_DEFAULT_MIN_CONTRIB. */
#define KNOBS_DEFAULTS \
    { \
        .depth = -1, .mode = RT_MODE_ADAPTIVE, .grid = RT_DEFAULT_GRID, .threshold = 625, \
        .min_contrib = 100, .octaves = 0, .footprint = 1 \
    }

/* 1 when `opt` is one of the settings' options (each takes a value), else 0. */
int knobs_is_option(const char *opt);

/* If `opt` is a setting's option, parses its value `val` into *k and returns 1, or returns -1
 * and points *expected at what the value should be (for the one-line error); returns 0 for
 * any other option. */
int knobs_parse(knobs *k, const char *opt, const char *val, const char **expected);

/* The rt_params of the settings; a depth of -1 becomes scene_depth. */
rt_params knobs_params(const knobs *k, int scene_depth);

/* A decimal integer in [lo, hi]: all of s, or when `end` is not NULL its leading digits (then
 * *end points past them). Returns 0, or -1 when s is not such a number. */
int knobs_int(const char *s, const char **end, long lo, long hi, long *out);

/* A decimal number with at most `decimals` decimals, in units of 10^-decimals, at most `max`
 * such units. Returns 0, or -1. */
int knobs_decimal(const char *s, int decimals, long max, long *out);

#endif
