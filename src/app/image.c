/* image.c: reading and writing image files (PNG through libpng, binary PPM) on the host. */
#define _POSIX_C_SOURCE 200809L
#include "image.h"

#include <errno.h>
#include <limits.h>
#include <png.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Refuse images larger than this (pixels) rather than exhausting memory: the largest frame
 * the renderers write (4096 x 4096), 48 MiB of RGB. */
#define IMG_MAX_SIDE 4096L
#define IMG_MAX_PIXELS (IMG_MAX_SIDE * IMG_MAX_SIDE)

static int img_fail(char *err, size_t errlen, const char *fmt, const char *a, const char *b)
{
    snprintf(err, errlen, fmt, a, b);
    return -1;
}

static int img_ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    if (n < m)
        return 0;
    for (size_t i = 0; i < m; i++) {
        char c = s[n - m + i];
        if (c >= 'A' && c <= 'Z')
            c = (char)(c - 'A' + 'a');
        if (c != suffix[i])
            return 0;
    }
    return 1;
}

int img_path_ok(const char *path)
{
    return img_ends_with(path, ".png") || img_ends_with(path, ".ppm");
}

void img_free(img_rgb *im)
{
    free(im->rgb);
    im->rgb = NULL;
    im->width = im->height = 0;
}

/* Next header token of a PPM file as a non-negative integer, skipping blanks and comments. */
static long img_ppm_int(FILE *f)
{
    int c = fgetc(f);
    for (;;) {
        while (c == ' ' || c == '\t' || c == '\n' || c == '\r')
            c = fgetc(f);
        if (c != '#')
            break;
        while (c != '\n' && c != EOF)
            c = fgetc(f);
    }
    if (c < '0' || c > '9')
        return -1;
    long v = 0;
    while (c >= '0' && c <= '9') {
        v = v * 10 + (c - '0');
        if (v > 1000000)
            return -1;
        c = fgetc(f);
    }
    /* exactly one blank ends the token (it precedes the raster after maxval) */
    if (c != ' ' && c != '\t' && c != '\n' && c != '\r')
        return -1;
    return v;
}

static int img_load_ppm(FILE *f, const char *path, img_rgb *out, char *err, size_t errlen)
{
    long w = img_ppm_int(f), h = img_ppm_int(f), maxval = img_ppm_int(f);
    if (w <= 0 || h <= 0 || maxval < 0)
        return img_fail(err, errlen, "%s: malformed PPM header%s", path, "");
    if (maxval != 255)
        return img_fail(err, errlen, "%s: PPM maxval must be 255 (8-bit)%s", path, "");
    if (w * h > IMG_MAX_PIXELS)
        return img_fail(err, errlen, "%s: image too large (more than 4096x4096 pixels)%s", path,
                        "");
    size_t n = (size_t)w * (size_t)h * 3;
    /* The header promises n bytes: a file that has fewer is refused before allocating them. */
    struct stat st;
    long at = ftell(f);
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode) && at >= 0 &&
        (unsigned long long)st.st_size - (unsigned long long)at < n)
        return img_fail(err, errlen, "%s: PPM data is truncated%s", path, "");
    out->rgb = malloc(n);
    if (!out->rgb)
        return img_fail(err, errlen, "%s: out of memory%s", path, "");
    if (fread(out->rgb, 1, n, f) != n) {
        img_free(out);
        return img_fail(err, errlen, "%s: PPM data is truncated%s", path, "");
    }
    out->width = (int)w;
    out->height = (int)h;
    return 0;
}

static int img_load_png(const char *path, img_rgb *out, char *err, size_t errlen)
{
    png_image image;
    memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&image, path))
        return img_fail(err, errlen, "%s: bad PNG: %s", path, image.message);
    if ((long)image.width * (long)image.height > IMG_MAX_PIXELS) {
        png_image_free(&image);
        return img_fail(err, errlen, "%s: image too large (more than 4096x4096 pixels)%s", path,
                        "");
    }
    image.format = PNG_FORMAT_RGB;
    out->rgb = malloc(PNG_IMAGE_SIZE(image));
    if (!out->rgb) {
        png_image_free(&image);
        return img_fail(err, errlen, "%s: out of memory%s", path, "");
    }
    if (!png_image_finish_read(&image, NULL, out->rgb, 0, NULL)) {
        img_free(out);
        return img_fail(err, errlen, "%s: bad PNG: %s", path, image.message);
    }
    out->width = (int)image.width;
    out->height = (int)image.height;
    return 0;
}

int img_load(const char *path, img_rgb *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    FILE *f = fopen(path, "rb");
    if (!f)
        return img_fail(err, errlen, "%s: cannot open: %s", path, strerror(errno));
    unsigned char magic[8] = {0};
    size_t got = fread(magic, 1, sizeof magic, f);
    int rc;
    if (ferror(f)) {
        int e = errno;
        fclose(f);
        return img_fail(err, errlen, "%s: cannot read: %s", path, strerror(e));
    }
    if (got >= 8 && png_sig_cmp(magic, 0, 8) == 0) {
        fclose(f);
        return img_load_png(path, out, err, errlen);
    }
    /* "P6", then a blank or a comment, as the format has it */
    if (got >= 3 && magic[0] == 'P' && magic[1] == '6' && strchr(" \t\n\r#", magic[2])) {
        rewind(f);
        (void)fgetc(f);
        (void)fgetc(f);
        rc = img_load_ppm(f, path, out, err, errlen);
    } else {
        rc = img_fail(err, errlen, "%s: not a PNG or binary PPM (P6) image%s", path, "");
    }
    fclose(f);
    return rc;
}

/* Packs 0x00RRGGBB pixels into RGB bytes. */
static uint8_t *img_pack(const uint32_t *pixels, int width, int height, int stride)
{
    uint8_t *rgb = malloc((size_t)width * (size_t)height * 3);
    if (!rgb)
        return NULL;
    uint8_t *q = rgb;
    for (int y = 0; y < height; y++) {
        const uint32_t *row = pixels + (size_t)y * (size_t)stride;
        for (int x = 0; x < width; x++) {
            *q++ = (uint8_t)(row[x] >> 16);
            *q++ = (uint8_t)(row[x] >> 8);
            *q++ = (uint8_t)row[x];
        }
    }
    return rgb;
}

/* The temporary file img_save is writing, removed by img_on_signal when a signal ends the
 * program meanwhile, so an interrupted run leaves no half-written file behind. The programs
 * write their files from one thread, one at a time. */
static char img_tmp[PATH_MAX];
static volatile sig_atomic_t img_tmp_live;
/* The signals whose default action ends the program that a user or a supervisor sends. */
static const int img_stop_signals[] = {SIGHUP, SIGINT, SIGQUIT, SIGTERM};
#define IMG_NSIG (int)(sizeof img_stop_signals / sizeof img_stop_signals[0])

static void img_on_signal(int sig)
{
    if (img_tmp_live)
        unlink(img_tmp);
    raise(sig); /* the handler was reset to the default (SA_RESETHAND): it ends the program */
}

/* For the time of a save: img_on_signal handles the signals left at their default action (a
 * handler of the program's own, such as SDL's, stays), and a file-size limit makes the write
 * fail with EFBIG instead of ending the program mid-file. */
typedef struct img_guard {
    struct sigaction old[IMG_NSIG], old_xfsz;
    int set[IMG_NSIG], set_xfsz;
} img_guard;

static void img_guard_on(img_guard *g)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = img_on_signal;
    sa.sa_flags = SA_RESETHAND;
    sigfillset(&sa.sa_mask);
    for (int i = 0; i < IMG_NSIG; i++)
        g->set[i] = sigaction(img_stop_signals[i], NULL, &g->old[i]) == 0 &&
            g->old[i].sa_handler == SIG_DFL && sigaction(img_stop_signals[i], &sa, NULL) == 0;
    sa.sa_handler = SIG_IGN;
    sa.sa_flags = 0;
    g->set_xfsz = sigaction(SIGXFSZ, NULL, &g->old_xfsz) == 0 &&
        g->old_xfsz.sa_handler == SIG_DFL && sigaction(SIGXFSZ, &sa, NULL) == 0;
}

static void img_guard_off(img_guard *g)
{
    for (int i = 0; i < IMG_NSIG; i++)
        if (g->set[i])
            sigaction(img_stop_signals[i], &g->old[i], NULL);
    if (g->set_xfsz)
        sigaction(SIGXFSZ, &g->old_xfsz, NULL);
}

int img_save(const char *path, const uint32_t *pixels, int width, int height, int stride, char *err,
             size_t errlen)
{
    if (!img_path_ok(path))
        return img_fail(err, errlen, "%s: unknown image type (use .png or .ppm)%s", path, "");
    size_t n = strlen(path);
    if (n + 12 > sizeof img_tmp)
        return img_fail(err, errlen, "%s: cannot write: %s", path, "the file name is too long");
    uint8_t *rgb = img_pack(pixels, width, height, stride);
    if (!rgb)
        return img_fail(err, errlen, "%s: out of memory%s", path, "");

    img_guard guard;
    img_guard_on(&guard);
    char *tmp = img_tmp;
    memcpy(tmp, path, n);
    memcpy(tmp + n, ".tmp-XXXXXX", 12);
    img_tmp_live = 1; /* before mkstemp creates the file: a signal just after it finds it */
    int fd = mkstemp(tmp);
    if (fd < 0) {
        img_tmp_live = 0;
        img_fail(err, errlen, "%s: cannot write: %s", path, strerror(errno));
        img_guard_off(&guard);
        free(rgb);
        return -1;
    }
    mode_t mask = umask(0); /* a temporary file is 0600: give the result the usual mode */
    umask(mask);
    (void)fchmod(fd, 0666 & ~mask);
    FILE *f = fdopen(fd, "wb");
    int ok = f != NULL;
    if (ok && img_ends_with(path, ".png")) {
        png_image image;
        memset(&image, 0, sizeof image);
        image.version = PNG_IMAGE_VERSION;
        image.width = (png_uint_32)width;
        image.height = (png_uint_32)height;
        image.format = PNG_FORMAT_RGB;
        ok = png_image_write_to_stdio(&image, f, 0, rgb, 0, NULL) != 0;
    } else if (ok) {
        size_t size = (size_t)width * (size_t)height * 3;
        ok = fprintf(f, "P6\n%d %d\n255\n", width, height) > 0 && fwrite(rgb, 1, size, f) == size;
    }
    int saved_errno = errno;
    if (f) {
        if (fclose(f) != 0 && ok) {
            ok = 0;
            saved_errno = errno;
        }
    } else {
        close(fd);
    }
    if (ok && rename(tmp, path) != 0) {
        ok = 0;
        saved_errno = errno;
    }
    if (!ok) {
        unlink(tmp);
        img_fail(err, errlen, "%s: cannot write: %s", path,
                 saved_errno ? strerror(saved_errno) : "write failed");
    }
    img_tmp_live = 0;
    img_guard_off(&guard);
    free(rgb);
    return ok ? 0 : -1;
}
