/* platform.h: the boundary between fixray and the machine it runs on: one header, one .c per backend.
 *
 * A backend owns main() and the frame memory; it calls into the program (app_main) and gets
 * frames back through plat_frame_present. Pixels are 0x00RRGGBB, `stride` pixels per row.
 * Backends: the desktop, platform/headless.c (image files, clock, main) with threads.c (worker
 * threads) and a display: sdl.c (a window through SDL2: rt-float, rt-fixed, the intro players)
 * or null.c (none: the tools, which never open a window and link no SDL2); platform/arm/
 * (bare-metal ARM926 on QEMU's versatilepb board: PL110 framebuffer, UART, semihosting files).
 */
#ifndef FIXRAY_PLATFORM_H
#define FIXRAY_PLATFORM_H

#include <stdint.h>

typedef struct plat_frame {
    uint32_t *pixels;
    int width, height, stride;
} plat_frame;

/* Gives *f a frame buffer of width x height owned by the platform until plat_frame_release.
 * Returns 0, or -1 when there is no memory for it (the caller reports). */
int plat_frame_acquire(plat_frame *f, int width, int height);

/* Returns the buffer of a frame to the platform (nothing when it has none). */
void plat_frame_release(plat_frame *f);

/* Hands over a finished frame. With `dest`, writes it to that file through a temporary file and
 * a rename, so no half-written file is ever left (desktop: PNG or PPM, chosen by the extension;
 * ARM: PPM on the host through semihosting, and shown on the display too). With dest NULL,
 * shows it on the display. Returns 0, or -1 after logging a one-line error naming the program
 * and the file. */
int plat_frame_present(const plat_frame *f, const char *dest);

/* Monotonic time in nanoseconds, for measuring only (the picture never depends on it). On the
 * ARM board under QEMU's `-icount shift=0` one guest instruction is exactly one nanosecond
 * (the clock's step is 125/3 ns). */
uint64_t plat_time_ns(void);

/* Writes one line of text (no newline in `line`) to the log: standard error, or the UART. */
void plat_log(const char *line);

/* ---- desktop only: the program's name, for messages (platform/headless.c) ------------------ */
const char *plat_program(void);

/* ---- desktop only: worker threads (platform/threads.c) ------------------------------------ */

#define PLAT_MAX_THREADS 64

/* Processors available to this process, 1..PLAT_MAX_THREADS. */
int plat_cpu_count(void);

/* Runs job(ctx, worker) on `threads` workers at once (worker = 0 .. threads - 1; the caller is
 * worker 0) and returns when all have returned. The pool starts on first use and is kept. */
void plat_parallel(int threads, void (*job)(void *ctx, int worker), void *ctx);

/* ---- desktop only: a window and keys (platform/sdl.c; platform/null.c has none) ------------- */

/* What the player's keys ask for. */
enum plat_key {
    PLAT_KEY_NONE,
    PLAT_KEY_QUIT,
    PLAT_KEY_PAUSE,
    PLAT_KEY_SAMPLES,
    PLAT_KEY_BACK,
    PLAT_KEY_FORWARD,
    PLAT_KEY_GRID,
    PLAT_KEY_REDRAW /* not a key: the window needs its picture again */
};

/* Opens a resizable window showing frames of width x height, scaled to fit (F toggles full
 * screen). Returns 0, or -1 after printing a one-line error (no display). */
int plat_display_open(int width, int height, const char *title);

/* Shows a frame of the size the display was opened with (plat_frame_present with no file). */
int plat_display_show(const plat_frame *f);

/* The next key pressed (enum plat_key), or PLAT_KEY_NONE after waiting up to wait_ms
 * milliseconds for one (0: never waits). */
int plat_display_poll(int wait_ms);

/* A status line: the window title. */
void plat_display_status(const char *text);

void plat_display_close(void);

/* The program, called by the backend's main(). Returns the process exit status. */
int app_main(int argc, char **argv);

#endif
