/* platform.h: the boundary between fixray and the machine it runs on: one header, one .c per backend.
 *
 * A backend owns main() and the frame memory; it calls into the program (app_main) and gets
 * frames back through plat_frame_present. Pixels are 0x00RRGGBB, `stride` pixels per row.
 * Backends: platform/headless.c (image files on a desktop system), platform/arm/ (bare-metal
 * ARM926 on QEMU's versatilepb board: PL110 framebuffer, UART, semihosting files).
 */
#ifndef FIXRAY_PLATFORM_H
#define FIXRAY_PLATFORM_H

#include <stdint.h>

typedef struct plat_frame {
    uint32_t *pixels;
    int width, height, stride;
} plat_frame;

/* Gives *f a frame buffer of width x height owned by the platform until plat_frame_release.
 * Returns 0, or -1 after printing a one-line error (out of memory). */
int plat_frame_acquire(plat_frame *f, int width, int height);

/* Returns the buffer of a frame to the platform. */
void plat_frame_release(plat_frame *f);

/* Hands over a finished frame. With `dest`, writes it to that file through a temporary file and
 * a rename, so no half-written file is ever left (headless: PNG or PPM, chosen by the extension;
 * ARM: PPM on the host through semihosting, and shown on the display too). With dest NULL,
 * shows it on the display (headless: an error). Returns 0, or -1 after logging a one-line
 * error naming the file. */
int plat_frame_present(const plat_frame *f, const char *dest);

/* Monotonic time in nanoseconds, for measuring only (the picture never depends on it). On the
 * ARM board under QEMU's `-icount shift=0` one guest instruction is exactly one nanosecond
 * (the clock's step is 125/3 ns). */
uint64_t plat_time_ns(void);

/* Writes one line of text (no newline in `line`) to the log: standard error, or the UART. */
void plat_log(const char *line);

/* The program, called by the backend's main(). Returns the process exit status. */
int app_main(int argc, char **argv);

#endif
