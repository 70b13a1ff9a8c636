/* player.c: the intro player, the desktop twin of the original 64 kB intro: plays the built-in intro in a window (build/intro-fixed, build/intro-float). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "outpath.h"
#include "platform.h"
#include "play.h"

extern const scn_desc scn_intro;

static const char *player_name = "intro";

/* A whole number in [lo, hi] from s, or -1 after an error naming the option. */
static long player_int(const char *opt, const char *s, long lo, long hi)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (!*s || *end || v < lo || v > hi) {
        fprintf(stderr, "%s: %s: '%s' is not a whole number in %ld..%ld\n", player_name, opt, s, lo,
                hi);
        return -1;
    }
    return v;
}

/* A side of --size: digits only, 1..4096; the character after it in *end. */
static int player_side(const char *s, const char **end)
{
    long v = 0;
    const char *p = s;
    while (*p >= '0' && *p <= '9' && v <= 4096)
        v = v * 10 + (*p++ - '0');
    *end = p;
    return p > s && v >= 1 && v <= 4096 ? (int)v : -1;
}

int app_main(int argc, char **argv)
{
    if (argc > 0 && argv[0][0]) {
        const char *slash = strrchr(argv[0], '/');
        player_name = slash ? slash + 1 : argv[0];
    }
    play_opts o = {.desc = &scn_intro,
                   .name = "intro",
                   .width = 640,
                   .height = 480,
                   .threads = plat_cpu_count(),
                   .params = {.depth = -1,
                              .min_contrib = RT_DEFAULT_MIN_CONTRIB,
                              .mode = RT_MODE_ADAPTIVE,
                              .grid = RT_DEFAULT_GRID,
                              .threshold = RT_DEFAULT_THRESHOLD}};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            printf("usage: %s [--size WxH] [--threads N] [--frames N] [--screenshot FILE]\n"
                   "plays the fixray intro in a window: Esc/Q quit, Space pause, F full screen,\n"
                   "S traced points, Left/Right seek 5 s, G grid size (build/rt-%s play has every "
                   "option)\n",
                   player_name, REAL_NAME);
            return 0;
        }
        int known = strcmp(a, "--size") == 0 || strcmp(a, "--threads") == 0 ||
            strcmp(a, "--frames") == 0 || strcmp(a, "--screenshot") == 0;
        if (!v || !known) {
            fprintf(stderr, "%s: %s: %s (see %s --help)\n", player_name, a,
                    known ? "needs a value" : "unknown option", player_name);
            return 2;
        }
        i++;
        if (strcmp(a, "--size") == 0) {
            const char *e;
            int w = player_side(v, &e), h = *e == 'x' ? player_side(e + 1, &e) : -1;
            if (w < 0 || h < 0 || *e) {
                fprintf(stderr, "%s: --size: '%s' is not WxH with sides 1..4096\n", player_name, v);
                return 2;
            }
            o.width = w;
            o.height = h;
        } else if (strcmp(a, "--threads") == 0) {
            long n = player_int(a, v, 1, PLAT_MAX_THREADS);
            if (n < 0)
                return 2;
            o.threads = (int)n;
        } else if (strcmp(a, "--frames") == 0) {
            if ((o.frames = player_int(a, v, 1, 100000000)) < 0)
                return 2;
        } else if (strcmp(a, "--screenshot") == 0) {
            char err[600];
            if (!img_path_ok(v)) {
                fprintf(stderr, "%s: --screenshot: the file must end in .png or .ppm, got '%s'\n",
                        player_name, v);
                return 2;
            }
            if (outpath_check(v, err, sizeof err) != 0) {
                fprintf(stderr, "%s: %s\n", player_name, err);
                return 2;
            }
            o.screenshot = v;
        } else {
            fprintf(stderr, "%s: %s: unknown option (see %s --help)\n", player_name, a,
                    player_name);
            return 2;
        }
    }
    return play_run(&o);
}
