/* frame.h: rendering a frame on several threads (the desktop programs; see frame.c). */
#ifndef FIXRAY_FRAME_H
#define FIXRAY_FRAME_H

#include <stddef.h>

#include "platform.h"
#include "rt.h"

/* Working storage for rendering frames up to `width` pixels wide on `threads` threads. */
typedef struct frame_ctx {
    int threads;
    unsigned long work_bytes;
    void *work[PLAT_MAX_THREADS];
} frame_ctx;

/* Counters of rt_stats summed over threads and frames, 64 bits each: n[i] sums the i-th
 * uint32_t of rt_stats (every field of rt_stats is a uint32_t counter or an array of them). */
#define FRAME_NSTATS (sizeof(rt_stats) / sizeof(uint32_t))
typedef struct frame_sums {
    unsigned long long n[FRAME_NSTATS];
} frame_sums;

/* The sum of counter `field` of rt_stats (an array's element i: FRAME_SUM(t, squares, i)). */
#define FRAME_SUM(t, field, i) ((t)->n[offsetof(rt_stats, field) / sizeof(uint32_t) + (i)])

/* Adds every counter of s to *t. */
void frame_sums_add(frame_sums *t, const rt_stats *s);

/* Sets up fc for `threads` threads (1..PLAT_MAX_THREADS) and frames `width` wide, any grid.
 * Returns 0, or -1 when out of memory. */
int frame_init(frame_ctx *fc, int threads, int width);

void frame_free(frame_ctx *fc);

/* rt_render on fc's threads: the same bytes whatever the number of threads. The rays counted in
 * *sums (added to) include the corner rows that neighbouring bands both trace. */
void frame_render(const frame_ctx *fc, const rt_scene *s, const rt_view *v, const rt_params *p,
                  uint32_t *pixels, int stride, frame_sums *sums, uint8_t *traced);

/* Paints every pixel of a width x height frame whose byte in `traced` (width per row) is set:
 * white the points shaded in full (RT_TRACED_FULL), else FRAME_LOCAL_COLOR those shaded with
 * their local part taken from their square's corners (RT_TRACED_LOCAL), else FRAME_PROBE_COLOR
 * the points only probed (probe mode) (--show-samples, the player's S key). */
#define FRAME_PROBE_COLOR 0xFF00FFu
#define FRAME_LOCAL_COLOR 0x00FFFFu
void frame_mark_traced(uint32_t *pixels, int stride, int width, int height, const uint8_t *traced);

#endif
