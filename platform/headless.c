/* headless.c: the headless backend: frames go to image files, time from the monotonic clock. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "image.h"
#include "platform.h"

/* The program's name, for messages: "rt-fixed: frame.png: cannot write: ...". */
static const char *plat_name = "rt";

int plat_frame_acquire(plat_frame *f, int width, int height)
{
    f->pixels = calloc((size_t)width * (size_t)height, sizeof *f->pixels);
    if (!f->pixels)
        return -1;
    f->width = width;
    f->height = height;
    f->stride = width;
    return 0;
}

void plat_frame_release(plat_frame *f)
{
    free(f->pixels);
    f->pixels = NULL;
}

int plat_frame_present(const plat_frame *f, const char *dest)
{
    char err[512];
    if (!dest)
        return plat_display_show(f);
    if (img_save(dest, f->pixels, f->width, f->height, f->stride, err, sizeof err) != 0) {
        fprintf(stderr, "%s: %s\n", plat_name, err);
        return -1;
    }
    return 0;
}

uint64_t plat_time_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

void plat_log(const char *line) { fprintf(stderr, "%s\n", line); }

const char *plat_program(void) { return plat_name; }

int main(int argc, char **argv)
{
    if (argc > 0 && argv[0][0]) {
        const char *slash = strrchr(argv[0], '/');
        plat_name = slash ? slash + 1 : argv[0];
    }
    return app_main(argc, argv);
}
