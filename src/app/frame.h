/* frame.h: rendering a frame on several threads (the desktop programs; see frame.c). */
#ifndef FIXRAY_FRAME_H
#define FIXRAY_FRAME_H

#include "platform.h"
#include "rt.h"

/* Working storage for rendering frames up to `width` pixels wide on `threads` threads. */
typedef struct frame_ctx {
    int threads;
    unsigned long work_bytes;
    void *work[PLAT_MAX_THREADS];
} frame_ctx;

/* Sets up fc for `threads` threads (1..PLAT_MAX_THREADS) and frames `width` wide, any grid.
 * Returns 0, or -1 when out of memory. */
int frame_init(frame_ctx *fc, int threads, int width);

void frame_free(frame_ctx *fc);

/* rt_render on fc's threads: the same bytes whatever the number of threads. The rays counted in
 * *stats (added to) include the corner rows that neighbouring bands both trace. */
void frame_render(const frame_ctx *fc, const rt_scene *s, const rt_view *v, const rt_params *p,
                  uint32_t *pixels, int stride, rt_stats *stats, uint8_t *traced);

/* Paints every pixel of a width x height frame whose byte in `traced` (width per row) is set:
 * white the points shaded in full (1), FRAME_PROBE_COLOR the points only probed (2, probe
 * mode) (--show-samples, the player's S key). */
#define FRAME_PROBE_COLOR 0xFF00FFu
void frame_mark_traced(uint32_t *pixels, int stride, int width, int height, const uint8_t *traced);

#endif
