/* edges.c: rt-edges, how few points adaptive subsampling could trace: the pixels its split criteria must see on a frame traced in full. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rt.h"
#include "scn_parse.h"

static const char *ed_name = "rt-edges";

static void ed_usage(FILE *f)
{
    fprintf(f,
            "usage: %s SCENE WxH SECONDS [--grid N] [--threshold X]\n"
            "  Traces every pixel of the scene at that moment (float, default depth and\n"
            "  --min-contrib) and counts the pixels that are a corner of some 1x1 cell whose four\n"
            "  corners the split criteria tell apart (object, light state, secondary objects,\n"
            "  contribution beyond --threshold, default 0.0625). Adaptive subsampling must trace\n"
            "  each of them, besides the --grid corners (default 8), to resolve every such edge to\n"
            "  the pixel: pixels / that count bounds its x_samples. Prints key=value lines.\n",
            ed_name);
}

/* A whole number in [lo, hi] from s, or -1. */
static long ed_int(const char *s, long lo, long hi)
{
    char *end;
    long v = strtol(s, &end, 10);
    return end != s && *end == 0 && v >= lo && v <= hi ? v : -1;
}

int main(int argc, char **argv)
{
    const char *pos[3] = {0};
    int npos = 0, grid = 8;
    double thr = 0.0625;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            ed_usage(stdout);
            return 0;
        } else if (!strcmp(a, "--grid") || !strcmp(a, "--threshold")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "%s: %s: needs a value\n", ed_name, a);
                return 2;
            }
            const char *v = argv[++i];
            char *end;
            if (!strcmp(a, "--grid")) {
                grid = (int)ed_int(v, 2, RT_GRID_MAX);
                if (grid != 2 && grid != 4 && grid != 8 && grid != 16) {
                    fprintf(stderr, "%s: --grid: want 2, 4, 8 or 16, got '%s'\n", ed_name, v);
                    return 2;
                }
            } else if (thr = strtod(v, &end), end == v || *end || !(thr >= 0 && thr <= 1)) {
                fprintf(stderr, "%s: --threshold: want a number in 0..1, got '%s'\n", ed_name, v);
                return 2;
            }
        } else if (a[0] == '-' && a[1] != 0) {
            fprintf(stderr, "%s: unknown option '%s' (see %s --help)\n", ed_name, a, ed_name);
            return 2;
        } else if (npos < 3) {
            pos[npos++] = a;
        } else {
            fprintf(stderr, "%s: one scene, one size and one time, not '%s'\n", ed_name, a);
            return 2;
        }
    }
    if (npos != 3) {
        fprintf(stderr, "%s: want SCENE WxH SECONDS (see %s --help)\n", ed_name, ed_name);
        return 2;
    }
    int w = 0, h = 0;
    char x = 0, tail = 0;
    if (sscanf(pos[1], "%d%c%d%c", &w, &x, &h, &tail) != 3 || x != 'x' || w < 1 || h < 1 ||
        w > 4096 || h > 4096) {
        fprintf(stderr, "%s: size: want WxH, each side 1..4096, got '%s'\n", ed_name, pos[1]);
        return 2;
    }
    char *end;
    double sec = strtod(pos[2], &end);
    if (end == pos[2] || *end || !(sec >= 0 && sec <= 3600)) {
        fprintf(stderr, "%s: time: want seconds in 0..3600, got '%s'\n", ed_name, pos[2]);
        return 2;
    }
    static scn_file file;
    char err[640];
    if (scn_load(pos[0], &file, err, sizeof err) != 0) {
        fprintf(stderr, "%s: %s\n", ed_name, err);
        return 2;
    }
    rt_scene scene;
    rt_view view;
    scn_eval(&file.desc, (int32_t)(sec * 1000 + 0.5), &scene);
    if (!rt_view_ok(&scene.camera)) {
        fprintf(stderr, "%s: %s: at %s s the camera has no view direction\n", ed_name, pos[0],
                pos[2]);
        return 2;
    }
    rt_view_init(&view, &scene.camera, w, h);
    rt_params p = {.depth = scene.depth, .min_contrib = RT_DEFAULT_MIN_CONTRIB,
                   .mode = RT_MODE_FULL, .grid = grid, .threshold = (real)thr};
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
            const rt_sample *k[4] = {&s[o], &s[o + 1], &s[o + w], &s[o + w + 1]};
            if (rt_corners_differ(k, thr8) != RT_SPLIT_NONE)
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
           pos[0], w, h, pos[2], pixels, edge, (double)edge / pixels, need,
           (double)pixels / (double)need);
    free(s);
    free(must);
    return 0;
}
