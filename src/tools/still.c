/* still.c: rt-still, a minimal program around a scene compiled in at build time: renders one frame as PPM on standard output. */
#include <stdio.h>
#include <stdlib.h>

#include "knobs.h"
#include "rt.h"
#include "scn.h"

/* The scene, from rt-scenec; the tracer is built with its RT_COMPILED_EFFECTS. */
extern const scn_desc scn_compiled;

/* A whole number in [lo, hi], or -1. */
static long still_arg(const char *s, long lo, long hi)
{
    long v;
    return knobs_number(s, -1, 0, lo, hi, &v) == KNOBS_NUM_OK ? v : -1;
}

int main(int argc, char **argv)
{
    long ms = argc == 4 ? still_arg(argv[1], 0, scn_compiled.duration_ms) : -1;
    long w = argc == 4 ? still_arg(argv[2], 1, 4096) : -1;
    long h = argc == 4 ? still_arg(argv[3], 1, 4096) : -1;
    if (ms < 0 || w < 0 || h < 0) {
        fprintf(
            stderr,
            "usage: %s TIME_MS WIDTH HEIGHT >frame.ppm  (TIME_MS in 0..%ld, sides "
            "1..4096): one frame of the compiled-in scene, rendered as `render` does by default\n",
            argv[0], (long)scn_compiled.duration_ms);
        return 2;
    }
    static rt_scene scene;
    scn_eval(&scn_compiled, (int32_t)ms, &scene);
    static const knobs defaults = KNOBS_DEFAULTS; /* render's */
    rt_params p = knobs_params(&defaults, scene.depth);
    rt_view v;
    rt_view_init(&v, &scene.camera, (int)w, (int)h);
    rt_view_cull(&v, &scene);
    uint32_t *pixels = malloc((size_t)w * (size_t)h * sizeof *pixels);
    void *work = malloc(rt_render_work_size(&p, (int)w));
    if (!pixels || !work) {
        fprintf(stderr, "%s: out of memory\n", argv[0]);
        return 1;
    }
    rt_stats stats = {0};
    rt_render(&scene, &v, &p, pixels, (int)w, &stats, work, NULL);
    printf("P6\n%ld %ld\n255\n", w, h);
    for (long i = 0; i < w * h; i++) {
        unsigned char rgb[3] = {(unsigned char)(pixels[i] >> 16), (unsigned char)(pixels[i] >> 8),
                                (unsigned char)pixels[i]};
        fwrite(rgb, 1, 3, stdout);
    }
    free(pixels);
    free(work);
    return fflush(stdout) == 0 ? 0 : 1;
}
