/* intro.c: the intro as a board without files or a shell runs it (the ARM image): play it, render listed frames, or benchmark a stretch.
 *
 * Commands, from the platform's argument list (on the ARM board: QEMU's semihosting
 * `arg=` values, the first being the program name):
 *   play                     loop the intro in real time on the display (the default)
 *   frames [--out P] N...    render intro frames N (at the scene's fps), show each and save it
 *                            as P-NNNN.ppm; log `frame=N instructions=M`
 *   bench FIRST LAST STEP    render frames FIRST, FIRST+STEP, ... <= LAST without saving them;
 *                            log `frame=N instructions=M` for each, then the mean and worst
 *   show N                   render frame N, show it, log `shown frame=N` and keep it on the
 *                            display until stopped (lets a test grab the display)
 * Every command also takes the render settings of `render` (src/scene/knobs.h): --depth, --mode,
 * --grid (4 or 8: the working storage of grids 2 and 16 does not fit the board's RAM budget),
 * --threshold, --min-contrib, --octaves, --footprint; their defaults are render's. Frames are INTRO_W x
 * INTRO_H, the board's display (320x240 by default, the ARM926's; 128x64 on the M3, set by the
 * Makefile); a frame is byte for byte `build/rt-fixed render --size WxH --frame N` with the same
 * settings. It goes to the platform band by band (plat_band_*): one band where the platform
 * holds a whole frame, else a row of squares (adaptive) or of pixels (full) at a time, each band
 * taking the row of corners it shares with the one before from the working storage.
 * `instructions` is the platform clock in nanoseconds across the rendering of the bands (not the
 * handing over): under QEMU with `-icount shift=0` a guest instruction advances that clock by
 * exactly 1 ns.
 * Nothing here allocates: the scene and the adaptive mode's working storage are static.
 */
#include <stddef.h>
#include <stdint.h>

#include "knobs.h"
#include "platform.h"
#include "rt.h"
#include "scn.h"

#ifndef INTRO_W
#define INTRO_W 320
#endif
#ifndef INTRO_H
#define INTRO_H 240
#endif

/* Working storage of the adaptive and probe modes at INTRO_W (rt_render_work_size): a row of
 * corners and one square's samples, for the grids the boards offer, 4 and 8 (8 is the default),
 * or 4 alone where the build renders no grid above (RT_GRID_BUILD_MAX; its default is then 4,
 * INTRO_DEFAULT_GRID). Grid 16 needs about 10 KB more, beyond the boards' RAM budgets; grid 2,
 * whose storage would fit, is not offered (app_main). */
#define INTRO_WORK(g) ((INTRO_W - 1 + (g)-1) / (g) + 1 + ((g) + 1) * ((g) + 1))
#if RT_GRID_BUILD_MAX >= 8
#define INTRO_WORK_SAMPLES (INTRO_WORK(4) > INTRO_WORK(8) ? INTRO_WORK(4) : INTRO_WORK(8))
#else
#define INTRO_WORK_SAMPLES INTRO_WORK(4)
#endif
#ifndef INTRO_DEFAULT_GRID
#define INTRO_DEFAULT_GRID KNOBS_DEFAULT_GRID
#endif
static rt_sample intro_work[INTRO_WORK_SAMPLES];
static rt_scene intro_scene;
static knobs intro_knobs = KNOBS_DEFAULTS; /* the command's render settings */

/* A line of log text under construction. */
typedef struct intro_line {
    char s[120];
    int n;
} intro_line;

static void intro_str(intro_line *l, const char *s)
{
    while (*s && l->n < (int)sizeof l->s - 1)
        l->s[l->n++] = *s++;
    l->s[l->n] = '\0';
}

static void intro_num(intro_line *l, uint64_t v)
{
    char d[24];
    int k = 0;
    do {
        d[k++] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    while (k && l->n < (int)sizeof l->s - 1)
        l->s[l->n++] = d[--k];
    l->s[l->n] = '\0';
}

/* Logs "prefix" followed by "name=value" pairs. */
static void intro_log2(const char *a, uint64_t va, const char *b, uint64_t vb)
{
    intro_line l = {.n = 0};
    intro_str(&l, a);
    intro_num(&l, va);
    if (b) {
        intro_str(&l, b);
        intro_num(&l, vb);
    }
    plat_log(l.s);
}

/* A whole number in [0, max], or -1. */
static long intro_arg(const char *s, long max)
{
    long v;
    return knobs_number(s, -1, 0, 0, max, &v) == KNOBS_NUM_OK ? v : -1;
}

static unsigned intro_len(const char *s)
{
    unsigned n = 0;
    while (s[n])
        n++;
    return n;
}

static int intro_streq(const char *a, const char *b)
{
    while (*a && *a == *b)
        a++, b++;
    return *a == *b;
}

static long intro_last_frame(void) { return (long)scn_intro.duration_ms * scn_intro.fps / 1000; }

/* Renders the intro at time ms band by band to the display and, with dest, to that file; *ns
 * gets the platform nanoseconds spent rendering (handing the bands over not counted). Returns 0,
 * or 1 after the platform logged why. */
static int intro_render(int32_t ms, const char *dest, uint64_t *ns)
{
    scn_eval(&scn_intro, ms, &intro_scene);
    rt_params p = knobs_params(&intro_knobs, intro_scene.depth);
    rt_view v;
    rt_view_init(&v, &intro_scene.camera, INTRO_W, INTRO_H);
    rt_view_cull(&v, &intro_scene);
    plat_frame f;
    if (plat_band_begin(&f, INTRO_W, INTRO_H, dest) != 0)
        return 1;
    /* Bands of a row of squares hold at most grid + 1 <= 9 rows (app_main checks the grid). */
    int nb = f.height >= INTRO_H ? 1 : rt_render_band_count(&p, INTRO_H);
    rt_stats stats = {0};
    *ns = 0;
    for (int b = 0; b < nb; b++) {
        int y0, rows;
        rt_render_band_rows(&p, INTRO_H, b, nb, &y0, &rows);
        uint32_t *px = plat_band_rows(y0, rows);
        uint64_t t0 = plat_time_ns();
        rt_render_band_into(&intro_scene, &v, &p, px, f.stride, &stats, intro_work, NULL, b, nb,
                            b > 0);
        *ns += plat_time_ns() - t0;
        if (plat_band_present() != 0)
            return 1;
    }
    return 0;
}

static int32_t intro_frame_ms(long frame) { return (int32_t)(frame * 1000 / scn_intro.fps); }

/* play: the timeline follows the clock; a slow frame skips ahead rather than slowing down. */
static int intro_play(void)
{
    uint64_t start = plat_time_ns(), shown = 0, t_fps = start;
    intro_log2("intro: playing looped, width ", INTRO_W, ", height ", INTRO_H);
    for (;;) {
        uint64_t now = plat_time_ns(), ns;
        int32_t ms = (int32_t)((now - start) / 1000000u % (uint64_t)scn_intro.duration_ms);
        if (intro_render(ms, NULL, &ns) != 0)
            return 1;
        shown++;
        now = plat_time_ns();
        if (now - t_fps >= 5000000000u) { /* every 5 s of the board's clock */
            uint64_t fps100 = shown * 100000000000u / (now - t_fps);
            intro_line l = {.n = 0};
            intro_str(&l, "intro: t=");
            intro_num(&l, (uint64_t)ms / 1000);
            intro_str(&l, " s, fps=");
            intro_num(&l, fps100 / 100);
            intro_str(&l, fps100 % 100 < 10 ? ".0" : ".");
            intro_num(&l, fps100 % 100);
            /* under QEMU the timer follows the host: the figure is the emulator's speed */
            intro_str(&l, " by the timer (under QEMU: the emulator's speed, not the board's)");
            plat_log(l.s);
            shown = 0;
            t_fps = now;
        }
    }
}

/* Renders frame k and logs its instruction count; saves it as PREFIX-NNNN.ppm when prefix is
 * not NULL (and shows it). Adds the count to *sum and *worst. Returns 0 or 1. */
static int intro_one(long k, const char *prefix, uint64_t *sum, uint64_t *worst)
{
    intro_line path = {.n = 0};
    if (prefix) {
        intro_str(&path, prefix);
        intro_str(&path, "-");
        for (long d = 1000; d > 1 && k < d; d /= 10)
            intro_str(&path, "0");
        intro_num(&path, (uint64_t)k);
        intro_str(&path, ".ppm");
    }
    uint64_t ns;
    if (intro_render(intro_frame_ms(k), prefix ? path.s : NULL, &ns) != 0)
        return 1;
    intro_log2("frame=", (uint64_t)k, " instructions=", ns);
    *sum += ns;
    *worst = ns > *worst ? ns : *worst;
    return 0;
}

static int intro_summary(uint64_t n, uint64_t sum, uint64_t worst)
{
    intro_log2("frames=", n, " mean=", sum / n);
    intro_log2("worst=", worst, NULL, 0);
    return 0;
}

/* frames [--out PREFIX] N...: checks every number before rendering any frame. */
static int intro_frames(int argc, char **argv)
{
    const char *prefix = "intro";
    long last = intro_last_frame();
    int n = 0;
    for (int i = 0; i < argc; i++) {
        if (intro_streq(argv[i], "--out")) {
            if (++i == argc) {
                plat_log("intro: error: --out wants a path prefix");
                return 2;
            }
            prefix = argv[i];
            if (intro_len(prefix) > 100) { /* the name gets "-NNNN.ppm" and ".tmp" */
                plat_log("intro: error: --out: the path prefix is longer than 100 characters");
                return 2;
            }
        } else if (intro_arg(argv[i], last) < 0) {
            intro_log2("intro: error: frame numbers are whole numbers 0..", (uint64_t)last, NULL,
                       0);
            return 2;
        } else {
            n++;
        }
    }
    if (n == 0) {
        plat_log("intro: error: frames wants at least one frame number");
        return 2;
    }
    uint64_t sum = 0, worst = 0;
    for (int i = 0; i < argc; i++) {
        if (intro_streq(argv[i], "--out"))
            i++;
        else if (intro_one(intro_arg(argv[i], last), prefix, &sum, &worst) != 0)
            return 1;
    }
    return intro_summary((uint64_t)n, sum, worst);
}

/* bench FIRST LAST STEP */
static int intro_bench(int argc, char **argv)
{
    long last = intro_last_frame();
    long a = argc == 3 ? intro_arg(argv[0], last) : -1;
    long b = argc == 3 ? intro_arg(argv[1], last) : -1;
    long step = argc == 3 ? intro_arg(argv[2], last) : -1;
    if (a < 0 || b < a || step < 1) {
        intro_log2("intro: error: bench wants FIRST LAST STEP, FIRST <= LAST in 0..",
                   (uint64_t)last, NULL, 0);
        return 2;
    }
    uint64_t sum = 0, worst = 0, n = 0;
    for (long k = a; k <= b; k += step, n++)
        if (intro_one(k, NULL, &sum, &worst) != 0)
            return 1;
    return intro_summary(n, sum, worst);
}

/* show N */
static int intro_show(int argc, char **argv)
{
    long k = argc == 1 ? intro_arg(argv[0], intro_last_frame()) : -1;
    if (k < 0) {
        intro_log2("intro: error: show wants one frame number in 0..", (uint64_t)intro_last_frame(),
                   NULL, 0);
        return 2;
    }
    uint64_t sum = 0, worst = 0;
    if (intro_one(k, NULL, &sum, &worst) != 0)
        return 1;
    intro_log2("shown frame=", (uint64_t)k, NULL, 0);
    for (;;)
        plat_time_ns(); /* the board has nothing else to do */
}

/* Takes the render settings out of argv, in the grammar of the desktop programs (`--depth N`
 * or `--depth=N`, each at most once), keeping the other arguments in order; returns how many
 * those are, or -1 after logging what is wrong. */
static int intro_take_knobs(int argc, char **argv)
{
    int n = 0;
    unsigned given = 0;
    for (int i = 0; i < argc; i++) {
        char name[24];
        const char *v = 0, *expected = "needs a value";
        int k = 0;
        /* the name, before any '=' (too long: no setting's name) */
        while (argv[i][k] && argv[i][k] != '=' && k < (int)sizeof name - 1)
            name[k] = argv[i][k], k++;
        name[k] = '\0';
        if (argv[i][k] == '=')
            v = argv[i] + k + 1;
        int idx = argv[i][k] == '=' || !argv[i][k] ? knobs_index(name) : -1;
        if (idx < 0) {
            argv[n++] = argv[i];
            continue;
        }
        if (!v && i + 1 < argc)
            v = argv[++i];
        if (given & (1u << idx))
            expected = "is given more than once", v = 0;
        else if (v && knobs_parse(&intro_knobs, name, v, &expected) >= 0)
            expected = 0;
        given |= 1u << idx;
        if (expected) {
            intro_line l = {.n = 0};
            intro_str(&l, "intro: error: ");
            intro_str(&l, name);
            intro_str(&l, ": ");
            intro_str(&l, expected);
            if (v) {
                intro_str(&l, ", got '");
                intro_str(&l, v);
                intro_str(&l, "'");
            }
            plat_log(l.s);
            return -1;
        }
    }
    return n;
}

int app_main(int argc, char **argv)
{
#if INTRO_DEFAULT_GRID != KNOBS_DEFAULT_GRID
    intro_knobs.grid = INTRO_DEFAULT_GRID;
#endif
    if (argc > 2) {
        int n = intro_take_knobs(argc - 2, argv + 2);
        if (n < 0)
            return 2;
        argc = 2 + n;
    }
#if RT_MAX_LIGHTS < 4 || RT_MAX_MATERIALS < 16 /* below the scene parser's limits (the M boards) */
    if (scn_intro.nobjects > RT_MAX_OBJECTS || scn_intro.nlights > RT_MAX_LIGHTS ||
        scn_intro.nmaterials > RT_MAX_MATERIALS) {
        plat_log("intro: error: the compiled scene exceeds RT_MAX_OBJECTS, _LIGHTS or _MATERIALS");
        return 2;
    }
#else
    if (scn_intro.nobjects > RT_MAX_OBJECTS) {
        plat_log("intro: error: the compiled scene has more objects than RT_MAX_OBJECTS");
        return 2;
    }
#endif
    rt_params p = knobs_params(&intro_knobs, 0);
#ifdef INTRO_MAX_DEPTH /* a board whose stack holds the ray tree only so deep (the M0) */
    if (intro_knobs.depth > INTRO_MAX_DEPTH) {
        intro_log2("intro: error: --depth: the board's stack holds the ray tree to depth ",
                   INTRO_MAX_DEPTH, ", not ", (uint64_t)intro_knobs.depth);
        return 2;
    }
#endif
    if (rt_render_work_size(&p, INTRO_W) > sizeof intro_work ||
        (RT_GRID_BUILD_MAX < RT_GRID_MAX && (p.grid > RT_GRID_BUILD_MAX || p.grid < 4))) {
        intro_line l = {.n = 0};
        intro_str(&l,
                  RT_GRID_BUILD_MAX >= 8
                      ? "intro: error: --grid: the board's working storage holds grids 4 and "
                        "8, not "
                      : "intro: error: --grid: the board's working storage holds grid 4, not ");
        intro_num(&l, (uint64_t)p.grid);
        plat_log(l.s);
        return 2;
    }
    if (argc < 2 || intro_streq(argv[1], "play")) {
        if (argc > 2) {
            plat_log("intro: error: play takes no arguments");
            return 2;
        }
        return intro_play();
    }
    if (intro_streq(argv[1], "frames"))
        return intro_frames(argc - 2, argv + 2);
    if (intro_streq(argv[1], "bench"))
        return intro_bench(argc - 2, argv + 2);
    if (intro_streq(argv[1], "show"))
        return intro_show(argc - 2, argv + 2);
    plat_log("intro: error: unknown command (commands: play, frames [--out PREFIX] N..., "
             "bench FIRST LAST STEP, show N; each with render's --depth, --mode, --grid, "
             "--threshold, --min-contrib, --octaves, --footprint)");
    return 2;
}
