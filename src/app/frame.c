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
    void *edges; /* the corner rows on the bands' edges (rt_render_edge), or NULL */
    atomic_int next, next_edge;
    rt_stats stats[PLAT_MAX_THREADS];
} frame_job;

static void frame_worker(void *ctx, int worker)
{
    frame_job *j = ctx;
    for (;;) {
        int b = atomic_fetch_add(&j->next, 1);
        if (b >= j->nbands)
            return;
        if (j->edges)
            rt_render_band_edges(j->scene, j->view, j->params, j->pixels, j->stride,
                                 &j->stats[worker], j->fc->work[worker], j->edges, j->traced, b,
                                 j->nbands);
        else
            rt_render_band(j->scene, j->view, j->params, j->pixels, j->stride, &j->stats[worker],
                           j->fc->work[worker], j->traced, b, j->nbands);
    }
}

/* The corner rows on the bands' edges, each traced once, before the bands. */
static void frame_edge_worker(void *ctx, int worker)
{
    frame_job *j = ctx;
    for (;;) {
        int e = atomic_fetch_add(&j->next_edge, 1);
        if (e > j->nbands)
            return;
        rt_render_edge(j->scene, j->view, j->params, &j->stats[worker], j->edges, j->traced, e,
                       j->nbands);
    }
}

_Static_assert(sizeof(rt_stats) % sizeof(uint32_t) == 0, "rt_stats: uint32_t counters only");

void frame_sums_add(frame_sums *t, const rt_stats *s)
{
    uint32_t c[FRAME_NSTATS];
    memcpy(c, s, sizeof c);
    for (size_t i = 0; i < FRAME_NSTATS; i++)
        t->n[i] += c[i];
}

void frame_mark_traced(uint32_t *pixels, int stride, int width, int height, const uint8_t *traced)
{
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            const uint8_t t = traced[(long)y * width + x];
            if (t)
                pixels[(long)y * stride + x] = t & RT_TRACED_FULL ? 0xFFFFFFu
                    : t & RT_TRACED_LOCAL                         ? FRAME_LOCAL_COLOR
                                                                  : FRAME_PROBE_COLOR;
        }
}

void frame_render(const frame_ctx *fc, const rt_scene *s, const rt_view *v, const rt_params *p,
                  uint32_t *pixels, int stride, frame_sums *sums, uint8_t *traced)
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
     * that a thread that drew easy bands takes more; the corner rows on the bands' edges are
     * traced first, once each (rt_render_edge), so the frame traces the points rt_render
     * traces, each once, on any number of threads. */
    int count = rt_render_band_count(p, v->height);
    j.nbands = fc->threads == 1 ? 1 : count < 8 * fc->threads ? count : 8 * fc->threads;
    atomic_init(&j.next, 0);
    atomic_init(&j.next_edge, 0);
    if (traced)
        memset(traced, 0, (size_t)v->width * (size_t)v->height);
    const unsigned long edge_bytes = j.nbands > 1 ? rt_render_edge_size(p, v->width, j.nbands) : 0;
    j.edges = edge_bytes ? malloc(edge_bytes) : NULL; /* none: each band traces its edges */
    if (j.edges)
        plat_parallel(fc->threads, frame_edge_worker, &j);
    plat_parallel(fc->threads, frame_worker, &j);
    free(j.edges);
    for (int w = 0; w < fc->threads; w++)
        frame_sums_add(sums, &j.stats[w]);
}
