/* app.c: rt-float and rt-fixed: the render and play commands (their options: cli.c). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "frame.h"
#include "image.h"
#include "knobs.h"
#include "outpath.h"
#include "platform.h"
#include "play.h"
#include "rt.h"
#include "scn.h"
#include "scn_parse.h"

#define APP_REAL REAL_NAME

#define APP_PROGRESS_STEP 5 /* percent between progress lines when not on a terminal */

/* The platform's clock in microseconds. */
static uint64_t app_us(void) { return plat_time_ns() / 1000u; }

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

/* What the options of render say together (cli_parse checked each alone). Returns 0 or 2. */
static int app_check_render(cli_opts *o)
{
    if (o->have_time + o->have_frame + o->have_frames > 1)
        return cli_error(o->have_time ? "--time" : "--frame",
                         "give only one of --time, --frame and --frames", NULL);
    if (o->have_step && !o->have_frames)
        return cli_error("--step", "goes with --frames", NULL);
    if (o->have_frames && !o->output && !o->checksum)
        return cli_error("--frames",
                         "needs -o with a frame-number pattern (such as "
                         "out/intro-%04d.png) or --checksum",
                         NULL);
    if (!o->output && !o->checksum)
        o->output = "frame.png";
    if (o->output && !img_path_ok(o->output))
        return cli_error("-o", "the output must end in .png or .ppm", o->output);
    if (o->output && o->have_frames) {
        char name[4096];
        int fields = app_expand(o->output, 0, name, sizeof name);
        if (fields == -1)
            return cli_error("-o",
                             "a '%' starts the frame-number field (%d, %04d, ...) or "
                             "stands for itself as %%",
                             o->output);
        if (fields == -2)
            return cli_error("-o", "the file name is too long", NULL);
        if (fields != 1)
            return cli_error("-o",
                             "with --frames the output needs one frame-number field, "
                             "such as %04d",
                             o->output);
    }
    return 0;
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

static void app_print_stats(const cli_opts *o, const char *scene_name, const rt_scene *scene,
                            const rt_params *params, long frames, const frame_sums *t, uint64_t us,
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
    printf("footprint=%s\n", o->k.footprint ? "on" : "off");
    printf("ms=%llu.%03llu\n", (unsigned long long)(us / 1000), (unsigned long long)(us % 1000));
    printf("pixels=%ld\n", (long)o->width * o->height);
    printf("threads=%d\n", o->threads);
    printf("samples_traced=%llu\n", FRAME_SUM(t, rays_primary, 0));
    printf("rays_primary=%llu\nrays_shadow=%llu\nrays_reflect=%llu\nrays_refract=%llu\n",
           FRAME_SUM(t, rays_primary, 0), FRAME_SUM(t, rays_shadow, 0),
           FRAME_SUM(t, rays_reflect, 0), FRAME_SUM(t, rays_refract, 0));
    printf("shadow_tests=%llu\n", FRAME_SUM(t, shadow_tests, 0));
    printf("noise_octaves=%llu\n", FRAME_SUM(t, noise_octaves, 0));
    if (o->k.mode == RT_MODE_PROBE)
        printf("probes=%llu\n", FRAME_SUM(t, probes, 0));
    if (o->k.mode != RT_MODE_FULL) {
        for (int l = 0, size = o->k.grid; l < RT_GRID_LEVELS && size > 1; l++, size /= 2)
            printf("squares_%d=%llu\nsplit_%d=%llu\n", size, FRAME_SUM(t, squares, l), size,
                   FRAME_SUM(t, split, l));
        printf("split_object=%llu\nsplit_light=%llu\nsplit_secondary=%llu\nsplit_contrib=%llu\n",
               FRAME_SUM(t, split_by, RT_SPLIT_OBJECT), FRAME_SUM(t, split_by, RT_SPLIT_LIGHT),
               FRAME_SUM(t, split_by, RT_SPLIT_SECONDARY),
               FRAME_SUM(t, split_by, RT_SPLIT_CONTRIB));
        printf("texture_squares=%llu\ntexture_pixels=%llu\n", FRAME_SUM(t, texture_squares, 0),
               FRAME_SUM(t, texture_pixels, 0));
        printf("noise_squares=%llu\nnoise_pixels=%llu\n", FRAME_SUM(t, noise_squares, 0),
               FRAME_SUM(t, noise_pixels, 0));
        printf("shadow_squares=%llu\nshadow_pixels=%llu\n", FRAME_SUM(t, shadow_squares, 0),
               FRAME_SUM(t, shadow_pixels, 0));
        printf("centre_tests=%llu\ncontrib_kept=%llu\n", FRAME_SUM(t, centre_tests, 0),
               FRAME_SUM(t, contrib_kept, 0));
        printf("local_points=%llu\n", FRAME_SUM(t, local_points, 0));
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
static const scn_desc *app_scene(const cli_opts *o, const char **name)
{
    static scn_file file;
    char err[640];
    *name = "intro (built in)";
    if (!o->scene)
        return &scn_intro;
    if (scn_load(o->scene, &file, err, sizeof err) != 0) {
        fprintf(stderr, "%s: %s\n", plat_program(), err);
        return NULL;
    }
    *name = o->scene;
    return &file.desc;
}

static int app_play(int argc, char **argv)
{
    cli_opts o = cli_defaults(CLI_PLAY);
    int rc = cli_parse(CLI_PLAY, argc, argv, &o);
    if (rc != 0)
        return rc < 0 ? 0 : rc; /* -1: --help, --version */
    play_opts p = cli_play_opts(&o);
    p.desc = app_scene(&o, &p.name);
    if (!p.desc)
        return 2;
    return play_run(&p);
}

static int app_render(int argc, char **argv)
{
    cli_opts o = cli_defaults(CLI_RENDER);
    int rc = cli_parse(CLI_RENDER, argc, argv, &o);
    if (rc == 0)
        rc = app_check_render(&o);
    if (rc != 0)
        return rc < 0 ? 0 : rc; /* -1: --help, --version */

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
            fprintf(stderr, "%s: %s: %ld is past the last frame of %s (%ld at %ld fps)\n",
                    plat_program(), o.have_frame ? "--frame" : "--frames", f, scene_name,
                    last_frame, (long)desc->fps);
            return 2;
        }
    } else if (o.time_ms > desc->duration_ms) {
        fprintf(stderr, "%s: --time: %ld.%03ld s is past the end of %s (%ld.%03ld s)\n",
                plat_program(), APP_SECONDS(o.time_ms), scene_name, APP_SECONDS(desc->duration_ms));
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
            fprintf(stderr, "%s: %s\n", plat_program(), err);
            return 2;
        }
        scn_eval(desc, t, &scene);
        if (!rt_view_ok(&scene.camera)) {
            fprintf(stderr,
                    "%s: %s: at %ld.%03ld s the camera's eye and the point it looks at "
                    "coincide: no view direction\n",
                    plat_program(), scene_name, APP_SECONDS(t));
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
        fprintf(stderr, "%s: out of memory for a %dx%d frame (%llu MiB)\n", plat_program(), o.width,
                o.height, (need + (1 << 20) - 1) >> 20);
        if (fc_ok)
            frame_free(&fc);
        free(traced);
        plat_frame_release(&frame);
        return 1;
    }

    /* On a terminal one line redrawn per frame; elsewhere (a log, CI) a plain line every
     * APP_PROGRESS_STEP percent. */
    int tty = isatty(2), progress = o.progress || (o.have_frames && tty);
    long shown_pct = -1;
    frame_sums sums = {0};
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
        rt_view_cull(&view, &scene);
        uint64_t t0 = app_us();
        frame_render(&fc, &scene, &view, &params, frame.pixels, frame.stride, &sums, traced);
        us += app_us() - t0;
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
            long pct = (i + 1) * 100 / nframes;
            if (tty || i + 1 == nframes || rc != 0 || pct / APP_PROGRESS_STEP != shown_pct) {
                fprintf(stderr,
                        "%s%s: frame %ld (%ld of %ld, %ld%%), %llu.%llu frames/s, %llu s left%s",
                        tty ? "\r" : "", plat_program(), f >= 0 ? f : 0, i + 1, nframes, pct,
                        fps10 / 10, fps10 % 10, left, tty ? "  " : "\n");
                shown_pct = pct / APP_PROGRESS_STEP;
            }
            if (tty && (i + 1 == nframes || rc != 0))
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
                plat_program(), nframes, o.first, o.last, o.step, scene_name,
                o.output ? " to " : "", o.output ? o.output : "", o.width, o.height, APP_REAL);
    else if (o.output)
        fprintf(stderr, "%s: wrote %s (%dx%d, %s)\n", plat_program(), o.output, o.width, o.height,
                APP_REAL);
    return 0;
}

int app_main(int argc, char **argv)
{
    const char *p = plat_program();
    if (argc < 2) {
        fprintf(stderr, "%s: no command given (usage: %s render|play [options]; see %s --help)\n",
                p, p, p);
        return 2;
    }
    const char *c = argv[1];
    if (strcmp(c, "--help") == 0 || strcmp(c, "-h") == 0 || strcmp(c, "help") == 0) {
        cli_usage(stdout, CLI_RENDER | CLI_PLAY);
        return 0;
    }
    if (strcmp(c, "--version") == 0 || strcmp(c, "version") == 0) {
        cli_version(stdout);
        return 0;
    }
    if (strcmp(c, "render") == 0)
        return app_render(argc - 2, argv + 2);
    if (strcmp(c, "play") == 0)
        return app_play(argc - 2, argv + 2);
    fprintf(stderr, "%s: unknown command '%s' (commands: render, play, help; see %s --help)\n", p,
            c, p);
    return 2;
}
