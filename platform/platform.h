/* platform.h: the boundary between fixray and the machine it runs on: one header, one .c per backend.
 *
 * A backend owns main() and the frame memory; it calls into the program (app_main) and gets
 * frames back through plat_frame_present. Pixels are 0x00RRGGBB, `stride` pixels per row.
 * Backends: platform/headless.c (image files).
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

/* Hands over a finished frame. The headless backend writes it to the file `dest` (PNG or PPM,
 * chosen by the extension) through a temporary file and a rename, so no half-written file is
 * ever left. Returns 0, or -1 after printing a one-line error naming the program and the file. */
int plat_frame_present(const plat_frame *f, const char *dest);

/* Monotonic time in microseconds, for measuring only (the picture never depends on it). */
uint64_t plat_time_us(void);

/* The program, called by the backend's main(). Returns the process exit status. */
int app_main(int argc, char **argv);

#endif
