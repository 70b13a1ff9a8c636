/* cmp.c: rt-cmp: compares two images of equal size and reports PSNR and pixel differences; --oled shows an image as the M3 board's OLED does. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "knobs.h"
#include "outpath.h"
#include "platform.h"
#include "topt.h"

/* Each channel of the difference picture is |a - b| times this, clamped to 255. */
#define CMP_DIFF_GAIN 16
/* Largest --box factor (a 16x16 supersampled reference is more than any test needs). */
#define CMP_BOX_MAX 16

/* Replaces im by its n x n box-filtered reduction (each pixel the rounded mean of an n x n
 * block); im's size must be a multiple of n. Returns 0, or -1 when out of memory. */
static int cmp_box(img_rgb *im, int n)
{
    int w = im->width / n, h = im->height / n;
    uint8_t *rgb = malloc((size_t)w * h * 3);
    if (!rgb)
        return -1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++) {
                long sum = 0;
                for (int j = 0; j < n; j++)
                    for (int i = 0; i < n; i++)
                        sum += im->rgb[3 * ((long)(y * n + j) * im->width + x * n + i) + c];
                rgb[3 * ((long)y * w + x) + c] = (uint8_t)((sum + n * n / 2) / (n * n));
            }
    free(im->rgb);
    im->rgb = rgb;
    im->width = w;
    im->height = h;
    return 0;
}
/* QEMU draws each OLED pixel as a square of this side (hw/display/ssd0323.c). */
#define CMP_OLED_MAGNIFY 4
/* The largest --oled input, in pixels: its picture is then as large as the images rt-cmp reads
 * (4096x4096, image.c), 16 times the pixels. */
#define CMP_OLED_MAX_PIXELS (1024L * 1024L)

static int cmp_usage(FILE *f)
{
    fprintf(f,
            "usage: rt-cmp A B [--diff D.png] [--box N]\n"
            "       rt-cmp --oled IMAGE OUT.ppm\n"
            "       rt-cmp --help | --version\n"
            "Compares two images of equal size (PNG or PPM) and prints one line:\n"
            "psnr_db=<x> max_abs=<n> differing=<n> over8=<n> pixels=<n>\n"
            "--diff D.png writes |A - B| amplified %dx (pure red where a channel is off by "
            "more than 8).\n"
            "--box N: A is N times B's width and height (a supersampled reference) and is\n"
            "box-filtered down to B's size first, each pixel the mean of N x N; N in 1..%d.\n"
            "Options take their value as --opt value or --opt=value, each at most once.\n"
            "--oled writes IMAGE as the M3 board's OLED shows it in QEMU (its screendump): each\n"
            "pixel at 16 levels of grey (plat_grey4), %dx%d pixels of grey 17 x level; IMAGE\n"
            "has at most 1024x1024 pixels.\n",
            CMP_DIFF_GAIN, CMP_BOX_MAX, CMP_OLED_MAGNIFY, CMP_OLED_MAGNIFY);
    return f == stdout ? 0 : 2;
}

/* rt-cmp --oled IMAGE OUT */
static int cmp_oled(const char *in, const char *out)
{
    char err[512];
    if (!img_path_ok(out)) {
        fprintf(stderr, "rt-cmp: %s: the OLED picture must end in .png or .ppm\n", out);
        return 2;
    }
    if (outpath_check(out, err, sizeof err) != 0) {
        fprintf(stderr, "rt-cmp: %s\n", err);
        return 2;
    }
    img_rgb a;
    if (img_load(in, &a, err, sizeof err) != 0) {
        fprintf(stderr, "rt-cmp: %s\n", err);
        return 2;
    }
    if ((long)a.width * a.height > CMP_OLED_MAX_PIXELS) {
        fprintf(stderr,
                "rt-cmp: %s: too large for --oled (%dx%d: more than 1024x1024 pixels, whose "
                "picture would be more than 4096x4096)\n",
                in, a.width, a.height);
        img_free(&a);
        return 2;
    }
    int w = a.width * CMP_OLED_MAGNIFY, h = a.height * CMP_OLED_MAGNIFY;
    uint32_t *px = malloc((size_t)w * (size_t)h * sizeof *px);
    if (!px) {
        img_free(&a);
        fprintf(stderr, "rt-cmp: out of memory\n");
        return 1;
    }
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const uint8_t *p =
                a.rgb + 3 * ((long)(y / CMP_OLED_MAGNIFY) * a.width + x / CMP_OLED_MAGNIFY);
            uint32_t grey = 17u * plat_grey4((uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2]);
            px[(long)y * w + x] = grey << 16 | grey << 8 | grey;
        }
    }
    img_free(&a);
    int rc = img_save(out, px, w, h, w, err, sizeof err);
    free(px);
    if (rc != 0) {
        fprintf(stderr, "rt-cmp: %s\n", err);
        return 1;
    }
    return 0;
}

/* The options, in the grammar of render's (topt.h). */
enum { CMP_HELP, CMP_VERSION, CMP_DIFF, CMP_BOX, CMP_OLED, CMP_NOPTS };
static const topt cmp_opts[CMP_NOPTS] = {{"--help", "-h", 0},
                                         {"--version", NULL, 0},
                                         {"--diff", NULL, 1},
                                         {"--box", NULL, 1},
                                         {"--oled", NULL, 0}};

int main(int argc, char **argv)
{
    const char *path[2] = {NULL, NULL}, *diff = NULL;
    int npath = 0, box = 1, oled = 0;
    unsigned given = 0;
    for (int i = 1; i < argc; i++) {
        const char *v;
        long n;
        switch (topt_next("rt-cmp", cmp_opts, CMP_NOPTS, argc, argv, &i, &given, &v)) {
        case TOPT_FAIL: return 2;
        case CMP_HELP: return cmp_usage(stdout);
        case CMP_VERSION: topt_version(stdout, "rt-cmp"); return 0;
        case CMP_DIFF: diff = v; break;
        case CMP_BOX:
            if (knobs_number(v, -1, 0, 1, CMP_BOX_MAX, &n) != KNOBS_NUM_OK) {
                char what[48];
                snprintf(what, sizeof what, "expected a whole number in 1..%d", CMP_BOX_MAX);
                return topt_error("rt-cmp", "--box", what, v);
            }
            box = (int)n;
            break;
        case CMP_OLED: oled = 1; break;
        default:
            if (npath == 2) {
                fprintf(stderr, "rt-cmp: too many files: '%s' (%s)\n", argv[i],
                        oled ? "--oled wants IMAGE OUT.ppm" : "compare two images");
                return 2;
            }
            path[npath++] = argv[i];
        }
    }
    if (oled) {
        if (npath != 2 || diff || box != 1) {
            fprintf(stderr,
                    "rt-cmp: --oled wants IMAGE OUT.ppm and no other option (see rt-cmp "
                    "--help)\n");
            return 2;
        }
        return cmp_oled(path[0], path[1]);
    }
    if (npath != 2) {
        fprintf(stderr,
                "rt-cmp: expected two images, got %d (usage: rt-cmp A B [--diff D.png]; "
                "see rt-cmp --help)\n",
                npath);
        return 2;
    }
    char err[512];
    if (diff && !img_path_ok(diff)) {
        fprintf(stderr, "rt-cmp: %s: the difference picture must end in .png or .ppm\n", diff);
        return 2;
    }
    if (diff && outpath_check(diff, err, sizeof err) != 0) {
        fprintf(stderr, "rt-cmp: %s\n", err);
        return 2;
    }

    img_rgb a, b;
    if (img_load(path[0], &a, err, sizeof err) != 0) {
        fprintf(stderr, "rt-cmp: %s\n", err);
        return 2;
    }
    if (img_load(path[1], &b, err, sizeof err) != 0) {
        fprintf(stderr, "rt-cmp: %s\n", err);
        img_free(&a);
        return 2;
    }
    if (box > 1 && (a.width != b.width * box || a.height != b.height * box)) {
        fprintf(stderr, "rt-cmp: --box %d: %s is %dx%d, not %d times %s (%dx%d)\n", box, path[0],
                a.width, a.height, box, path[1], b.width, b.height);
        img_free(&a);
        img_free(&b);
        return 2;
    }
    if (box > 1 && cmp_box(&a, box) != 0) {
        fprintf(stderr, "rt-cmp: out of memory\n");
        img_free(&a);
        img_free(&b);
        return 1;
    }
    if (a.width != b.width || a.height != b.height) {
        fprintf(stderr, "rt-cmp: sizes differ: %s is %dx%d, %s is %dx%d\n", path[0], a.width,
                a.height, path[1], b.width, b.height);
        img_free(&a);
        img_free(&b);
        return 2;
    }

    long pixels = (long)a.width * a.height, differing = 0, over8 = 0;
    int max_abs = 0;
    double sse = 0;
    uint32_t *dpix = diff ? malloc((size_t)pixels * sizeof *dpix) : NULL;
    if (diff && !dpix) {
        fprintf(stderr, "rt-cmp: out of memory\n");
        return 1;
    }
    for (long i = 0; i < pixels; i++) {
        int worst = 0;
        uint32_t dp = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs((int)a.rgb[3 * i + c] - (int)b.rgb[3 * i + c]);
            sse += (double)d * d;
            if (d > worst)
                worst = d;
            int g = d * CMP_DIFF_GAIN > 255 ? 255 : d * CMP_DIFF_GAIN;
            dp |= (uint32_t)g << (16 - 8 * c);
        }
        if (worst > max_abs)
            max_abs = worst;
        differing += worst > 0;
        over8 += worst > 8;
        if (dpix)
            dpix[i] = worst > 8 ? 0xFF0000u : dp;
    }
    int width = a.width, height = a.height;
    img_free(&a);
    img_free(&b);

    double mse = sse / (3.0 * (double)pixels);
    if (mse == 0)
        printf("psnr_db=inf");
    else
        printf("psnr_db=%.2f", 10.0 * log10(255.0 * 255.0 / mse));
    printf(" max_abs=%d differing=%ld over8=%ld pixels=%ld\n", max_abs, differing, over8, pixels);

    int rc = 0;
    if (dpix) {
        if (img_save(diff, dpix, width, height, width, err, sizeof err) != 0) {
            fprintf(stderr, "rt-cmp: %s\n", err);
            rc = 1;
        }
        free(dpix);
    }
    return rc;
}
