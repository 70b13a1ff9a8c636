/* edges.c: rt-edges, how few points adaptive subsampling could trace: the pixels its split criteria must see on a frame traced in full. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "platform.h"
#include "rt_local.h"
#include "scn_parse.h"

int app_main(int argc, char **argv)
{
    const char *ed_name = plat_program();
    cli_opts c = cli_defaults(CLI_EDGES);
    int rc = cli_parse(CLI_EDGES, argc - 1, argv + 1, &c);
    if (rc != 0)
        return rc < 0 ? 0 : rc; /* -1: --help, --version */
    if (!c.scene)
        return cli_error("--scene", "is required: the scene to measure", NULL);
    knobs k = c.k;
    long ms = c.time_ms;
    char time[16];
    snprintf(time, sizeof time, "%ld.%03ld", ms / 1000, ms % 1000);
    static scn_file file;
    char err[640];
    if (scn_load(c.scene, &file, err, sizeof err) != 0) {
        fprintf(stderr, "%s: %s\n", ed_name, err);
        return 2;
    }
    rt_scene scene;
    rt_view view;
    scn_eval(&file.desc, (int32_t)ms, &scene);
    if (!rt_view_ok(&scene.camera)) {
        fprintf(stderr, "%s: %s: at %s s the camera has no view direction\n", ed_name, c.scene,
                time);
        return 2;
    }
    int w = c.width, h = c.height;
    rt_view_init(&view, &scene.camera, w, h);
    rt_view_cull(&view, &scene);
    rt_params p = knobs_params(&k, scene.depth);
    int grid = p.grid;
    rt_sample *s = malloc((size_t)w * h * sizeof *s);
    unsigned char *must = calloc((size_t)w * h, 1);
    if (!s || !must) {
        fprintf(stderr, "%s: out of memory for %dx%d records\n", ed_name, w, h);
        return 1;
    }
    rt_stats st = {0};
    for (int y = 0; y < h; y++)
        for (int i = 0; i < w; i++)
            rt_trace_pixel(&scene, &view, &p, i, y, &st, &s[(long)y * w + i]);
    int thr8 = r_to_byte(p.threshold);
    long edge = 0, need = 0;
    for (int y = 0; y + 1 < h; y++)
        for (int i = 0; i + 1 < w; i++) {
            long o = (long)y * w + i;
            const rt_sample *q[4] = {&s[o], &s[o + 1], &s[o + w], &s[o + w + 1]};
            if (rt_corners_differ(q, thr8) != RT_SPLIT_NONE)
                must[o] = must[o + 1] = must[o + w] = must[o + w + 1] = 1;
        }
    for (int y = 0; y < h; y++)
        for (int i = 0; i < w; i++) {
            long o = (long)y * w + i;
            edge += must[o];
            int corner = (i % grid == 0 || i == w - 1) && (y % grid == 0 || y == h - 1);
            need += must[o] || corner;
        }
    long pixels = (long)w * h;
    printf("scene=%s\nsize=%dx%d\ntime=%s\npixels=%ld\nedge_pixels=%ld\nedge_share=%.4f\n"
           "must_trace=%ld\nbound_x_samples=%.2f\n",
           c.scene, w, h, time, pixels, edge, (double)edge / pixels, need,
           (double)pixels / (double)need);
    free(s);
    free(must);
    return 0;
}
