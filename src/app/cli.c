/* cli.c: the option table of render, play, the intro players and rt-edges: the grammar, the values, the messages and the usage text, all from one row per option. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "eline.h"
#include "image.h"
#include "outpath.h"
#include "platform.h"

/* What an option sets; cli_set turns its value into cli_opts. */
enum cli_id {
    CLI_HELP,
    CLI_VERSION,
    CLI_SCENE,
    CLI_OUTPUT,
    CLI_SIZE,
    CLI_TIME,
    CLI_FRAME,
    CLI_FRAMES,
    CLI_STEP,
    CLI_CHECKSUM,
    CLI_PROGRESS,
    CLI_KNOB, /* a render setting: knobs.c parses it (the boards share that parser) */
    CLI_EFFECTS,
    CLI_SHOW_SAMPLES,
    CLI_THREADS,
    CLI_STATS,
    CLI_PLAY_FRAMES,
    CLI_SCREENSHOT
};

#define CLI_R CLI_RENDER
#define CLI_P (CLI_PLAY | CLI_INTRO) /* the players: play and the intro players */
#define CLI_ALL (CLI_R | CLI_P | CLI_EDGES)

/* The options, in the order of the usage text. `arg` names the value (NULL: a flag); in `help`
 * a '\n' starts a continuation line, "%d" is the number of processors, "%%" a '%'. Two rows may
 * share a name when they belong to different commands (render's and play's --frames). */
_Static_assert(CLI_MAX_SIDE == 4096 && CLI_MAX_TIME_MS == 3600000 && RT_MAX_DEPTH == 8 &&
                   KNOBS_DEFAULT_GRID == 8 && KNOBS_DEFAULT_THRESHOLD == 625 &&
                   KNOBS_DEFAULT_MIN_CONTRIB == 100 && PLAT_MAX_THREADS == 64,
               "cli_table's help states the limits and defaults");
/* The players (build/intro-*, compiled with -DCLI_PLAYER=1) must fit in 64 kB: the rows they
 * do not take are left out of them (#if !CLI_PLAYER), and with them the code of those options;
 * their help lists the options' names only. */
#ifndef CLI_PLAYER
#define CLI_PLAYER 0
#endif
#if CLI_PLAYER
#define CLI_HELP_TEXT(s) NULL
#else
#define CLI_HELP_TEXT(s) s
#endif
static const struct cli_option {
    const char *name, *alias, *arg;
    unsigned cmds;
    int id;
    const char *help;
} cli_table[] = {
#if !CLI_PLAYER
    {"--scene", NULL, "FILE", CLI_R | CLI_PLAY | CLI_EDGES, CLI_SCENE,
     "scene file (docs/scene-format.md; default: the built-in intro,\nscenes/intro.scene)"},
    {"--output", "-o", "FILE", CLI_R, CLI_OUTPUT,
     "output image, .png or .ppm (default frame.png); with --frames\na pattern with one "
     "frame-number field, e.g. out/intro-%%04d.png"},
#endif
    {"--size", NULL, "WxH", CLI_ALL, CLI_SIZE,
     CLI_HELP_TEXT("image size, each side 1..4096 (default 320x240 for render and\nrt-edges, "
                   "640x480 for the players)")},
#if !CLI_PLAYER
    {"--time", NULL, "SECONDS", CLI_R | CLI_EDGES, CLI_TIME,
     "moment of the scene's timeline, e.g. 2.5 (default 0)"},
    {"--frame", NULL, "N", CLI_R, CLI_FRAME,
     "frame N at the scene's frame rate (instead of --time)"},
    {"--frames", NULL, "A-B", CLI_R, CLI_FRAMES,
     "frames A to B, one file each (-o pattern); --frames all: every\nframe of the scene"},
    {"--step", NULL, "N", CLI_R, CLI_STEP,
     "with --frames: every Nth frame of the range (default 1)"},
    {"--checksum", NULL, NULL, CLI_R, CLI_CHECKSUM,
     "print [frame=N] time_ms=T fnv64=H per frame (64-bit FNV-1a of the\nRGB bytes; frame= "
     "with --frame and --frames); writes no image\nunless -o is given"},
    {"--progress", NULL, NULL, CLI_R, CLI_PROGRESS,
     "a progress line on standard error (default with --frames when\nstandard error is a "
     "terminal)"},
    {"--depth", NULL, "N", CLI_R | CLI_PLAY | CLI_EDGES, CLI_KNOB,
     "recursion limit 0..8 (default: the scene's)"},
    {"--mode", NULL, "M", CLI_R | CLI_PLAY, CLI_KNOB,
     "full (trace every pixel), adaptive (default) or probe (new\npoints probed first, "
     "shaded in full only where needed)"},
    {"--grid", NULL, "N", CLI_R | CLI_PLAY | CLI_EDGES, CLI_KNOB,
     "adaptive: square size 2, 4, 8 or 16 (default 8)"},
    {"--threshold", NULL, "X", CLI_R | CLI_PLAY | CLI_EDGES, CLI_KNOB,
     "adaptive: split squares whose corners' colour contributions\ndiffer by more than X, 0..1 "
     "(default 0.0625; 1 = never)"},
    {"--min-contrib", NULL, "X", CLI_R | CLI_PLAY | CLI_EDGES, CLI_KNOB,
     "skip secondary rays weighing less than X in the pixel, 0..1\n(default 0.01; 0 = trace "
     "every ray)"},
    {"--octaves", NULL, "N", CLI_R | CLI_PLAY | CLI_EDGES, CLI_KNOB,
     "noise textures sum at most N octaves, 1..8 (default: each\ntexture's own count, from the "
     "scene)"},
    {"--footprint", NULL, "F", CLI_R | CLI_PLAY | CLI_EDGES, CLI_KNOB,
     "on: noise octaves finer than a pixel are left out, the last\none faded (default); off: "
     "every octave"},
    {"--effects", NULL, "E", CLI_R, CLI_EFFECTS,
     "auto: trace only the effects the frame needs (default);\nall: every effect on, for "
     "comparison"},
    {"--show-samples", NULL, NULL, CLI_R | CLI_PLAY, CLI_SHOW_SAMPLES,
     "paint every traced point white (cyan: its local part taken\nfrom its square's corners; "
     "magenta: only probed)"},
#endif
    {"--threads", NULL, "N", CLI_R | CLI_P, CLI_THREADS,
     CLI_HELP_TEXT("render on N threads, 1..64 (default: every processor, %d\nhere); the "
                   "picture is the same for any N")},
#if !CLI_PLAYER
    {"--stats", NULL, NULL, CLI_R, CLI_STATS,
     "print key=value statistics on standard output (with --frames:\nsummed over the frames)"},
#endif
    {"--frames", NULL, "N", CLI_P, CLI_PLAY_FRAMES,
     CLI_HELP_TEXT("quit after N frames, stepping the timeline by exactly one frame\nperiod "
                   "each (a scripted, reproducible run)")},
    {"--screenshot", NULL, "FILE", CLI_P, CLI_SCREENSHOT,
     CLI_HELP_TEXT("save the last frame shown (.png or .ppm)")},
    {"--help", "-h", NULL, CLI_ALL, CLI_HELP, CLI_HELP_TEXT("print this help")},
    {"--version", NULL, NULL, CLI_ALL, CLI_VERSION,
     CLI_HELP_TEXT("print the version and the number system")},
};
#define CLI_NOPTS (int)(sizeof cli_table / sizeof *cli_table)
_Static_assert(CLI_NOPTS <= 32, "cli_parse's `given` has one bit per row");

cli_opts cli_defaults(int cmd)
{
    int player = (cmd & CLI_P) != 0;
    return (cli_opts){.width = player ? 640 : 320,
                      .height = player ? 480 : 240,
                      .k = KNOBS_DEFAULTS,
                      .step = 1,
                      .threads = plat_cpu_count()};
}

int cli_error(const char *option, const char *what, const char *value)
{
    const char *p = plat_program();
    if (value)
        eline_print("%s: %s: %s, got '%s' (see %s --help)", p, option, what, value, p);
    else
        eline_print("%s: %s: %s (see %s --help)", p, option, what, p);
    return 2;
}

void cli_version(FILE *f)
{
    fprintf(f, "%s (fixray) %s, %s\n", plat_program(), CLI_VERSION_NAME, REAL_NAME);
}

#if !CLI_PLAYER
#define CLI_KEYS \
    "  keys: Esc or Q quit, Space pause, F full screen, S traced points, Left/Right seek\n" \
    "  5 s, G grid size (2, 4, 8, 16); the title shows frames per second and ms per frame\n"

/* The commands of rt-float/rt-fixed and rt-edges: name ("" for a program that is one
 * command), what they do, what the usage adds after their options. */
static const struct cli_command {
    int cmd;
    const char *name, *summary, *more;
} cli_commands[] = {
    {CLI_RENDER, "render", "render frames of a scene to image files", NULL},
    {CLI_PLAY, "play", "play a scene in a window, in real time", CLI_KEYS},
    {CLI_EDGES, "", "how few points adaptive subsampling could trace",
     "Traces every pixel of the scene at that moment (float; the settings and their defaults\n"
     "as for rt-float render) and counts the pixels that are a corner of some 1x1 cell whose\n"
     "four corners the split criteria tell apart (object, light state, secondary objects,\n"
     "contribution beyond --threshold). Adaptive subsampling must trace each of them, besides\n"
     "the --grid corners, to resolve every such edge to the pixel: pixels / that count bounds\n"
     "its x_samples. Prints key=value lines. --scene is required.\n"},
};

static const struct cli_command *cli_command(int cmd)
{
    for (size_t i = 0; i < sizeof cli_commands / sizeof *cli_commands; i++)
        if (cli_commands[i].cmd == cmd)
            return &cli_commands[i];
    return &cli_commands[0];
}

/* A help text: "\n" continues at column `indent`, "%d" is the number of processors. */
static void cli_text(FILE *f, const char *s, int indent)
{
    for (; *s; s++) {
        if (*s == '\n')
            fprintf(f, "\n%*s", indent, "");
        else if (s[0] == '%' && s[1] == 'd')
            fprintf(f, "%d", plat_cpu_count()), s++;
        else if (s[0] == '%' && s[1] == '%')
            fputc('%', f), s++;
        else
            fputc(*s, f);
    }
    fputc('\n', f);
}

static void cli_row(FILE *f, const struct cli_option *r)
{
    char left[40];
    snprintf(left, sizeof left, "%s%s%s%s%s", r->alias ? r->alias : "", r->alias ? ", " : "",
             r->name, r->arg ? " " : "", r->arg ? r->arg : "");
    fprintf(f, "  %-19s ", left);
    cli_text(f, r->help, 22);
}

void cli_usage(FILE *f, int cmds)
{
    const char *p = plat_program();
    int shown = 0, printed[CLI_NOPTS] = {0};
    for (int c = 1; c <= CLI_EDGES; c <<= 1) {
        const struct cli_command *k = cli_command(c);
        if (!(cmds & c))
            continue;
        fprintf(f, "%s %s%s%s [options]  ", shown ? "      " : "usage:", p, *k->name ? " " : "",
                k->name);
        cli_text(f, k->summary, 2);
        shown++;
    }
    fprintf(f, "       %s%s--help | --version\n", p, cmds & CLI_RENDER ? " help | " : " ");
    for (int c = 1; c <= CLI_EDGES; c <<= 1) {
        const struct cli_command *k = cli_command(c);
        int shared = 0;
        if (!(cmds & c))
            continue;
        if (shown > 1)
            fprintf(f, "%s:", k->name);
        /* rows already described above: their names only */
        for (int i = 0, col = (int)strlen(k->name) + 1; i < CLI_NOPTS; i++)
            if ((cli_table[i].cmds & c) && printed[i] && cli_table[i].id != CLI_HELP &&
                cli_table[i].id != CLI_VERSION) {
                if (col + (int)strlen(cli_table[i].name) > 90)
                    col = fprintf(f, ",\n ") - 2;
                else if (shared)
                    col += fprintf(f, ",");
                col += fprintf(f, " %s", cli_table[i].name);
                shared++;
            }
        if (shared)
            fprintf(f, " as above, and");
        if (shown > 1)
            fputc('\n', f);
        for (int i = 0; i < CLI_NOPTS; i++)
            if ((cli_table[i].cmds & c) && !printed[i]) {
                cli_row(f, &cli_table[i]);
                printed[i] = 1;
            }
        if (k->more)
            fputs(k->more, f);
    }
    fprintf(f,
            "Errors get one line on standard error: exit status 2 for bad options, scenes and\n"
            "output names (all refused before rendering), 1 when writing a file fails.\n"
            "Number system of this build: %s.\n",
            REAL_NAME);
}

#else
/* The players' usage: the options' names; the help of rt-float and rt-fixed describes them. */
void cli_usage(FILE *f, int cmds)
{
    (void)cmds;
    fprintf(f, "usage: %s [options]  play the fixray intro in a window, in real time\n ",
            plat_program());
    for (int i = 0; i < CLI_NOPTS; i++)
        fprintf(f, " %s%s%s", cli_table[i].name, cli_table[i].arg ? " " : "",
                cli_table[i].arg ? cli_table[i].arg : "");
    fprintf(f,
            "\n  as for build/rt-%s play (see its --help); keys: Esc or Q quit, Space pause,\n"
            "  F full screen, S traced points, Left/Right seek 5 s, G grid size\n",
            REAL_NAME);
}
#endif

/* The commands of the rows named `name` (bits), and in *row the one of command cmd, or -1. */
static unsigned cli_find(const char *name, int cmd, int *row)
{
    unsigned cmds = 0;
    *row = -1;
    for (int i = 0; i < CLI_NOPTS; i++) {
        const struct cli_option *r = &cli_table[i];
        if (strcmp(name, r->name) != 0 && !(r->alias && strcmp(name, r->alias) == 0))
            continue;
        cmds |= r->cmds;
        if (r->cmds & (unsigned)cmd)
            *row = i;
    }
    return cmds;
}

#if !CLI_PLAYER
/* "--frames: is an option of render, not of play". */
static int cli_not_here(const char *name, unsigned cmds, int cmd)
{
    char what[160] = "is an option of ";
    int n = 0;
    for (int c = CLI_RENDER; c <= CLI_PLAY; c <<= 1)
        if (cmds & (unsigned)c) {
            strcat(what, n++ ? " and " : "");
            strcat(what, cli_command(c)->name);
        }
    strcat(what, ", not of ");
    strcat(what, *cli_command(cmd)->name ? cli_command(cmd)->name : plat_program());
    return cli_error(name, what, NULL);
}

#endif

/* WxH (or WXH), each side 1..CLI_MAX_SIDE. */
static int cli_size(const char *s, int *w, int *h)
{
    const char *x = s;
    long a, b;
    while (*x && *x != 'x' && *x != 'X')
        x++;
    if (!*x || knobs_number(s, (int)(x - s), 0, 1, CLI_MAX_SIDE, &a) != KNOBS_NUM_OK ||
        knobs_number(x + 1, -1, 0, 1, CLI_MAX_SIDE, &b) != KNOBS_NUM_OK)
        return -1;
    *w = (int)a;
    *h = (int)b;
    return 0;
}

#if !CLI_PLAYER
/* render --frames: "FIRST-LAST" or "all" (then *last = -1: the scene's last frame). */
static int cli_frames(const char *s, long *first, long *last)
{
    const char *dash = strchr(s, '-');
    if (strcmp(s, "all") == 0) {
        *first = 0;
        *last = -1;
        return 0;
    }
    if (!dash || knobs_number(s, (int)(dash - s), 0, 0, CLI_MAX_FRAME, first) != KNOBS_NUM_OK)
        return -1;
    return knobs_number(dash + 1, -1, 0, *first, CLI_MAX_FRAME, last) == KNOBS_NUM_OK ? 0 : -1;
}

#endif

/* A whole number in [lo, hi]. */
static int cli_whole(const char *s, long lo, long hi, long *out)
{
    return knobs_number(s, -1, 0, lo, hi, out) == KNOBS_NUM_OK ? 0 : -1;
}

/* Sets the option of row r from its value v. Returns 0, -1 for --help and --version (printed),
 * or 2 after the error. */
static int cli_set(const struct cli_option *r, const char *name, const char *v, int cmd,
                   cli_opts *o)
{
    const char *expected = NULL;
    long n = 0;
    char err[600];
    switch (r->id) {
    case CLI_HELP:
        cli_usage(stdout, cmd & (CLI_RENDER | CLI_PLAY) ? CLI_RENDER | CLI_PLAY : cmd);
        return -1;
    case CLI_VERSION: cli_version(stdout); return -1;
    case CLI_SIZE:
        if (cli_size(v, &o->width, &o->height) != 0)
            expected = "expected WxH with W and H in 1..4096";
        break;
    case CLI_THREADS:
        if (cli_whole(v, 1, PLAT_MAX_THREADS, &n) != 0)
            expected = "expected a number of threads in 1..64";
        o->threads = (int)n;
        break;
#if !CLI_PLAYER
    case CLI_SCENE: o->scene = v; break;
    case CLI_OUTPUT: o->output = v; break;
    case CLI_TIME:
        if (knobs_number(v, -1, 3, 0, CLI_MAX_TIME_MS, &n) != KNOBS_NUM_OK)
            expected = "expected seconds in 0..3600 with at most 3 decimals";
        o->time_ms = (int32_t)n;
        o->have_time = 1;
        break;
    case CLI_FRAME:
        if (cli_whole(v, 0, CLI_MAX_FRAME, &o->frame) != 0)
            expected = "expected a frame number (0 or more)";
        o->have_frame = 1;
        break;
    case CLI_FRAMES:
        if (cli_frames(v, &o->first, &o->last) != 0)
            expected = "expected FIRST-LAST frame numbers with FIRST <= LAST, or all";
        o->have_frames = 1;
        break;
    case CLI_STEP:
        if (cli_whole(v, 1, CLI_MAX_FRAME, &o->step) != 0)
            expected = "expected a whole number of frames, 1 or more";
        o->have_step = 1;
        break;
    case CLI_CHECKSUM: o->checksum = 1; break;
    case CLI_PROGRESS: o->progress = 1; break;
    case CLI_KNOB:
        if (knobs_parse(&o->k, r->name, v, &expected) >= 0)
            expected = NULL;
        break;
    case CLI_EFFECTS:
        if (strcmp(v, "auto") == 0 || strcmp(v, "all") == 0)
            o->effects_all = strcmp(v, "all") == 0;
        else
            expected = "expected auto or all";
        break;
    case CLI_SHOW_SAMPLES: o->show_samples = 1; break;
    case CLI_STATS: o->stats = 1; break;
#endif
    case CLI_PLAY_FRAMES:
        if (cli_whole(v, 1, CLI_MAX_FRAME, &o->play_frames) != 0)
            expected = "expected a number of frames, 1 or more";
        break;
    case CLI_SCREENSHOT:
        if (!img_path_ok(v))
            return cli_error(name, "the screenshot must end in .png or .ppm", v);
        if (outpath_check(v, err, sizeof err) != 0) {
            eline_print("%s: %s", plat_program(), err);
            return 2;
        }
        o->screenshot = v;
        break;
    }
    return expected ? cli_error(name, expected, v) : 0;
}

int cli_parse(int cmd, int argc, char **argv, cli_opts *o)
{
    uint32_t given = 0; /* one bit per row */
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *eq = a[0] == '-' ? strchr(a, '=') : NULL;
        char name[32];
        int row;
        /* --opt=value (or -o=value): the name before the '=' */
        if (eq && (size_t)(eq - a) < sizeof name) {
            memcpy(name, a, (size_t)(eq - a));
            name[eq - a] = 0;
        } else {
            snprintf(name, sizeof name, "%s", a);
            eq = NULL;
        }
        unsigned cmds = cli_find(name, cmd, &row);
#if !CLI_PLAYER
        if (row < 0 && cmds)
            return cli_not_here(name, cmds, cmd);
#else
        (void)cmds; /* the players hold only their own rows */
#endif
        if (row < 0)
            return cli_error(eq ? name : a, "unknown option", NULL);
        const struct cli_option *r = &cli_table[row];
        const char *v = eq ? eq + 1 : NULL;
        if (r->arg && !v) {
            if (i + 1 == argc)
                return cli_error(name, "needs a value", NULL);
            v = argv[++i];
        } else if (!r->arg && v) {
            return cli_error(name, "takes no value", v);
        }
        if (r->arg && !*v)
            return cli_error(name, "needs a value, not an empty one", NULL);
        if (given & (1u << row))
            return cli_error(name, "is given more than once", NULL);
        given |= 1u << row;
        int rc = cli_set(r, name, v, cmd, o);
        if (rc != 0)
            return rc;
    }
    return 0;
}

play_opts cli_play_opts(const cli_opts *o)
{
    return (play_opts){.width = o->width,
                       .height = o->height,
                       .threads = o->threads,
                       .frames = o->play_frames,
                       .screenshot = o->screenshot,
                       .show_samples = o->show_samples,
                       .params = knobs_params(&o->k, -1)};
}
