/* app.c: the command line of rt-float and rt-fixed: parses options and runs the render command. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "frame.h"
#include "image.h"
#include "knobs.h"
#include "outpath.h"
#include "platform.h"
#include "play.h"
#include "rt.h"
#include "scn.h"
#include "scn_parse.h"

/* The intro, scenes/intro.scene compiled into the program at build time (rt-scenec). */
extern const scn_desc scn_intro;

#define APP_REAL REAL_NAME

#define APP_MAX_SIDE 4096
#define APP_MAX_TIME_MS SCN_MAX_DURATION_MS
#define APP_MAX_FRAME ((long)APP_MAX_TIME_MS / 1000 * SCN_MAX_FPS) /* of the longest scene */

static const char *app_name = "rt";

/* The platform's clock in microseconds. */
static uint64_t app_us(void) { return plat_time_ns() / 1000u; }

typedef struct app_opts {
    const char *output;
    int width, height;
    const char *scene; /* NULL: the built-in intro */
    int32_t time_ms;
    long frame;
    int have_time, have_frame;
    long first, last, step; /* --frames: a range, last = -1 for the scene's last frame */
    int have_frames, have_step;
    int checksum, progress;
    int effects_all;
    knobs k; /* --depth, --mode, --grid, --threshold, --min-contrib, --octaves */
    int stats;
    int show_samples;
    int threads;            /* 1..PLAT_MAX_THREADS */
    int play;               /* the play command: --frames N counts frames */
    long play_frames;       /* play --frames N: quit after N frames (0: run until quit) */
    const char *screenshot; /* play --screenshot FILE */
} app_opts;

static void app_usage(FILE *f)
{
    fprintf(
        f,
        "usage: %s render [options]     render frames of a scene to image files\n"
        "       %s play [options]       play a scene in a window, in real time\n"
        "  --scene FILE        scene file (docs/scene-format.md; default: the built-in intro,\n"
        "                      scenes/intro.scene)\n"
        "  -o, --output FILE   output image, .png or .ppm (default frame.png); with --frames\n"
        "                      a pattern with one frame-number field, e.g. out/intro-%%04d.png\n"
        "  --size WxH          image size, each side 1..%d (default 320x240)\n"
        "  --time SECONDS      moment of the scene's timeline, e.g. 2.5 (default 0)\n"
        "  --frame N           frame N at the scene's frame rate (instead of --time)\n"
        "  --frames A-B        frames A to B, one file each (-o pattern); --frames all: every\n"
        "                      frame of the scene\n"
        "  --step N            with --frames: every Nth frame of the range (default 1)\n"
        "  --checksum          print frame=N time_ms=T fnv64=H per frame (64-bit FNV-1a of\n"
        "                      the RGB bytes); writes no image unless -o is given\n"
        "  --progress          a progress line on standard error (default with --frames when\n"
        "                      standard error is a terminal)\n"
        "  --depth N           recursion limit 0..%d (default: the scene's)\n"
        "  --mode M            full (trace every pixel), adaptive (default) or probe\n"
        "                      (adaptive, new points probed first, docs/probe.md)\n"
        "  --grid N            adaptive: square size 2, 4, 8 or 16 (default %d)\n"
        "  --threshold X       adaptive: split squares whose corners' colour contributions\n"
        "                      differ by more than X, 0..1 (default 0.0625; 1 = never)\n"
        "  --min-contrib X     skip secondary rays weighing less than X in the pixel, 0..1\n"
        "                      (default 0.01; 0 = trace every ray)\n"
        "  --octaves N         noise textures sum at most N octaves, 1..8 (default: each\n"
        "                      texture's own count, from the scene)\n"
        "  --effects E         auto: trace only the effects the frame needs (default);\n"
        "                      all: every effect on, for comparison\n"
        "  --show-samples      paint every traced point white\n"
        "  --threads N         render on N threads, 1..%d (default: every processor, %d\n"
        "                      here); the picture is the same for any N\n"
        "  --stats             print key=value statistics on standard output (with --frames:\n"
        "                      summed over the frames)\n"
        "play: --scene, --size (default 640x480), --threads, --depth, --mode, --grid,\n"
        "--threshold, --min-contrib, --octaves and --show-samples as above, and\n"
        "  --frames N          quit after N frames, stepping the timeline by exactly one frame\n"
        "                      period each (a scripted, reproducible run)\n"
        "  --screenshot FILE   save the last frame shown (.png or .ppm)\n"
        "  keys: Esc or Q quit, Space pause, F full screen, S traced points, Left/Right seek\n"
        "  5 s, G grid size (2, 4, 8, 16); the title shows frames per second and ms per frame\n"
        "       %s --help\n"
        "Errors get one line on standard error: exit status 2 for bad options, scenes and\n"
        "output names (all refused before rendering), 1 when writing a file fails.\n"
        "Number system of this build: %s.\n",
        app_name, app_name, APP_MAX_SIDE, RT_MAX_DEPTH, RT_DEFAULT_GRID, PLAT_MAX_THREADS,
        plat_cpu_count(), app_name, APP_REAL);
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

/* Seconds with at most three decimals, as milliseconds. */
static int app_parse_time(const char *s, int32_t *ms)
{
    long v;
    if (knobs_decimal(s, 3, APP_MAX_TIME_MS, &v) != 0)
        return -1;
    *ms = (int32_t)v;
    return 0;
}

static int app_parse_size(const char *s, int *w, int *h)
{
    const char *p;
    long a, b;
    if (knobs_int(s, &p, 1, APP_MAX_SIDE, &a) != 0 || (*p != 'x' && *p != 'X'))
        return -1;
    if (knobs_int(p + 1, NULL, 1, APP_MAX_SIDE, &b) != 0)
        return -1;
    *w = (int)a;
    *h = (int)b;
    return 0;
}

/* --frames: "FIRST-LAST" or "all" (then *last = -1: the scene's last frame). */
static int app_parse_frames(const char *s, long *first, long *last)
{
    const char *p;
    long max = APP_MAX_FRAME;
    if (strcmp(s, "all") == 0) {
        *first = 0;
        *last = -1;
        return 0;
    }
    if (knobs_int(s, &p, 0, max, first) != 0 || *p != '-')
        return -1;
    return knobs_int(p + 1, NULL, *first, max, last);
}

/* The output file of frame `frame`: `pattern` with its frame-number fields ("%d", "%4d",
 * "%04d": width 1..9) replaced and "%%" turned into "%". Returns the number of fields, -1 for
 * any other '%', -2 when the name does not fit in n bytes. */
static int app_expand(const char *pattern, long frame, char *buf, size_t n)
{
    size_t k = 0;
    int fields = 0;
    for (const char *p = pattern; *p; p++) {
        char piece[32] = {*p, 0};
        if (*p == '%' && p[1] == '%') {
            p++;
        } else if (*p == '%') {
            int zero = p[1] == '0', width = 0;
            p += 1 + zero;
            if (*p >= '1' && *p <= '9')
                width = *p++ - '0';
            if (*p != 'd')
                return -1;
            if (zero)
                snprintf(piece, sizeof piece, "%0*ld", width, frame);
            else
                snprintf(piece, sizeof piece, "%*ld", width, frame);
            fields++;
        }
        size_t m = strlen(piece);
        if (k + m >= n)
            return -2;
        memcpy(buf + k, piece, m);
        k += m;
    }
    buf[k] = 0;
    return fields;
}

static int app_parse_render(int argc, char **argv, app_opts *o)
{
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        const char *expected;
        int kr;
        int takes_value = strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0 ||
            strcmp(a, "--size") == 0 || strcmp(a, "--time") == 0 || strcmp(a, "--frame") == 0 ||
            knobs_is_option(a) || strcmp(a, "--frames") == 0 || strcmp(a, "--step") == 0 ||
            strcmp(a, "--scene") == 0 || strcmp(a, "--effects") == 0 ||
            strcmp(a, "--threads") == 0 || strcmp(a, "--screenshot") == 0;
        static const char *const render_only[] = {"-o",         "--output", "--time",
                                                  "--frame",    "--step",   "--checksum",
                                                  "--progress", "--stats",  "--effects"};
        for (size_t k = 0; o->play && k < sizeof render_only / sizeof *render_only; k++)
            if (strcmp(a, render_only[k]) == 0)
                return app_error(a, "is an option of render, not of play", NULL);
        if (!o->play && strcmp(a, "--screenshot") == 0)
            return app_error(a, "is an option of play, not of render", NULL);
        if (takes_value && !v)
            return app_error(a, "needs a value", NULL);
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            app_usage(stdout);
            return -1;
        }
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
            if (knobs_int(v, NULL, 0, APP_MAX_FRAME, &o->frame) != 0)
                return app_error(a, "expected a frame number (0 or more)", v);
            o->have_frame = 1;
        } else if (strcmp(a, "--frames") == 0 && o->play) {
            if (knobs_int(v, NULL, 1, APP_MAX_FRAME, &o->play_frames) != 0)
                return app_error(a, "expected a number of frames, 1 or more", v);
        } else if (strcmp(a, "--screenshot") == 0) {
            if (!img_path_ok(v))
                return app_error(a, "the screenshot must end in .png or .ppm", v);
            o->screenshot = v;
        } else if (strcmp(a, "--threads") == 0) {
            long n;
            if (knobs_int(v, NULL, 1, PLAT_MAX_THREADS, &n) != 0)
                return app_error(a, "expected a number of threads in 1..64", v);
            o->threads = (int)n;
        } else if (strcmp(a, "--frames") == 0) {
            if (app_parse_frames(v, &o->first, &o->last) != 0)
                return app_error(a, "expected FIRST-LAST frame numbers with FIRST <= LAST, or all",
                                 v);
            o->have_frames = 1;
        } else if (strcmp(a, "--step") == 0) {
            if (knobs_int(v, NULL, 1, APP_MAX_FRAME, &o->step) != 0)
                return app_error(a, "expected a whole number of frames, 1 or more", v);
            o->have_step = 1;
        } else if (strcmp(a, "--checksum") == 0) {
            o->checksum = 1;
            continue;
        } else if (strcmp(a, "--progress") == 0) {
            o->progress = 1;
            continue;
        } else if ((kr = knobs_parse(&o->k, a, v, &expected)) != 0) {
            if (kr < 0)
                return app_error(a, expected, v);
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
    if (o->play) {
        char err[600];
        if (o->screenshot && outpath_check(o->screenshot, err, sizeof err) != 0) {
            fprintf(stderr, "%s: %s\n", app_name, err);
            return 2;
        }
        return 0;
    }
    if (o->have_time + o->have_frame + o->have_frames > 1)
        return app_error(o->have_time ? "--time" : "--frame",
                         "give only one of --time, --frame and --frames", NULL);
    if (o->have_step && !o->have_frames)
        return app_error("--step", "goes with --frames", NULL);
    if (o->have_frames && !o->output && !o->checksum)
        return app_error("--frames",
                         "needs -o with a frame-number pattern (such as "
                         "out/intro-%04d.png) or --checksum",
                         NULL);
    if (!o->output && !o->checksum)
        o->output = "frame.png";
    if (o->output && !img_path_ok(o->output))
        return app_error("-o", "the output must end in .png or .ppm", o->output);
    if (o->output && o->have_frames) {
        char name[4096];
        int fields = app_expand(o->output, 0, name, sizeof name);
        if (fields == -1)
            return app_error("-o",
                             "a '%' starts the frame-number field (%d, %04d, ...) or "
                             "stands for itself as %%",
                             o->output);
        if (fields == -2)
            return app_error("-o", "the file name is too long", NULL);
        if (fields != 1)
            return app_error("-o",
                             "with --frames the output needs one frame-number field, "
                             "such as %04d",
                             o->output);
    }
    return 0;
}

/* Counters of rt_stats summed over the frames of a run (64 bits: many frames, large ones). */
typedef struct app_sums {
    unsigned long long rays[4], shadow_tests, noise_octaves, squares[RT_GRID_LEVELS],
        split[RT_GRID_LEVELS], split_by[5], probes[3];
} app_sums;

static void app_add(app_sums *t, const rt_stats *s)
{
    t->rays[0] += s->rays_primary;
    t->rays[1] += s->rays_shadow;
    t->rays[2] += s->rays_reflect;
    t->rays[3] += s->rays_refract;
    t->shadow_tests += s->shadow_tests;
    t->noise_octaves += s->noise_octaves;
    for (int l = 0; l < RT_GRID_LEVELS; l++) {
        t->squares[l] += s->squares[l];
        t->split[l] += s->split[l];
    }
    for (int r = 0; r < 5; r++)
        t->split_by[r] += s->split_by[r];
    t->probes[0] += s->probes;
    t->probes[1] += s->probe_shadow;
    t->probes[2] += s->probe_secondary;
}

/* 64-bit FNV-1a of the frame's RGB bytes, row by row: the bytes of a PPM file's raster. */
static unsigned long long app_fnv(const plat_frame *f)
{
    unsigned long long h = 14695981039346656037ull;
    for (int y = 0; y < f->height; y++)
        for (int x = 0; x < f->width; x++) {
            uint32_t p = f->pixels[(long)y * f->stride + x];
            for (int c = 16; c >= 0; c -= 8)
                h = (h ^ ((p >> c) & 0xFF)) * 1099511628211ull;
        }
    return h;
}

static void app_print_stats(const app_opts *o, const char *scene_name, const rt_scene *scene,
                            const rt_params *params, long frames, const app_sums *t, uint64_t us,
                            unsigned long work_bytes)
{
    printf("real=%s\nscene=%s\nsize=%dx%d\n", APP_REAL, scene_name, o->width, o->height);
    if (o->have_frames)
        printf("frames=%ld\nfirst_frame=%ld\nlast_frame=%ld\nstep=%ld\n", frames, o->first, o->last,
               o->step);
    else
        printf("time_ms=%ld\n", (long)o->time_ms);
    printf("depth=%d\n", params->depth);
    static const char *const fx_names[] = {"shadow",  "specular", "reflect",
                                           "refract", "texture",  "noise"};
    printf("effects=");
    for (int b = 0, n = 0; b < 6; b++)
        if (scene->effects & (1u << b))
            printf("%s%s", n++ ? "," : "", fx_names[b]);
    printf("%s\n", scene->effects ? "" : "none");
    printf("reach_depth=%d\n",
           params->depth < scene->reach_depth ? params->depth : scene->reach_depth);
    printf("mode=%s\n", rt_mode_name(o->k.mode));
    if (o->k.mode != RT_MODE_FULL)
        printf("grid=%d\nthreshold=%ld.%04ld\n", o->k.grid, (long)o->k.threshold / KNOBS_SCALE,
               (long)o->k.threshold % KNOBS_SCALE);
    printf("min_contrib=%ld.%04ld\n", (long)o->k.min_contrib / KNOBS_SCALE,
           (long)o->k.min_contrib % KNOBS_SCALE);
    if (o->k.octaves > 0)
        printf("octaves=%d\n", o->k.octaves);
    else
        printf("octaves=scene\n");
    printf("ms=%llu.%03llu\n", (unsigned long long)(us / 1000), (unsigned long long)(us % 1000));
    printf("pixels=%ld\n", (long)o->width * o->height);
    printf("threads=%d\n", o->threads);
    printf("samples_traced=%llu\n", t->rays[0]);
    printf("rays_primary=%llu\nrays_shadow=%llu\nrays_reflect=%llu\nrays_refract=%llu\n",
           t->rays[0], t->rays[1], t->rays[2], t->rays[3]);
    printf("shadow_tests=%llu\n", t->shadow_tests);
    printf("noise_octaves=%llu\n", t->noise_octaves);
    if (o->k.mode == RT_MODE_PROBE)
        printf("probes=%llu\nprobe_rays_shadow=%llu\nprobe_rays_secondary=%llu\n", t->probes[0],
               t->probes[1], t->probes[2]);
    if (o->k.mode != RT_MODE_FULL) {
        for (int l = 0, size = o->k.grid; l < RT_GRID_LEVELS && size > 1; l++, size /= 2)
            printf("squares_%d=%llu\nsplit_%d=%llu\n", size, t->squares[l], size, t->split[l]);
        printf("split_object=%llu\nsplit_light=%llu\nsplit_secondary=%llu\nsplit_contrib=%llu\n",
               t->split_by[RT_SPLIT_OBJECT], t->split_by[RT_SPLIT_LIGHT],
               t->split_by[RT_SPLIT_SECONDARY], t->split_by[RT_SPLIT_CONTRIB]);
        printf("work_bytes=%lu\n", work_bytes);
    }
#if FX_COUNT_EVENTS
    printf("fx_overflow=%lu\nfx_domain=%lu\nfx_nonfinite=%lu\n", fx_event_count[FX_EV_OVERFLOW],
           fx_event_count[FX_EV_DOMAIN], fx_event_count[FX_EV_NONFINITE]);
#endif
}

/* "12.345 s" of a time in milliseconds, for messages. */
#define APP_SECONDS(ms) (long)(ms) / 1000, (long)(ms) % 1000

/* The scene of o: a file, or the intro compiled in. Returns NULL after a one-line error. */
static const scn_desc *app_scene(const app_opts *o, const char **name)
{
    static scn_file file;
    char err[640];
    *name = "intro (built in)";
    if (!o->scene)
        return &scn_intro;
    if (scn_load(o->scene, &file, err, sizeof err) != 0) {
        fprintf(stderr, "%s: %s\n", app_name, err);
        return NULL;
    }
    *name = o->scene;
    return &file.desc;
}

/* Options as the command line gives them. */
static app_opts app_defaults(int play)
{
    return (app_opts){.width = play ? 640 : 320,
                      .height = play ? 480 : 240,
                      .k = KNOBS_DEFAULTS,
                      .step = 1,
                      .threads = plat_cpu_count(),
                      .play = play};
}

static int app_play(int argc, char **argv)
{
    app_opts o = app_defaults(1);
    int rc = app_parse_render(argc, argv, &o);
    if (rc != 0)
        return rc < 0 ? 0 : rc; /* -1: --help */
    play_opts p = {.width = o.width,
                   .height = o.height,
                   .threads = o.threads,
                   .frames = o.play_frames,
                   .screenshot = o.screenshot,
                   .show_samples = o.show_samples,
                   .params = knobs_params(&o.k, -1)};
    p.desc = app_scene(&o, &p.name);
    if (!p.desc)
        return 2;
    return play_run(&p);
}

static int app_render(int argc, char **argv)
{
    app_opts o = app_defaults(0);
    int rc = app_parse_render(argc, argv, &o);
    if (rc != 0)
        return rc < 0 ? 0 : rc; /* -1: --help */

    const char *scene_name;
    const scn_desc *desc = app_scene(&o, &scene_name);
    if (!desc)
        return 2;
    char err[640];
    /* The frames: one moment (--time, --frame), or a range of frames at the scene's rate. */
    long last_frame = (long)desc->duration_ms * desc->fps / 1000;
    if (o.have_frames && o.last < 0)
        o.last = last_frame;
    if (o.have_frame || o.have_frames) {
        long f = o.have_frame ? o.frame : o.last;
        if (f > last_frame) {
            fprintf(stderr, "%s: %s: %ld is past the last frame of %s (%ld at %ld fps)\n", app_name,
                    o.have_frame ? "--frame" : "--frames", f, scene_name, last_frame,
                    (long)desc->fps);
            return 2;
        }
    } else if (o.time_ms > desc->duration_ms) {
        fprintf(stderr, "%s: --time: %ld.%03ld s is past the end of %s (%ld.%03ld s)\n", app_name,
                APP_SECONDS(o.time_ms), scene_name, APP_SECONDS(desc->duration_ms));
        return 2;
    }
    if (!o.have_frames) {
        o.first = o.last = o.have_frame ? o.frame : -1;
        if (o.have_frame)
            o.time_ms = (int32_t)(o.frame * 1000 / desc->fps);
    }
    long nframes = o.have_frames ? (o.last - o.first) / o.step + 1 : 1;

    /* Everything that can be refused is refused before the first frame is rendered: an output
     * file that cannot be created, and a camera without a view direction at some frame. */
    char out[4096];
    static rt_scene scene;
    for (long i = 0; i < nframes; i++) {
        long f = o.first + i * o.step;
        int32_t t = o.have_frames ? (int32_t)(f * 1000 / desc->fps) : o.time_ms;
        err[0] = 0;
        if (o.output && o.have_frames && app_expand(o.output, f, out, sizeof out) != 1)
            snprintf(err, sizeof err, "%.64s...: the file name is too long", o.output);
        else if (o.output)
            outpath_check(o.have_frames ? out : o.output, err, sizeof err);
        if (err[0]) {
            fprintf(stderr, "%s: %s\n", app_name, err);
            return 2;
        }
        scn_eval(desc, t, &scene);
        if (!rt_view_ok(&scene.camera)) {
            fprintf(stderr,
                    "%s: %s: at %ld.%03ld s the camera's eye and the point it looks at "
                    "coincide: no view direction\n",
                    app_name, scene_name, APP_SECONDS(t));
            return 2;
        }
    }

    /* Frame buffer, working storage of the adaptive mode and the map of traced points: the
     * same for every frame, allocated once. */
    rt_params params = knobs_params(&o.k, 0); /* the depth is set per frame */
    unsigned long work_bytes = rt_render_work_size(&params, o.width);
    size_t pixels = (size_t)o.width * (size_t)o.height;
    frame_ctx fc;
    int fc_ok = frame_init(&fc, o.threads, o.width) == 0;
    uint8_t *traced = o.show_samples ? malloc(pixels) : NULL;
    plat_frame frame = {0};
    if (!fc_ok || (o.show_samples && !traced) ||
        plat_frame_acquire(&frame, o.width, o.height) != 0) {
        /* frame, samples map, working storage, and 3 bytes a pixel when the file is written */
        unsigned long long need = (unsigned long long)pixels * (4 + 3 + (o.show_samples ? 1 : 0)) +
            (unsigned long long)work_bytes * (unsigned)o.threads;
        fprintf(stderr, "%s: out of memory for a %dx%d frame (%llu MiB)\n", app_name, o.width,
                o.height, (need + (1 << 20) - 1) >> 20);
        if (fc_ok)
            frame_free(&fc);
        free(traced);
        plat_frame_release(&frame);
        return 1;
    }

    int progress = o.progress || (o.have_frames && isatty(2));
    app_sums sums = {0};
    rt_view view;
    uint64_t us = 0, start = app_us();
#if FX_COUNT_EVENTS
    fx_events_reset();
#endif
    for (long i = 0; i < nframes && rc == 0; i++) {
        long f = o.first + i * o.step;
        int32_t t = o.have_frames ? (int32_t)(f * 1000 / desc->fps) : o.time_ms;
        scn_eval(desc, t, &scene);
        if (o.effects_all)
            rt_scene_force_effects(&scene);
        params.depth = o.k.depth >= 0 ? o.k.depth : scene.depth;
        rt_view_init(&view, &scene.camera, o.width, o.height);
        rt_stats stats = {0};
        uint64_t t0 = app_us();
        frame_render(&fc, &scene, &view, &params, frame.pixels, frame.stride, &stats, traced);
        us += app_us() - t0;
        app_add(&sums, &stats);
        if (traced)
            frame_mark_traced(frame.pixels, frame.stride, o.width, o.height, traced);
        if (o.checksum) {
            if (f >= 0)
                printf("frame=%ld ", f);
            printf("time_ms=%ld fnv64=%016llx\n", (long)t, app_fnv(&frame));
        }
        if (o.output) {
            if (o.have_frames)
                app_expand(o.output, f, out, sizeof out);
            if (plat_frame_present(&frame, o.have_frames ? out : o.output) != 0)
                rc = 1;
        }
        if (progress) {
            uint64_t el = app_us() - start + 1;
            unsigned long long fps10 = (unsigned long long)(i + 1) * 10000000u / el;
            unsigned long long left =
                el * (unsigned long long)(nframes - i - 1) / (i + 1) / 1000000u;
            fprintf(stderr,
                    "\r%s: frame %ld (%ld of %ld, %ld%%), %llu.%llu frames/s, %llu s left  ",
                    app_name, f >= 0 ? f : 0, i + 1, nframes, (i + 1) * 100 / nframes, fps10 / 10,
                    fps10 % 10, left);
            if (i + 1 == nframes || rc != 0)
                fputc('\n', stderr);
        }
    }
    frame_free(&fc);
    free(traced);
    plat_frame_release(&frame);
    if (rc != 0)
        return rc;
    if (o.stats)
        app_print_stats(&o, scene_name, &scene, &params, nframes, &sums, us, work_bytes);
    if (o.have_frames)
        fprintf(stderr, "%s: rendered %ld frames (%ld-%ld, step %ld) of %s%s%s (%dx%d, %s)\n",
                app_name, nframes, o.first, o.last, o.step, scene_name, o.output ? " to " : "",
                o.output ? o.output : "", o.width, o.height, APP_REAL);
    else if (o.output)
        fprintf(stderr, "%s: wrote %s (%dx%d, %s)\n", app_name, o.output, o.width, o.height,
                APP_REAL);
    return 0;
}

int app_main(int argc, char **argv)
{
    if (argc > 0 && argv[0][0]) {
        const char *slash = strrchr(argv[0], '/');
        app_name = slash ? slash + 1 : argv[0];
    }
    if (argc < 2) {
        fprintf(stderr, "%s: no command given (usage: %s render|play [options]; see %s --help)\n",
                app_name, app_name, app_name);
        return 2;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        app_usage(stdout);
        return 0;
    }
    if (strcmp(argv[1], "render") == 0)
        return app_render(argc - 2, argv + 2);
    if (strcmp(argv[1], "play") == 0)
        return app_play(argc - 2, argv + 2);
    fprintf(stderr, "%s: unknown command '%s' (commands: render, play; see %s --help)\n", app_name,
            argv[1], app_name);
    return 2;
}
