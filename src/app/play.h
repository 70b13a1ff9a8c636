/* play.h: the real-time player of the desktop programs (`rt-float play`, `rt-fixed play`; see play.c). */
#ifndef FIXRAY_PLAY_H
#define FIXRAY_PLAY_H

#include "rt.h"
#include "scn.h"

typedef struct play_opts {
    const scn_desc *desc; /* the scene */
    const char *name;     /* its name, for the window title */
    int width, height;    /* render size */
    int threads;
    rt_params params;       /* depth < 0: the scene's */
    long frames;            /* > 0: quit after this many frames, stepping one frame period each */
    const char *screenshot; /* save the last frame shown here (PNG or PPM), or NULL */
    int show_samples;
} play_opts;

/* Plays until Esc/Q, a closed window or `frames` frames. Returns the exit status: 0, or 1 after
 * a one-line error (no display, out of memory, screenshot not written). */
int play_run(const play_opts *o);

#endif
