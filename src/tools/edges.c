/* edges.c: rt-edges, how few points adaptive subsampling could trace: the pixels its split criteria must see on a frame traced in full. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "knobs.h"
#include "rt.h"
#include "scn_parse.h"

static const char *ed_name = "rt-edges";

static void ed_usage(FILE *f)
{
    fprintf(f,
            "usage: %s SCENE WxH SECONDS [--grid N] [--threshold X] [--depth N]\n"
            "          [--min-contrib X] [--octaves N]\n"
            "  Traces every pixel of the scene at that moment (float; the settings as for\n"
            "  rt-float render, defaults alike) and counts the pixels that are a corner of some\n"
            "  1x1 cell whose four corners the split criteria tell apart (object, light state,\n"
            "  secondary objects, contribution beyond --threshold). Adaptive subsampling must\n"
            "  trace each of them, besides the --grid corners, to resolve every such edge to the\n"
            "  pixel: pixels / that count bounds its x_samples. Prints key=value lines.\n",
            ed_name);
}

/* One line and exit status 2. */
static int ed_error(const char *what, const char *value)
{
    fprintf(stderr, "%s: %s, got '%s' (see %s --help)\n", ed_name, what, value, ed_name);
    return 2;
}

int main(int argc, char **argv)
{
    const char *pos[3] = {0};
    int npos = 0;
    knobs k = KNOBS_DEFAULTS;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *expected = "";
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            ed_usage(stdout);
            return 0;
        } else if (!strcmp(a, "--mode")) {
            fprintf(stderr, "%s: --mode: the bound is for adaptive subsampling (see %s --help)\n",
                    ed_name, ed_name);
            return 2;
        } else if (knobs_is_option(a)) {
            if (i + 1 >= argc) {
                fprintf(stderr, "%s: %s: needs a value\n", ed_name, a);
                return 2;
            }
            const char *v = argv[++i];
            if (knobs_parse(&k, a, v, &expected) < 0) {
                char what[96];
                snprintf(what, sizeof what, "%s: %s", a, expected);
                return ed_error(what, v);
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
    long lw, lh, ms;
    const char *x;
    if (knobs_int(pos[1], &x, 1, 4096, &lw) != 0 || *x != 'x' ||
        knobs_int(x + 1, NULL, 1, 4096, &lh) != 0)
        return ed_error("size: want WxH, each side 1..4096", pos[1]);
    if (knobs_decimal(pos[2], 3, SCN_MAX_DURATION_MS, &ms) != 0)
        return ed_error("time: want seconds, at most 3 decimals, 0..3600", pos[2]);
    static scn_file file;
    char err[640];
    if (scn_load(pos[0], &file, err, sizeof err) != 0) {
        fprintf(stderr, "%s: %s\n", ed_name, err);
        return 2;
    }
    rt_scene scene;
    rt_view view;
    scn_eval(&file.desc, (int32_t)ms, &scene);
    if (!rt_view_ok(&scene.camera)) {
        fprintf(stderr, "%s: %s: at %s s the camera has no view direction\n", ed_name, pos[0],
                pos[2]);
        return 2;
    }
    int w = (int)lw, h = (int)lh;
    rt_view_init(&view, &scene.camera, w, h);
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
           pos[0], w, h, pos[2], pixels, edge, (double)edge / pixels, need,
           (double)pixels / (double)need);
    free(s);
    free(must);
    return 0;
}
