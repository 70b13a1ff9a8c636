/* frame.c: renders frames on several threads: horizontal bands handed out to the platform's workers, each with its own working storage and counters. */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "frame.h"

int frame_init(frame_ctx *fc, int threads, int width)
{
    memset(fc, 0, sizeof *fc);
    fc->threads = threads < 1 ? 1 : threads > PLAT_MAX_THREADS ? PLAT_MAX_THREADS : threads;
    /* Enough for any grid, so that the grid can change between frames. */
    for (int g = 2; g <= RT_GRID_MAX; g *= 2) {
        rt_params p = {.mode = RT_MODE_ADAPTIVE, .grid = g};
        unsigned long n = rt_render_work_size(&p, width);
        fc->work_bytes = n > fc->work_bytes ? n : fc->work_bytes;
    }
    for (int i = 0; i < fc->threads; i++) {
        fc->work[i] = malloc(fc->work_bytes);
        if (!fc->work[i]) {
            frame_free(fc);
            return -1;
        }
    }
    return 0;
}

void frame_free(frame_ctx *fc)
{
    for (int i = 0; i < PLAT_MAX_THREADS; i++) {
        free(fc->work[i]);
        fc->work[i] = NULL;
    }
}

typedef struct frame_job {
    const frame_ctx *fc;
    const rt_scene *scene;
    const rt_view *view;
    const rt_params *params;
    uint32_t *pixels;
    int stride;
    uint8_t *traced;
    int nbands;
    atomic_int next;
    rt_stats stats[PLAT_MAX_THREADS];
} frame_job;

static void frame_worker(void *ctx, int worker)
{
    frame_job *j = ctx;
    for (;;) {
        int b = atomic_fetch_add(&j->next, 1);
        if (b >= j->nbands)
            return;
        rt_render_band(j->scene, j->view, j->params, j->pixels, j->stride, &j->stats[worker],
                       j->fc->work[worker], j->traced, b, j->nbands);
    }
}

void frame_mark_traced(uint32_t *pixels, int stride, int width, int height, const uint8_t *traced)
{
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++)
            if (traced[(long)y * width + x])
                pixels[(long)y * stride + x] =
                    !RT_COMPILED_PROBE || traced[(long)y * width + x] == 1 ? 0xFFFFFFu
                                                                           : FRAME_PROBE_COLOR;
}

void frame_render(const frame_ctx *fc, const rt_scene *s, const rt_view *v, const rt_params *p,
                  uint32_t *pixels, int stride, rt_stats *stats, uint8_t *traced)
{
    static frame_job j; /* one frame at a time; too big for the stack */
    memset(&j, 0, sizeof j);
    j.fc = fc;
    j.scene = s;
    j.view = v;
    j.params = p;
    j.pixels = pixels;
    j.stride = stride;
    j.traced = traced;
    /* One band on one thread: exactly rt_render. Otherwise about eight bands per thread, so
     * that a thread that drew easy bands takes more; each band traces its top corner row
     * again (about 1.7% more points at 640x480 on two threads). */
    int count = rt_render_band_count(p, v->height);
    j.nbands = fc->threads == 1 ? 1 : count < 8 * fc->threads ? count : 8 * fc->threads;
    atomic_init(&j.next, 0);
    if (traced)
        memset(traced, 0, (size_t)v->width * (size_t)v->height);
    plat_parallel(fc->threads, frame_worker, &j);
    for (int w = 0; w < fc->threads; w++) {
        const rt_stats *t = &j.stats[w];
        stats->rays_primary += t->rays_primary;
        stats->rays_shadow += t->rays_shadow;
        stats->rays_reflect += t->rays_reflect;
        stats->rays_refract += t->rays_refract;
        stats->shadow_tests += t->shadow_tests;
        stats->noise_octaves += t->noise_octaves;
        for (int l = 0; l < RT_GRID_LEVELS; l++) {
            stats->squares[l] += t->squares[l];
            stats->split[l] += t->split[l];
        }
        for (int r = 0; r < 5; r++)
            stats->split_by[r] += t->split_by[r];
        stats->probes += t->probes;
        stats->probe_shadow += t->probe_shadow;
        stats->probe_secondary += t->probe_secondary;
    }
}
