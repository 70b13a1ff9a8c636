/* fuzz_cli.c: libFuzzer harness: bytes become a command line (words split at NUL bytes) of render, play, the intro player or rt-edges, parsed through cli.c's one option table. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "noise.h"
#include "platform.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The platform's two functions cli.c asks for: the program's name (for messages) and the
 * processor count (--threads' default). */
const char *plat_program(void) { return "rt"; }
int plat_cpu_count(void) { return 2; }

static FILE *fc_err; /* standard error of each parse, read back */

static void fc_fail(const char *what, long a, long b)
{
    fprintf(stderr, "fuzz_cli: %s (%ld, %ld)\n", what, a, b);
    abort();
}

/* Parses argv for cmd with standard error going to fc_err; returns cli_parse's result and the
 * bytes written there in *out (NUL-terminated, at most n - 1). */
static int fc_parse(int cmd, int argc, char **argv, cli_opts *o, char *out, size_t n)
{
    fflush(stderr);
    int saved = dup(2);
    rewind(fc_err);
    if (saved < 0 || ftruncate(fileno(fc_err), 0) != 0 || dup2(fileno(fc_err), 2) < 0)
        fc_fail("cannot redirect standard error", 0, 0);
    int rc = cli_parse(cmd, argc, argv, o);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    rewind(fc_err);
    size_t got = fread(out, 1, n - 1, fc_err);
    out[got] = 0;
    return rc;
}

/* Field by field (the struct's padding is not part of the result). */
static int fc_same(const cli_opts *a, const cli_opts *b)
{
    return a->output == b->output && a->width == b->width && a->height == b->height &&
        a->scene == b->scene && a->time_ms == b->time_ms && a->frame == b->frame &&
        a->have_time == b->have_time && a->have_frame == b->have_frame && a->first == b->first &&
        a->last == b->last && a->step == b->step && a->have_frames == b->have_frames &&
        a->have_step == b->have_step && a->checksum == b->checksum && a->progress == b->progress &&
        a->effects_all == b->effects_all && memcmp(&a->k, &b->k, sizeof a->k) == 0 &&
        a->stats == b->stats && a->show_samples == b->show_samples && a->threads == b->threads &&
        a->play_frames == b->play_frames && a->screenshot == b->screenshot;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const int cmds[4] = {CLI_RENDER, CLI_PLAY, CLI_INTRO, CLI_EDGES};
    if (size < 1 || size > 2048)
        return 0;
    if (!fc_err && !(fc_err = tmpfile()))
        fc_fail("cannot open a temporary file", 0, 0);
    int cmd = cmds[data[0] & 3];
    static char buf[2048];
    char *argv[64];
    int argc = 0;
    memcpy(buf, data + 1, size - 1);
    buf[size - 1] = 0;
    for (size_t i = 0; i < size - 1 && argc < 64; i += strlen(buf + i) + 1)
        argv[argc++] = buf + i;
    cli_opts o = cli_defaults(cmd), o2 = cli_defaults(cmd);
    char err[1024], err2[1024];
    int rc = fc_parse(cmd, argc, argv, &o, err, sizeof err);
    char *nl = strchr(err, '\n');
    if (rc == 2) {
        /* one line: "rt: OPTION: WHAT ..." */
        if (strncmp(err, "rt: ", 4) != 0 || !nl || nl[1] || nl - err < 8)
            fc_fail("a refusal without one line on standard error", (long)strlen(err), 0);
    } else if (rc == 0 || rc == -1) {
        if (err[0])
            fc_fail("standard error written without a refusal", rc, (long)strlen(err));
    } else {
        fc_fail("cli_parse returned something else than 0, -1 or 2", rc, 0);
    }
    if (rc == 0) {
        /* every value within the range its message states */
        if (o.width < 1 || o.width > CLI_MAX_SIDE || o.height < 1 || o.height > CLI_MAX_SIDE)
            fc_fail("size", o.width, o.height);
        if (o.threads < 1 || o.threads > PLAT_MAX_THREADS)
            fc_fail("threads", o.threads, 0);
        if (o.time_ms < 0 || o.time_ms > CLI_MAX_TIME_MS || o.frame < 0 || o.frame > CLI_MAX_FRAME)
            fc_fail("time or frame", o.time_ms, o.frame);
        if (o.have_frames &&
            (o.first < 0 || (o.last != -1 && o.last < o.first) || o.last > CLI_MAX_FRAME))
            fc_fail("frames", o.first, o.last);
        if (o.step < 1 || o.step > CLI_MAX_FRAME || o.play_frames < 0 ||
            o.play_frames > CLI_MAX_FRAME)
            fc_fail("step or play frames", o.step, o.play_frames);
        const knobs *k = &o.k;
        if (k->depth < -1 || k->depth > RT_MAX_DEPTH || k->octaves < 0 ||
            k->octaves > RT_NOISE_MAX_OCTAVES || k->threshold < 0 || k->threshold > KNOBS_SCALE ||
            k->min_contrib < 0 || k->min_contrib > KNOBS_SCALE ||
            (k->grid != 2 && k->grid != 4 && k->grid != 8 && k->grid != 16))
            fc_fail("settings", k->depth, k->grid);
        /* the strings kept are words of the command line */
        const char *strs[3] = {o.output, o.scene, o.screenshot};
        for (int i = 0; i < 3; i++)
            if (strs[i] && (strs[i] < buf || strs[i] >= buf + size))
                fc_fail("a kept string is not a word of the command line", i, 0);
    }
    /* the same words parse the same way again */
    int rc2 = fc_parse(cmd, argc, argv, &o2, err2, sizeof err2);
    if (rc2 != rc || strcmp(err, err2) != 0 || (rc == 0 && !fc_same(&o, &o2)))
        fc_fail("two parses of the same words differ", rc, rc2);
    return 0;
}
