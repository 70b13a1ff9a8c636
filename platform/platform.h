/* platform.h: the boundary between fixray and the machine it runs on: one header, one .c per backend.
 *
 * A backend owns main() and the frame memory; it calls into the program (app_main) and gets
 * frames back through plat_frame_present. Pixels are 0x00RRGGBB, `stride` pixels per row.
 * Backends: the desktop, platform/headless.c (image files, clock, main) with threads.c (worker
 * threads) and a display: sdl.c (a window through SDL2: rt-float, rt-fixed, the intro players)
 * or null.c (none: the tools, which never open a window and link no SDL2); platform/arm/
 * (bare-metal ARM926 on QEMU's versatilepb board: PL110 framebuffer, UART, semihosting files);
 * platform/m3/ (bare-metal Cortex-M3 on QEMU's lm3s6965evb: a 128x64 grey OLED that keeps its
 * own pixels, so frames reach it band by band and no frame is ever in RAM).
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

/* ---- the boards: a frame handed over band by band (platform/arm/, platform/m3/) ------------ */

/* Starts a frame of width x height that the program hands over in bands of whole rows, top to
 * bottom. Sets f->width, f->stride and f->height: the most rows a band may have, the whole frame
 * where there is a framebuffer (ARM926), a few rows where the display keeps its own pixels (M3).
 * dest as for plat_frame_present, written as the bands come. Returns 0, or -1 after logging
 * (a frame larger than the board's, a file that cannot be created). */
int plat_band_begin(plat_frame *f, int width, int height, const char *dest);

/* The memory for rows y0 .. y0 + rows - 1 of the frame begun, rows <= the f->height that
 * plat_band_begin set, y0 the row after the previous band's: row y0 first, f->stride apart. */
uint32_t *plat_band_rows(int y0, int rows);

/* Hands over the band of the last plat_band_rows, its pixels rendered. The band that ends the
 * frame also shows it and finishes its file. Returns 0, or -1 after logging: the frame is then
 * abandoned and no file is left. */
int plat_band_present(void);

/* A pixel's grey on a 16-level display (the M3's OLED, and rt-cmp --oled on the host): luma
 * (77 R + 150 G + 29 B) / 256, rounded, then quantised to 0..15, rounded. The display shows
 * level n as 17 n. */
static inline unsigned plat_grey4(uint32_t rgb)
{
    unsigned y = (77u * (rgb >> 16 & 255) + 150u * (rgb >> 8 & 255) + 29u * (rgb & 255) + 128) >> 8;
    return (y * 15 + 127) / 255;
}

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
