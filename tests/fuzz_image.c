/* fuzz_image.c: libFuzzer harness: bytes become an image file read by img_load (image.c: PNG through libpng, binary PPM), as rt-cmp reads its inputs. */
#define _GNU_SOURCE /* memmem */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char fi_path[64];

static void fi_fail(const char *what, long a, long b)
{
    fprintf(stderr, "fuzz_image: %s (%ld, %ld)\n", what, a, b);
    abort();
}

static void fi_cleanup(void) { unlink(fi_path); }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!fi_path[0]) {
        /* one file for every input, in memory where the system has a tmpfs */
        const char *dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
        snprintf(fi_path, sizeof fi_path, "%s/fuzz_image-%ld.img", dir, (long)getpid());
        atexit(fi_cleanup);
    }
    FILE *f = fopen(fi_path, "wb");
    if (!f || fwrite(data, 1, size, f) != size || fclose(f) != 0)
        fi_fail("cannot write the input's file", (long)size, 0);
    img_rgb im;
    char err[512];
    err[0] = 0;
    if (img_load(fi_path, &im, err, sizeof err) != 0) {
        /* a refusal: one line naming the file, nothing allocated */
        size_t n = strlen(fi_path);
        if (strncmp(err, fi_path, n) != 0 || strncmp(err + n, ": ", 2) != 0 || strchr(err, '\n') ||
            strlen(err) < n + 4)
            fi_fail("malformed error message", (long)strlen(err), 0);
        if (im.rgb || im.width || im.height)
            fi_fail("a refused image left pixels", im.width, im.height);
        return 0;
    }
    if (im.width < 1 || im.height < 1 || (long)im.width * im.height > 4096L * 4096L || !im.rgb)
        fi_fail("an accepted image of a size the reader refuses", im.width, im.height);
    /* every byte is there to read (ASan checks the allocation's size) */
    unsigned sum = 0;
    for (size_t i = 0; i < (size_t)im.width * (size_t)im.height * 3; i++)
        sum += im.rgb[i];
    /* a PPM holds its pixels as they are, after a header of at least 11 bytes ("P6 1 1 255 ") */
    if (data[0] == 'P') {
        size_t n = (size_t)im.width * (size_t)im.height * 3;
        if (size < n + 11 || !memmem(data, size, im.rgb, n))
            fi_fail("a PPM's pixels are not its bytes", im.width, im.height);
    }
    img_free(&im);
    return (int)(sum & 0); /* 0: the sum only makes every byte read */
}
