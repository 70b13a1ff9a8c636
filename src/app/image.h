/* image.h: reading and writing image files (PNG through libpng, binary PPM) on the host. */
#ifndef FIXRAY_IMAGE_H
#define FIXRAY_IMAGE_H

#include <stddef.h>
#include <stdint.h>

/* An 8-bit RGB image, rows packed (3 * width bytes per row). */
typedef struct img_rgb {
    int width, height;
    uint8_t *rgb;
} img_rgb;

/* Reads a PNG or PPM (P6, maxval 255) file, told apart by content. Returns 0, or -1 with a
 * one-line reason in err. The caller frees with img_free. */
int img_load(const char *path, img_rgb *out, char *err, size_t errlen);

void img_free(img_rgb *im);

/* Writes 0x00RRGGBB pixels as PNG or PPM, chosen by the extension of path (.png, .ppm), through
 * a temporary file in the same folder renamed into place. Returns 0, or -1 with a reason. */
int img_save(const char *path, const uint32_t *pixels, int width, int height, int stride, char *err,
             size_t errlen);

/* Nonzero when path ends in an extension img_save can write. */
int img_path_ok(const char *path);

#endif
