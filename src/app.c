/* app.c: the command line of rt-float and rt-fixed: parses options and runs the render command. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "platform.h"
#include "rt.h"
#include "scn.h"
#include "scn_parse.h"

/* The intro, scenes/intro.scene compiled into the program at build time (rt-scenec). */
extern const scn_desc scn_intro;

#if REAL_FIXED
#define APP_REAL "fixed"
#else
#define APP_REAL "float"
#endif

#define APP_MAX_SIDE 4096
#define APP_MAX_TIME_MS SCN_MAX_DURATION_MS

static const char *app_name = "rt";

typedef struct app_opts {
    const char *output;
    int width, height;
    const char *scene; /* NULL: the built-in intro */
    int32_t time_ms;
    long frame;
    int have_time, have_frame;
    int effects_all;
    int depth; /* -1: the scene's */
    int stats;
    int mode, grid;
    long threshold, min_contrib; /* in 1/10000 */
    int show_samples;
} app_opts;

#define APP_DECIMALS 4
#define APP_SCALE 10000

static void app_usage(FILE *f)
{
    fprintf(f,
            "usage: %s render [options]     render one frame of a scene to an image file\n"
            "  --scene FILE        scene file (docs/scene-format.md; default: the built-in intro,\n"
            "                      scenes/intro.scene)\n"
            "  -o, --output FILE   output image, .png or .ppm (default frame.png)\n"
            "  --size WxH          image size, each side 1..%d (default 320x240)\n"
            "  --time SECONDS      moment of the scene's timeline, e.g. 2.5 (default 0)\n"
            "  --frame N           frame N at the scene's frame rate (instead of --time)\n"
            "  --depth N           recursion limit 0..%d (default: the scene's)\n"
            "  --mode M            full (trace every pixel) or adaptive (default)\n"
            "  --grid N            adaptive: square size 2, 4, 8 or 16 (default %d)\n"
            "  --threshold X       adaptive: split squares whose corners' colour contributions\n"
            "                      differ by more than X, 0..1 (default 0.0625; 1 = never)\n"
            "  --min-contrib X     skip secondary rays weighing less than X in the pixel, 0..1\n"
            "                      (default 0.01; 0 = trace every ray)\n"
            "  --effects E         auto: trace only the effects the frame needs (default);\n"
            "                      all: every effect on, for comparison\n"
            "  --show-samples      paint every traced point white\n"
            "  --stats             print key=value statistics on standard output\n"
            "       %s --help\n"
            "Number system of this build: %s.\n",
            app_name, APP_MAX_SIDE, RT_MAX_DEPTH, RT_DEFAULT_GRID, app_name, APP_REAL);
}

static int app_error(const char *option, const char *what, const char *value)
{
    if (value)
        fprintf(stderr, "%s: %s: %s, got '%s' (see %s --help)\n", app_name, option, what, value,
                app_name);
    else
        fprintf(stderr, "%s: %s: %s (see %s --help)\n", app_name, option, what, app_name);
    return 2;
}

/* Parses a decimal integer in [lo, hi] that fills the whole of s up to `end` (or NUL). */
static int app_parse_int(const char *s, const char **end, long lo, long hi, long *out)
{
    long v = 0;
    const char *p = s;
    if (*p < '0' || *p > '9')
        return -1;
    while (*p >= '0' && *p <= '9') {
        v = v * 10 + (*p - '0');
        if (v > hi)
            return -1;
        p++;
    }
    if (v < lo)
        return -1;
    if (end)
        *end = p;
    else if (*p)
        return -1;
    *out = v;
    return 0;
}

/* A decimal number with at most `decimals` decimals, in units of 10^-decimals, at most `max`
 * such units: no floating point involved. */
static int app_parse_decimal(const char *s, int decimals, long max, long *out)
{
    const char *p;
    long whole, frac = 0, scale = 1;
    for (int i = 0; i < decimals; i++)
        scale *= 10;
    if (app_parse_int(s, &p, 0, max / scale, &whole) != 0)
        return -1;
    if (*p == '.') {
        int digits = 0;
        p++;
        while (*p >= '0' && *p <= '9' && digits < decimals) {
            frac = frac * 10 + (*p - '0');
            digits++;
            p++;
        }
        if (digits == 0 || *p)
            return -1;
        while (digits++ < decimals)
            frac *= 10;
    } else if (*p) {
        return -1;
    }
    long total = whole * scale + frac;
    if (total > max)
        return -1;
    *out = total;
    return 0;
}

/* Seconds with at most three decimals, as milliseconds. */
static int app_parse_time(const char *s, int32_t *ms)
{
    long v;
    if (app_parse_decimal(s, 3, APP_MAX_TIME_MS, &v) != 0)
        return -1;
    *ms = (int32_t)v;
    return 0;
}

static int app_parse_size(const char *s, int *w, int *h)
{
    const char *p;
    long a, b;
    if (app_parse_int(s, &p, 1, APP_MAX_SIDE, &a) != 0 || (*p != 'x' && *p != 'X'))
        return -1;
    if (app_parse_int(p + 1, NULL, 1, APP_MAX_SIDE, &b) != 0)
        return -1;
    *w = (int)a;
    *h = (int)b;
    return 0;
}

static int app_parse_render(int argc, char **argv, app_opts *o)
{
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        int takes_value = strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0 ||
                          strcmp(a, "--size") == 0 || strcmp(a, "--time") == 0 ||
                          strcmp(a, "--frame") == 0 || strcmp(a, "--depth") == 0 ||
                          strcmp(a, "--mode") == 0 || strcmp(a, "--grid") == 0 ||
                          strcmp(a, "--threshold") == 0 || strcmp(a, "--min-contrib") == 0 ||
                          strcmp(a, "--scene") == 0 || strcmp(a, "--effects") == 0;
        if (takes_value && !v)
            return app_error(a, "needs a value", NULL);
        if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
            o->output = v;
        } else if (strcmp(a, "--scene") == 0) {
            o->scene = v;
        } else if (strcmp(a, "--effects") == 0) {
            if (strcmp(v, "auto") == 0)
                o->effects_all = 0;
            else if (strcmp(v, "all") == 0)
                o->effects_all = 1;
            else
                return app_error(a, "expected auto or all", v);
        } else if (strcmp(a, "--size") == 0) {
            if (app_parse_size(v, &o->width, &o->height) != 0)
                return app_error(a, "expected WxH with W and H in 1..4096", v);
        } else if (strcmp(a, "--time") == 0) {
            if (app_parse_time(v, &o->time_ms) != 0)
                return app_error(a, "expected seconds in 0..3600 with at most 3 decimals", v);
            o->have_time = 1;
        } else if (strcmp(a, "--frame") == 0) {
            if (app_parse_int(v, NULL, 0, (long)APP_MAX_TIME_MS / 1000 * SCN_MAX_FPS, &o->frame) != 0)
                return app_error(a, "expected a frame number (0 or more)", v);
            o->have_frame = 1;
        } else if (strcmp(a, "--depth") == 0) {
            long n;
            if (app_parse_int(v, NULL, 0, RT_MAX_DEPTH, &n) != 0)
                return app_error(a, "expected a recursion limit in 0..8", v);
            o->depth = (int)n;
        } else if (strcmp(a, "--mode") == 0) {
            if (strcmp(v, "full") == 0)
                o->mode = RT_MODE_FULL;
            else if (strcmp(v, "adaptive") == 0)
                o->mode = RT_MODE_ADAPTIVE;
            else
                return app_error(a, "expected full or adaptive", v);
        } else if (strcmp(a, "--grid") == 0) {
            long n;
            if (app_parse_int(v, NULL, 2, RT_GRID_MAX, &n) != 0 || (n & (n - 1)) != 0)
                return app_error(a, "expected a square size of 2, 4, 8 or 16", v);
            o->grid = (int)n;
        } else if (strcmp(a, "--threshold") == 0 || strcmp(a, "--min-contrib") == 0) {
            long n;
            if (app_parse_decimal(v, APP_DECIMALS, APP_SCALE, &n) != 0)
                return app_error(a, "expected a number in 0..1 with at most 4 decimals", v);
            if (strcmp(a, "--threshold") == 0)
                o->threshold = n;
            else
                o->min_contrib = n;
        } else if (strcmp(a, "--stats") == 0) {
            o->stats = 1;
            continue;
        } else if (strcmp(a, "--show-samples") == 0) {
            o->show_samples = 1;
            continue;
        } else {
            return app_error(a, "unknown option", NULL);
        }
        i++; /* the value */
    }
    if (o->have_time && o->have_frame)
        return app_error("--time", "give either --time or --frame, not both", NULL);
    if (!o->output)
        o->output = "frame.png";
    return 0;
}

static int app_render(int argc, char **argv)
{
    /* threshold and min_contrib in 1/10000: RT_DEFAULT_THRESHOLD and RT_DEFAULT_MIN_CONTRIB */
    app_opts o = {.width = 320, .height = 240, .depth = -1, .mode = RT_MODE_ADAPTIVE,
                  .grid = RT_DEFAULT_GRID, .threshold = 625, .min_contrib = 100};
    int rc = app_parse_render(argc, argv, &o);
    if (rc != 0)
        return rc;
    if (!img_path_ok(o.output))
        return app_error("-o", "the output must end in .png or .ppm", o.output);

    /* The scene: a file, or the intro compiled in. */
    static scn_file file;
    const scn_desc *desc = &scn_intro;
    const char *scene_name = "intro (built in)";
    if (o.scene) {
        char err[640];
        if (scn_load(o.scene, &file, err, sizeof err) != 0) {
            fprintf(stderr, "%s: %s\n", app_name, err);
            return 2;
        }
        desc = &file.desc;
        scene_name = o.scene;
    }
    if (o.have_frame) {
        long last = (long)desc->duration_ms * desc->fps / 1000;
        if (o.frame > last) {
            fprintf(stderr, "%s: --frame: %ld is past the last frame of %s (%ld at %ld fps)\n",
                    app_name, o.frame, scene_name, last, (long)desc->fps);
            return 2;
        }
        o.time_ms = (int32_t)(o.frame * 1000 / desc->fps);
    } else if (o.time_ms > desc->duration_ms) {
        fprintf(stderr, "%s: --time: %ld.%03ld s is past the end of %s (%ld.%03ld s)\n", app_name,
                (long)o.time_ms / 1000, (long)o.time_ms % 1000, scene_name,
                (long)desc->duration_ms / 1000, (long)desc->duration_ms % 1000);
        return 2;
    }
    static rt_scene scene;
    scn_eval(desc, o.time_ms, &scene);
    if (o.effects_all)
        rt_scene_force_effects(&scene);
    rt_params params = {
        .depth = o.depth >= 0 ? o.depth : scene.depth,
        .min_contrib = r_from_ratio((int32_t)o.min_contrib, APP_SCALE),
        .mode = o.mode,
        .grid = o.grid,
        .threshold = r_from_ratio((int32_t)o.threshold, APP_SCALE),
    };
    rt_view view;
    rt_view_init(&view, &scene.camera, o.width, o.height);

    /* Working storage of the adaptive mode, and the map of traced points when asked for. */
    unsigned long work_bytes = rt_render_work_size(&params, o.width);
    void *work = work_bytes ? malloc(work_bytes) : NULL;
    uint8_t *traced = o.show_samples ? malloc((size_t)o.width * (size_t)o.height) : NULL;
    plat_frame frame;
    if ((work_bytes && !work) || (o.show_samples && !traced)) {
        fprintf(stderr, "%s: out of memory for a %dx%d frame\n", app_name, o.width, o.height);
        rc = 1;
    } else if (plat_frame_acquire(&frame, o.width, o.height) != 0) {
        rc = 1;
    }
    if (rc != 0) {
        free(work);
        free(traced);
        return rc;
    }
    rt_stats stats = {0};
#if FX_COUNT_EVENTS
    fx_events_reset();
#endif
    uint64_t t0 = plat_time_ns();
    rt_render(&scene, &view, &params, frame.pixels, frame.stride, &stats, work, traced);
    uint64_t us = (plat_time_ns() - t0) / 1000u;
    if (traced)
        for (int y = 0; y < o.height; y++)
            for (int x = 0; x < o.width; x++)
                if (traced[(long)y * o.width + x])
                    frame.pixels[(long)y * frame.stride + x] = 0xFFFFFF;
    free(work);
    free(traced);
    rc = plat_frame_present(&frame, o.output) == 0 ? 0 : 1;
    plat_frame_release(&frame);
    if (rc != 0)
        return rc;

    if (o.stats) {
        printf("real=%s\nscene=%s\nsize=%dx%d\ntime_ms=%ld\ndepth=%d\n", APP_REAL, scene_name,
               o.width, o.height, (long)o.time_ms, params.depth);
        static const char *const fx_names[] = {"shadow", "specular", "reflect", "refract",
                                               "texture", "noise"};
        printf("effects=");
        for (int b = 0, n = 0; b < 6; b++)
            if (scene.effects & (1u << b))
                printf("%s%s", n++ ? "," : "", fx_names[b]);
        printf("%s\n", scene.effects ? "" : "none");
        printf("reach_depth=%d\n", params.depth < scene.reach_depth ? params.depth : scene.reach_depth);
        printf("mode=%s\n", o.mode == RT_MODE_ADAPTIVE ? "adaptive" : "full");
        if (o.mode == RT_MODE_ADAPTIVE)
            printf("grid=%d\nthreshold=%ld.%04ld\n", o.grid, o.threshold / APP_SCALE,
                   o.threshold % APP_SCALE);
        printf("min_contrib=%ld.%04ld\n", o.min_contrib / APP_SCALE, o.min_contrib % APP_SCALE);
        printf("ms=%llu.%03llu\n", (unsigned long long)(us / 1000),
               (unsigned long long)(us % 1000));
        printf("pixels=%ld\n", (long)o.width * o.height);
        printf("samples_traced=%lu\n", (unsigned long)stats.rays_primary);
        printf("rays_primary=%lu\nrays_shadow=%lu\nrays_reflect=%lu\nrays_refract=%lu\n",
               (unsigned long)stats.rays_primary, (unsigned long)stats.rays_shadow,
               (unsigned long)stats.rays_reflect, (unsigned long)stats.rays_refract);
        printf("shadow_tests=%lu\n", (unsigned long)stats.shadow_tests);
        if (o.mode == RT_MODE_ADAPTIVE) {
            for (int l = 0, size = o.grid; l < RT_GRID_LEVELS && size > 1; l++, size /= 2)
                printf("squares_%d=%lu\nsplit_%d=%lu\n", size, (unsigned long)stats.squares[l],
                       size, (unsigned long)stats.split[l]);
            printf("split_object=%lu\nsplit_light=%lu\nsplit_secondary=%lu\nsplit_contrib=%lu\n",
                   (unsigned long)stats.split_by[RT_SPLIT_OBJECT],
                   (unsigned long)stats.split_by[RT_SPLIT_LIGHT],
                   (unsigned long)stats.split_by[RT_SPLIT_SECONDARY],
                   (unsigned long)stats.split_by[RT_SPLIT_CONTRIB]);
            printf("work_bytes=%lu\n", work_bytes);
        }
#if FX_COUNT_EVENTS
        printf("fx_overflow=%lu\nfx_domain=%lu\nfx_nonfinite=%lu\n",
               fx_event_count[FX_EV_OVERFLOW], fx_event_count[FX_EV_DOMAIN],
               fx_event_count[FX_EV_NONFINITE]);
#endif
    }
    fprintf(stderr, "%s: wrote %s (%dx%d, %s)\n", app_name, o.output, o.width, o.height, APP_REAL);
    return 0;
}

int app_main(int argc, char **argv)
{
    if (argc > 0 && argv[0][0]) {
        const char *slash = strrchr(argv[0], '/');
        app_name = slash ? slash + 1 : argv[0];
    }
    if (argc < 2) {
        app_usage(stderr);
        return 2;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        app_usage(stdout);
        return 0;
    }
    if (strcmp(argv[1], "render") == 0)
        return app_render(argc - 2, argv + 2);
    fprintf(stderr, "%s: unknown command '%s' (commands: render; see %s --help)\n", app_name,
            argv[1], app_name);
    return 2;
}
