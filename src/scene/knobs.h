/* knobs.h: the render settings a command line can change (depth, mode, grid, threshold, min-contrib, octaves, footprint) and their defaults, and the one number syntax of command lines and scene files; integers only, shared by the desktop programs and the boards. */
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

/* The defaults of every program (render, play, the intro players, the boards, rt-edges): the
 * only place they are written. */
#define KNOBS_DEFAULT_GRID 8
#define KNOBS_DEFAULT_THRESHOLD 625   /* 0.0625 */
#define KNOBS_DEFAULT_MIN_CONTRIB 100 /* 0.01 */
#define KNOBS_DEFAULTS \
    { \
        .depth = -1, .mode = RT_MODE_ADAPTIVE, .grid = KNOBS_DEFAULT_GRID, \
        .threshold = KNOBS_DEFAULT_THRESHOLD, .min_contrib = KNOBS_DEFAULT_MIN_CONTRIB, \
        .octaves = 0, .footprint = 1 \
    }

/* Which setting `opt` names: 0 .. KNOBS_COUNT - 1 (one bit each for "given twice"), or -1. */
#define KNOBS_COUNT 7
int knobs_index(const char *opt);

/* If `opt` is a setting's option, parses its value `val` into *k and returns 1, or returns -1
 * and points *expected at what the value should be (for the one-line error); returns 0 for
 * any other option. */
int knobs_parse(knobs *k, const char *opt, const char *val, const char **expected);

/* The rt_params of the settings; a depth of -1 becomes scene_depth. */
rt_params knobs_params(const knobs *k, int scene_depth);

/* ---- the numbers of command lines and scene files (one syntax, no libc, no floating point) ---
 * A number is an optional '-', digits, and optionally '.' and more digits: no '+', no
 * exponent, no leading or trailing '.', no spaces. */

/* What knobs_scan read: |value| = whole + frac / 10^frac_digits (the first 9 decimals; more
 * are counted in decimals but dropped). whole saturates at KNOBS_BIG. */
#define KNOBS_BIG 1000000000L
typedef struct knobs_num {
    int neg;
    long whole, frac, frac_pow10; /* frac_pow10 = 10^(decimals kept) */
    int decimals;                 /* decimals written */
} knobs_num;

/* Reads s[0 .. len) (len < 0: up to the terminating NUL). Returns 0, or -1 when it does not
 * have the syntax of a number. */
int knobs_scan(const char *s, int len, knobs_num *n);

enum knobs_num_result {
    KNOBS_NUM_OK,
    KNOBS_NUM_SYNTAX,   /* not a number */
    KNOBS_NUM_DECIMALS, /* more decimals than allowed (a whole number with a '.') */
    KNOBS_NUM_RANGE     /* a number, outside [lo, hi] */
};

/* A number of s[0 .. len) (len < 0: NUL-terminated) with at most `decimals` decimals
 * (0: a whole number), as an integer in units of 10^-decimals, in [lo, hi] (|lo|, |hi| below
 * KNOBS_BIG). Returns an enum knobs_num_result; *out is set only with KNOBS_NUM_OK. */
int knobs_number(const char *s, int len, int decimals, long lo, long hi, long *out);

#endif
