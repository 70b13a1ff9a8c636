/* cli.h: the command line of the desktop programs: one option table for render, play, the intro players and rt-edges, one grammar and one set of messages (see cli.c). */
#ifndef FIXRAY_CLI_H
#define FIXRAY_CLI_H

#include <stdio.h>

#include "knobs.h"
#include "play.h"

/* fixray's version, printed by --version. */
#define CLI_VERSION_NAME "1.0"

#define CLI_MAX_SIDE 4096
#define CLI_MAX_TIME_MS SCN_MAX_DURATION_MS
#define CLI_MAX_FRAME ((long)CLI_MAX_TIME_MS / 1000 * SCN_MAX_FPS) /* of the longest scene */

/* The commands, as bits: the commands an option belongs to. */
enum cli_cmd {
    CLI_RENDER = 1, /* rt-float/rt-fixed render */
    CLI_PLAY = 2,   /* rt-float/rt-fixed play */
    CLI_INTRO = 4,  /* the intro players, build/intro-*: play without --scene */
    CLI_EDGES = 8   /* rt-edges */
};

/* Everything a command line can say; cli_defaults gives what it says when it says nothing. */
typedef struct cli_opts {
    const char *output; /* -o: NULL until given */
    int width, height;
    const char *scene; /* NULL: the built-in intro */
    int32_t time_ms;
    long frame;
    int have_time, have_frame;
    long first, last, step; /* render --frames: a range, last = -1 for the scene's last frame */
    int have_frames, have_step;
    int checksum, progress;
    int effects_all;
    knobs k; /* --depth, --mode, --grid, --threshold, --min-contrib, --octaves */
    int stats;
    int show_samples;
    int threads;            /* 1..PLAT_MAX_THREADS */
    long play_frames;       /* play --frames N: quit after N frames (0: run until quit) */
    const char *screenshot; /* play --screenshot FILE */
} cli_opts;

/* The defaults of command `cmd` (one enum cli_cmd). */
cli_opts cli_defaults(int cmd);

/* Parses the options of command `cmd` (argv: what follows the program and command names) into
 * *o, which holds cli_defaults(cmd). The grammar: `--opt value` or `--opt=value`, flags without
 * a value, each option at most once. Returns 0; -1 after printing the help or the version
 * (--help, --version: exit status 0); or 2 after a one-line error on standard error. Checks
 * each value alone; what options say together is the command's to check. */
int cli_parse(int cmd, int argc, char **argv, cli_opts *o);

/* The usage of the program whose commands are the bits of `cmds`, generated from the table. */
void cli_usage(FILE *f, int cmds);

/* "--version": the program, fixray's version, the number system. */
void cli_version(FILE *f);

/* Prints "PROGRAM: OPTION: WHAT, got 'VALUE' (see PROGRAM --help)" (no ", got" part when value
 * is NULL) on standard error and returns 2, the exit status of a bad command line. */
int cli_error(const char *option, const char *what, const char *value);

/* The player's settings of a parsed play (or intro player) command line; desc and name are the
 * caller's. */
play_opts cli_play_opts(const cli_opts *o);

#endif
