/* fuzz_scene.c: libFuzzer harness: bytes go to the scene parser; accepted scenes are evaluated along their timeline and rendered small. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "knobs.h"
#include "noise.h"
#include "rt_local.h"
#include "scn.h"
#include "scn_parse.h"

/* The tiny frame every accepted scene is rendered into. */
#define FZ_W 8
#define FZ_H 6

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static scn_file fz_file;
static rt_scene fz_scene;
static uint32_t fz_pixels[FZ_W * FZ_H];
static uint8_t fz_traced[FZ_W * FZ_H];
static rt_sample
    fz_work[2 * 8 + 17 * 17]; /* adaptive working storage: checked against the size asked */
static FILE *fz_null;

/* A broken promise of the code under test: report it and stop, so libFuzzer keeps the input. */
static void fz_fail(const char *what, long a, long b)
{
    fprintf(stderr, "fuzz_scene: %s (%ld, %ld)\n", what, a, b);
    abort();
}

static uint64_t fz_hash(const uint8_t *p, size_t n)
{
    uint64_t h = 14695981039346656037u;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 1099511628211u;
    return h;
}

/* Renders the scene at its current moment with settings picked by bits of h. */
static void fz_render(uint64_t h)
{
    static const int grids[4] = {2, 4, 8, 16};
    static const knobs defaults = KNOBS_DEFAULTS;
    const rt_params d = knobs_params(&defaults, 0);
    rt_params p = {
        .depth = (h & 1) ? fz_scene.depth : (int)((h >> 1) % (RT_MAX_DEPTH + 1)),
        .min_contrib = (h & 16) ? 0 : d.min_contrib,
        .mode = (h & 32)      ? RT_MODE_FULL
            : ((h >> 13) & 1) ? RT_MODE_PROBE
                              : RT_MODE_ADAPTIVE,
        .grid = grids[(h >> 6) & 3],
        .threshold = (h & 256) ? 0 : d.threshold,
        .octaves = (int)((h >> 40) % (RT_NOISE_MAX_OCTAVES + 1)), /* 0: the scene's */
    };
    unsigned long need = rt_render_work_size(&p, FZ_W);
    if (need > sizeof fz_work)
        fz_fail("adaptive working storage larger than expected", (long)need, (long)sizeof fz_work);
    int w = FZ_W - (int)((h >> 9) & 3), hgt = FZ_H - (int)((h >> 11) & 3);
    rt_view v;
    rt_view_init(&v, &fz_scene.camera, w, hgt);
    rt_stats stats = {0};
    memset(fz_traced, 0, sizeof fz_traced);
    rt_render(&fz_scene, &v, &p, fz_pixels, FZ_W, &stats, fz_work, fz_traced);
    for (int y = 0; y < hgt; y++)
        for (int x = 0; x < w; x++)
            if (fz_pixels[y * FZ_W + x] > 0xFFFFFFu)
                fz_fail("pixel out of range", x, y);
    /* The primary rays' tile candidates and the mirror candidates (rt_view_cull) change no
     * pixel: the same frame with them and with every set full (the small spheres rt_view_cull
     * marks, rt_view.small, are the view's in both: they decide splits, not candidates). */
    static uint32_t plain[FZ_W * FZ_H];
    rt_view_cull(&v, &fz_scene);
    rt_view vp = v;
    vp.mirror_plane = -1;
    for (int i = 0; i < RT_VIEW_TILES; i++)
        vp.cull_cols[i] = vp.cull_rows[i] = vp.mirror_cols[i] = vp.mirror_rows[i] = 0xFFFFFFFFu;
    rt_render(&fz_scene, &vp, &p, fz_pixels, FZ_W, &stats, fz_work, fz_traced);
    memcpy(plain, fz_pixels, sizeof plain);
    rt_stats culled = {0};
    rt_render(&fz_scene, &v, &p, fz_pixels, FZ_W, &culled, fz_work, fz_traced);
    for (int y = 0; y < hgt; y++)
        for (int x = 0; x < w; x++)
            if (fz_pixels[y * FZ_W + x] != plain[y * FZ_W + x])
                fz_fail("rt_view_cull changed a pixel", x, y);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[640];
    if (!fz_null && !(fz_null = fopen("/dev/null", "w")))
        fz_fail("cannot open /dev/null", 0, 0);
    if (scn_parse("fuzz.scene", (const char *)data, size, &fz_file, err, sizeof err) != 0) {
        /* a refusal is one line naming the file, line and column */
        if (strncmp(err, "fuzz.scene:", 11) != 0 || strchr(err, '\n') || strlen(err) < 16)
            fz_fail("malformed error message", (long)strlen(err), 0);
        return 0;
    }
    const scn_desc *d = &fz_file.desc;
    uint64_t h = fz_hash(data, size);
    unsigned all = scn_effects_union(d);
    /* Moments: the start, the end, one picked by the input's hash, and each track's keys. */
    int32_t moments[8] = {0, d->duration_ms, (int32_t)(h % ((uint64_t)d->duration_ms + 1))};
    int n = 3;
    for (int t = 0; t < d->ntracks && n < 8; t++)
        moments[n++] = d->keys[d->tracks[t].first + (h >> 20) % d->tracks[t].count].time_ms;
    for (int i = 0; i < n; i++) {
#if FX_COUNT_EVENTS
        fx_events_reset();
#endif
        scn_eval(d, moments[i], &fz_scene);
        /* scn_effects_union promises a superset of every frame's effects (compiled scenes) */
        if (fz_scene.effects & ~all)
            fz_fail("frame effects outside scn_effects_union", (long)fz_scene.effects, (long)all);
        /* a camera whose eye meets the point it looks at is refused by render (rt_view_ok) */
        if ((i == 2 || i == 1) && rt_view_ok(&fz_scene.camera)) {
            if ((h >> 13) & 1)
                rt_scene_force_effects(&fz_scene);
            fz_render(h >> (i == 1 ? 0 : 14));
        }
#if FX_COUNT_EVENTS
        /* an accepted scene never drives the numbers out of range */
        if (fx_event_count[FX_EV_OVERFLOW] || fx_event_count[FX_EV_DOMAIN]) {
            fprintf(stderr, "fuzz_scene: at %ld ms: fx_overflow=%lu fx_domain=%lu\n",
                    (long)moments[i], fx_event_count[FX_EV_OVERFLOW], fx_event_count[FX_EV_DOMAIN]);
            fz_fail("numeric events on an accepted scene", 0, 0);
        }
#endif
    }
    if (scn_write_c(fz_null, d, "scn_fuzz", "fuzz.scene") != 0)
        fz_fail("writing C failed", 0, 0);
    return 0;
}
