/* play.c: the real-time player: the timeline follows the clock (a slow frame skips ahead in time), keys pause, seek, cycle the grid and show the traced points; or a scripted run of N frames. */
#include <stdio.h>
#include <stdlib.h>

#include "frame.h"
#include "platform.h"
#include "play.h"

#define PLAY_REAL REAL_NAME

#define PLAY_SEEK_MS 5000
#define PLAY_STATUS_NS 500000000u /* the title is updated twice a second */

/* Where the timeline is. */
typedef struct play_clock {
    int64_t duration_ms;
    int64_t base_ms; /* position at base_ns */
    uint64_t base_ns;
    int paused;
} play_clock;

static int64_t play_wrap(int64_t ms, int64_t duration)
{
    if (duration <= 0)
        return 0;
    ms %= duration;
    return ms < 0 ? ms + duration : ms;
}

static int64_t play_position(const play_clock *c, uint64_t now)
{
    if (c->paused)
        return c->base_ms;
    return play_wrap(c->base_ms + (int64_t)((now - c->base_ns) / 1000000u), c->duration_ms);
}

/* Moves the timeline to ms (wrapped) from now on. */
static void play_set(play_clock *c, uint64_t now, int64_t ms)
{
    c->base_ms = play_wrap(ms, c->duration_ms);
    c->base_ns = now;
}

/* "12.3" for v in tenths. */
#define PLAY_TENTHS(v) (unsigned long)((v) / 10), (unsigned long)((v) % 10)

/* The window title: where the timeline is, frames per second shown, rendering time. */
static void play_status(const play_opts *o, const rt_params *p, int64_t ms, int paused,
                        uint64_t frames, uint64_t wall_ns, uint64_t render_ns, uint64_t worst_ns)
{
    char title[200];
    uint64_t fps10 = frames * 10000000000u / (wall_ns ? wall_ns : 1);
    uint64_t mean10 = render_ns / 100000u / (frames ? frames : 1), worst10 = worst_ns / 100000u;
    snprintf(title, sizeof title,
             "fixray %s - %s - %lu.%lu s - %lu.%lu fps - %lu.%lu ms/frame (worst %lu.%lu) - %s "
             "grid %d - %d thread%s%s",
             PLAY_REAL, o->name, PLAY_TENTHS((uint64_t)ms / 100), PLAY_TENTHS(fps10),
             PLAY_TENTHS(mean10), PLAY_TENTHS(worst10), rt_mode_name(p->mode), p->grid, o->threads,
             o->threads == 1 ? "" : "s", paused ? " - paused" : "");
    plat_display_status(title);
}

int play_run(const play_opts *o)
{
    static rt_scene scene;
    frame_ctx fc;
    plat_frame f = {0};
    uint8_t *traced = malloc((size_t)o->width * (size_t)o->height);
    if (!traced || frame_init(&fc, o->threads, o->width) != 0) {
        fprintf(stderr, "%s: out of memory for a %dx%d player\n", plat_program(), o->width,
                o->height);
        free(traced);
        return 1;
    }
    int rc = plat_frame_acquire(&f, o->width, o->height) == 0 ? 0 : 1;
    if (rc == 0) {
        char title[120];
        snprintf(title, sizeof title, "fixray %s - %s", PLAY_REAL, o->name);
        rc = plat_display_open(o->width, o->height, title) == 0 ? 0 : 1;
        if (rc != 0)
            plat_frame_release(&f);
    }
    if (rc != 0) {
        frame_free(&fc);
        free(traced);
        return rc;
    }

    rt_params p = o->params;
    int show = o->show_samples;
    play_clock clk = {.duration_ms = o->desc->duration_ms, .base_ns = plat_time_ns()};
    uint64_t status_ns = clk.base_ns, status_frames = 0, status_render = 0, status_worst = 0;
    uint64_t total_render = 0, total_worst = 0, start_ns = clk.base_ns;
    long n = 0, last_frame = (long)o->desc->duration_ms * o->desc->fps / 1000;
    int quit = 0, shown = 0; /* shown: the paused picture is on screen, nothing changed since */
    while (!quit) {
        /* Paused and already shown: wait for a key rather than render the same frame again. */
        int idle = clk.paused && shown && o->frames == 0;
        int key = plat_display_poll(idle ? 100 : 0);
        if (idle && key == PLAT_KEY_NONE)
            continue;
        shown = 0;
        uint64_t now = plat_time_ns();
        for (; key != PLAT_KEY_NONE; key = plat_display_poll(0)) {
            int64_t pos = play_position(&clk, now);
            if (key == PLAT_KEY_QUIT)
                quit = 1;
            else if (key == PLAT_KEY_PAUSE && o->frames == 0) { /* scripted runs keep going */
                play_set(&clk, now, pos);
                clk.paused = !clk.paused;
            } else if (key == PLAT_KEY_SAMPLES)
                show = !show;
            else if (key == PLAT_KEY_BACK || key == PLAT_KEY_FORWARD)
                play_set(&clk, now, pos + (key == PLAT_KEY_BACK ? -PLAY_SEEK_MS : PLAY_SEEK_MS));
            else if (key == PLAT_KEY_GRID)
                p.grid = p.grid >= RT_GRID_MAX ? 2 : p.grid * 2;
        }
        if (quit)
            break;
        /* Scripted runs step exactly one frame period per frame; otherwise the clock rules. */
        /* Scripted runs loop over the scene's frames 0 .. last_frame, as render --frame does. */
        int64_t ms = o->frames > 0 ? (int64_t)(n % (last_frame + 1)) * 1000 / o->desc->fps
                                   : play_position(&clk, now);
        scn_eval(o->desc, (int32_t)ms, &scene);
        if (o->params.depth < 0)
            p.depth = scene.depth;
        rt_view view;
        rt_view_init(&view, &scene.camera, o->width, o->height);
        rt_view_cull(&view, &scene);
        frame_sums st = {0};
        uint64_t t0 = plat_time_ns();
        frame_render(&fc, &scene, &view, &p, f.pixels, f.stride, &st, show ? traced : NULL);
        uint64_t dt = plat_time_ns() - t0;
        if (show)
            frame_mark_traced(f.pixels, f.stride, o->width, o->height, traced);
        if (plat_frame_present(&f, NULL) != 0) {
            rc = 1;
            break;
        }
        shown = 1;
        n++;
        status_frames++;
        status_render += dt;
        status_worst = dt > status_worst ? dt : status_worst;
        total_render += dt;
        total_worst = dt > total_worst ? dt : total_worst;
        now = plat_time_ns();
        if (now - status_ns >= PLAY_STATUS_NS) {
            play_status(o, &p, ms, clk.paused, status_frames, now - status_ns, status_render,
                        status_worst);
            status_ns = now;
            status_frames = status_render = status_worst = 0;
        }
        if (o->frames > 0 && n >= o->frames)
            break;
    }
    if (rc == 0 && o->screenshot && n > 0)
        rc = plat_frame_present(&f, o->screenshot) == 0 ? 0 : 1;
    if (n > 0) {
        uint64_t wall = plat_time_ns() - start_ns;
        uint64_t fps10 = (uint64_t)n * 10000000000u / (wall ? wall : 1);
        uint64_t mean100 = total_render / 10000u / (uint64_t)n, worst100 = total_worst / 10000u;
        fprintf(stderr,
                "%s: %ld frames in %lu.%02lu s (%lu.%lu fps shown); rendering %lu.%02lu ms/frame "
                "mean, %lu.%02lu worst; %dx%d, %s, %d thread%s\n",
                plat_program(), n, (unsigned long)(wall / 1000000000u),
                (unsigned long)(wall / 10000000u % 100), PLAY_TENTHS(fps10),
                (unsigned long)(mean100 / 100), (unsigned long)(mean100 % 100),
                (unsigned long)(worst100 / 100), (unsigned long)(worst100 % 100), o->width,
                o->height, PLAY_REAL, o->threads, o->threads == 1 ? "" : "s");
    }
    plat_display_close();
    plat_frame_release(&f);
    frame_free(&fc);
    free(traced);
    return rc;
}
