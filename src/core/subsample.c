/* subsample.c: adaptive subsampling: trace square corners, split squares whose corners disagree, interpolate the rest (probe mode: probe the points a split adds first, probe.c). */
#include <string.h>

#include "rt.h"

/* Squares along a side of n pixels: corners at 0, g, 2g, ... and at the last pixel, n - 1
 * (so the last square may be narrower); at least one square, even for n = 1. */
static int ss_count(int n, int g)
{
    int k = (n - 1 + g - 1) / g;
    return k > 0 ? k : 1;
}

/* Pixel coordinate of corner i along a side of n pixels. */
static int ss_corner(int i, int g, int n)
{
    int c = i * g;
    return c < n - 1 ? c : n - 1;
}

unsigned long rt_render_work_size(const rt_params *p, int width)
{
    if (p->mode == RT_MODE_FULL)
        return 0;
    unsigned long row = (unsigned long)ss_count(width, p->grid) + 1;
    unsigned long side = (unsigned long)p->grid + 1;
    return (2 * row + side * side) * sizeof(rt_sample);
}

int rt_render_band_count(const rt_params *p, int height)
{
    return p->mode != RT_MODE_FULL ? ss_count(height, p->grid) : height;
}

enum rt_split_reason rt_corners_differ(const rt_sample *const k[4], int thr8)
{
    const rt_sample *a = k[0];
    for (int i = 1; i < 4; i++)
        if (k[i]->hits[0].object != a->hits[0].object || k[i]->cell != a->cell)
            return RT_SPLIT_OBJECT;
    for (int i = 1; i < 4; i++)
        if (k[i]->lights != a->lights)
            return RT_SPLIT_LIGHT;
    int n = a->nhits < RT_SAMPLE_MAX_HITS ? a->nhits : RT_SAMPLE_MAX_HITS;
    for (int i = 1; i < 4; i++) {
        if (k[i]->nhits != a->nhits)
            return RT_SPLIT_SECONDARY;
        for (int j = 1; j < n; j++)
            if (k[i]->hits[j].object != a->hits[j].object ||
                k[i]->hits[j].level != a->hits[j].level)
                return RT_SPLIT_SECONDARY;
    }
    for (int j = 0; j < n; j++) {
        for (int ch = 0; ch < 3; ch++) {
            int lo = 255, hi = 0;
            for (int i = 0; i < 4; i++) {
                int c = k[i]->hits[j].contrib[ch];
                lo = c < lo ? c : lo;
                hi = c > hi ? c : hi;
            }
            if (hi - lo > thr8)
                return RT_SPLIT_CONTRIB;
        }
    }
    return RT_SPLIT_NONE;
}

/* The fill works on integer channels: a colour in [0, 1] as its Q16.16 value, 0..65536
 * (r_unit_to_q16), and weights i / n as Q16.16 integers rounded to nearest. Its arithmetic is
 * the fixed-point build's r_lerp, r_mul and r_to_byte step for step (no intermediate value can
 * saturate), so fixed frames are what they were with those calls, at a fraction of the cost;
 * the float build interpolates the same way from its rounded corners. */
typedef struct ss_rgb {
    int32_t c[3];
} ss_rgb;

/* ss_wq[n][i] = i / n as a Q16.16 integer rounded to nearest (r_from_ratio's fixed-point
 * value), for squares of up to RT_GRID_MAX pixels: a constant table, no division. */
#define SS_W(i, n) ((n) > 0 ? ((i)*65536 + (n) / 2) / ((n) > 0 ? (n) : 1) : 0)
#define SS_ROW(n) \
    { \
        SS_W(0, n), SS_W(1, n), SS_W(2, n), SS_W(3, n), SS_W(4, n), SS_W(5, n), SS_W(6, n), \
            SS_W(7, n), SS_W(8, n), SS_W(9, n), SS_W(10, n), SS_W(11, n), SS_W(12, n), \
            SS_W(13, n), SS_W(14, n), SS_W(15, n), SS_W(16, n) \
    }
#if RT_GRID_MAX != 16
#error "ss_wq is written out for RT_GRID_MAX 16"
#endif
static const int32_t ss_wq[RT_GRID_MAX + 1][RT_GRID_MAX + 1] = {
    SS_ROW(0),  SS_ROW(1),  SS_ROW(2),  SS_ROW(3),  SS_ROW(4),  SS_ROW(5),
    SS_ROW(6),  SS_ROW(7),  SS_ROW(8),  SS_ROW(9),  SS_ROW(10), SS_ROW(11),
    SS_ROW(12), SS_ROW(13), SS_ROW(14), SS_ROW(15), SS_ROW(16)};

/* A colour already clamped to [0, 1] (ss_trace clamps every sample's). */
static ss_rgb ss_rgb_of(rt_color c)
{
    ss_rgb v = {{r_unit_to_q16(c.x), r_unit_to_q16(c.y), r_unit_to_q16(c.z)}};
    return v;
}

static ss_rgb ss_rgb_clamped(rt_color c)
{
    return ss_rgb_of(v3(r_clamp(c.x, 0, R_ONE), r_clamp(c.y, 0, R_ONE), r_clamp(c.z, 0, R_ONE)));
}

/* d * t / 2^16 rounded half away from zero (as r_mul rounds), for |d| <= 65536 and
 * 0 <= t < 65536: the product and its rounding fit in 32 unsigned bits. */
static int32_t ss_mul(int32_t d, int32_t t)
{
    uint32_t p = (uint32_t)(d < 0 ? -d : d) * (uint32_t)t;
    int32_t q = (int32_t)((p + 0x8000u) >> 16);
    return d < 0 ? -q : q;
}

/* One channel as a byte: clamped to [0, 65536] and rounded as r_to_byte does. */
static uint32_t ss_byte(int32_t v)
{
    if (v <= 0)
        return 0;
    if (v >= 65536)
        return 255;
    return ((uint32_t)v * 255u + 0x8000u) >> 16;
}

static uint32_t ss_pixel(const int32_t *c)
{
    return ss_byte(c[0]) << 16 | ss_byte(c[1]) << 8 | ss_byte(c[2]);
}

/* Bilinear fill with the Q16.16 weights wx[i] = i / w and wy[j] = j / h given (only wx[1] is
 * used). */
static void ss_fill(uint32_t *dst, int stride, int w, int h, int cols, int rows, const int32_t *wx,
                    const int32_t *wy, ss_rgb c00, ss_rgb c10, ss_rgb c01, ss_rgb c11)
{
    int inner = cols < w ? cols : w; /* columns 0..inner-1 come from the left edge and steps */
    for (int j = 0; j < rows; j++) {
        ss_rgb l, r;
        if (j == 0) {
            l = c00;
            r = c10;
        } else if (j == h) {
            l = c01;
            r = c11;
        } else {
            for (int ch = 0; ch < 3; ch++) {
                l.c[ch] = c00.c[ch] + ss_mul(c01.c[ch] - c00.c[ch], wy[j]);
                r.c[ch] = c10.c[ch] + ss_mul(c11.c[ch] - c10.c[ch], wy[j]);
            }
        }
        uint32_t *row = dst + (long)j * stride;
        row[0] = ss_pixel(l.c);
        if (inner > 1) {
            /* Along the row by forward differences: w additions of (r - l) / w drift by at
             * most w/2 steps of Q16.16, far below an 8-bit level (and within 32 bits). */
            int32_t s0 = ss_mul(r.c[0] - l.c[0], wx[1]), s1 = ss_mul(r.c[1] - l.c[1], wx[1]),
                    s2 = ss_mul(r.c[2] - l.c[2], wx[1]);
            int32_t v0 = l.c[0], v1 = l.c[1], v2 = l.c[2];
            for (int i = 1; i < inner; i++) {
                v0 += s0;
                v1 += s1;
                v2 += s2;
                row[i] = ss_byte(v0) << 16 | ss_byte(v1) << 8 | ss_byte(v2);
            }
        }
        if (cols > w && w > 0)
            row[w] = ss_pixel(r.c);
    }
}

void rt_interpolate(uint32_t *dst, int stride, int w, int h, int cols, int rows, rt_color c00,
                    rt_color c10, rt_color c01, rt_color c11)
{
    if (w > RT_GRID_MAX || h > RT_GRID_MAX || cols > w + 1 || rows > h + 1)
        return;
    ss_fill(dst, stride, w, h, cols, rows, ss_wq[w], ss_wq[h], ss_rgb_clamped(c00),
            ss_rgb_clamped(c10), ss_rgb_clamped(c01), ss_rgb_clamped(c11));
}

/* One frame's adaptive rendering state. */
typedef struct ss_ctx {
    const rt_scene *scene;
    const rt_view *view;
    const rt_params *params;
    rt_stats *stats;
    uint32_t *pixels; /* pixel row py0 of the frame */
    int stride;
    int py0;
    uint8_t *traced;
    int thr8;       /* contribution threshold in 1/255 steps */
    rt_sample *lat; /* samples of the current square, (grid + 1)^2, row-major */
    int lstride;    /* grid + 1 */
    int sx, sy;     /* pixel of the lattice's (0, 0) */
    real wt[RT_GRID_MAX + 1][RT_GRID_MAX + 1]; /* wt[n][i] = i / n */
} ss_ctx;

/* Shades the point (x, y) in full into *out (in probe mode from the primary hit a probe found,
 * *pri, if not NULL), clamps its colour, marks it, and in probe mode sets its flags. */
static void ss_shade(ss_ctx *c, int x, int y, rt_sample *out, rt_primary *pri)
{
    if (RT_COMPILED_PROBE && pri) {
        rt_trace_pixel_from(c->scene, c->view, c->params, x, y, pri, c->stats, out);
        out->flags = (uint8_t)rt_probe_opaque(c->scene, out);
    } else {
        rt_trace_pixel(c->scene, c->view, c->params, x, y, c->stats, out);
        out->flags = RT_COMPILED_PROBE && c->params->mode == RT_MODE_PROBE
            ? (uint8_t)rt_probe_opaque(c->scene, out)
            : 0;
    }
    /* Interpolate what is shown: colours clamped as the pixel will be. */
    out->color = v3(r_clamp(out->color.x, 0, R_ONE), r_clamp(out->color.y, 0, R_ONE),
                    r_clamp(out->color.z, 0, R_ONE));
    /* Bands running at the same time both trace the corners on the edge between them: the
     * mark is an atomic store, so two of them may set the same byte. */
    if (c->traced)
        __atomic_store_n(&c->traced[(long)y * c->view->width + x], 1, __ATOMIC_RELAXED);
}

static void ss_trace(ss_ctx *c, int x, int y, rt_sample *out) { ss_shade(c, x, y, out, NULL); }

/* The sample at pixel (x, y) of the current square, traced on first use. */
static const rt_sample *ss_at(ss_ctx *c, int x, int y)
{
    rt_sample *sm = &c->lat[(y - c->sy) * c->lstride + (x - c->sx)];
    if (sm->nhits == 0)
        ss_trace(c, x, y, sm);
    return sm;
}

/* Probe mode: the point (x, y) a split adds, not decided yet, with its context k
 * (rt_probe_point); probed, and shaded in full only when rt_probe_point cannot give its
 * colour. */
static __attribute__((noinline)) void ss_probe_new(ss_ctx *c, int x, int y, int n,
                                                   const rt_sample *const k[],
                                                   enum rt_split_reason why, real tx, real ty,
                                                   int span)
{
    rt_sample *sm = &c->lat[(y - c->sy) * c->lstride + (x - c->sx)];
    rt_primary pri;
    if (rt_probe_point(c->scene, c->view, c->params, c->stats, c->thr8, x, y, n, k, why, tx, ty,
                       span, &pri, sm)) {
        if (c->traced)
            __atomic_store_n(&c->traced[(long)y * c->view->width + x], 2, __ATOMIC_RELAXED);
        return;
    }
    ss_shade(c, x, y, sm, &pri); /* in full, from the primary hit if the probe found it */
}

/* Probe mode: the points splitting the square (x0, y0, w, h) into nx by ny adds (k: its
 * corners): the middles of the edges it halves, each against the ends of its edge, and the
 * centre against the four corners. A point some square added before is kept: it got its record
 * from the same context (the ends of its edge), so the frame does not depend on the order
 * squares are visited in. */
static __attribute__((noinline)) void ss_probe_split(ss_ctx *c, int x0, int y0, int w, int h,
                                                     int nx, int ny, const rt_sample *const k[4],
                                                     enum rt_split_reason why)
{
    real tx = c->wt[w][w / 2], ty = c->wt[h][h / 2];
    int xm = x0 + w / 2, ym = y0 + h / 2;
    /* the lattice at (x0, y0): a point already decided (nhits) is kept */
    const rt_sample *at = &c->lat[(y0 - c->sy) * c->lstride + (x0 - c->sx)];
    for (int j = 0; j < 2 && nx == 2; j++) /* top, bottom: k[0], k[1] and k[2], k[3] */
        if (!at[j * h * c->lstride + w / 2].nhits)
            ss_probe_new(c, xm, y0 + j * h, 2, k + 2 * j, why, tx, 0, w);
    for (int i = 0; i < 2 && ny == 2; i++) { /* left, right */
        const rt_sample *kk[2] = {k[i], k[i + 2]};
        if (!at[h / 2 * c->lstride + i * w].nhits)
            ss_probe_new(c, x0 + i * w, ym, 2, kk, why, ty, 0, h);
    }
    if (nx == 2 && ny == 2 && !at[h / 2 * c->lstride + w / 2].nhits)
        ss_probe_new(c, xm, ym, 4, k, why, tx, ty, w > h ? w : h);
}

/* The square with corners (x0, y0) and (x0 + w, y0 + h), at subdivision `level`. It writes the
 * pixels it owns: [x0, x0 + w) x [y0, y0 + h), plus its right column and bottom row where it
 * ends the frame (own_r, own_b). Every pixel is thus written once, whatever the order. */
static void ss_square(ss_ctx *c, int x0, int y0, int w, int h, int level, int own_r, int own_b)
{
    const rt_sample *k[4] = {ss_at(c, x0, y0), ss_at(c, x0 + w, y0), ss_at(c, x0, y0 + h),
                             ss_at(c, x0 + w, y0 + h)};
    if (w > 1 || h > 1) { /* some pixel is not a corner */
        int li = level < RT_GRID_LEVELS ? level : RT_GRID_LEVELS - 1;
        c->stats->squares[li]++;
        enum rt_split_reason why = rt_corners_differ(k, c->thr8);
        if (why != RT_SPLIT_NONE) {
            c->stats->split[li]++;
            c->stats->split_by[why]++;
            int xs[3] = {x0, x0 + w, x0 + w}, ys[3] = {y0, y0 + h, y0 + h};
            int nx = 1, ny = 1;
            if (w >= 2) {
                xs[1] = x0 + w / 2;
                nx = 2;
            }
            if (h >= 2) {
                ys[1] = y0 + h / 2;
                ny = 2;
            }
            if (RT_COMPILED_PROBE && c->params->mode == RT_MODE_PROBE)
                ss_probe_split(c, x0, y0, w, h, nx, ny, k, why);
            for (int j = 0; j < ny; j++)
                for (int i = 0; i < nx; i++)
                    ss_square(c, xs[i], ys[j], xs[i + 1] - xs[i], ys[j + 1] - ys[j], level + 1,
                              i == nx - 1 && own_r, j == ny - 1 && own_b);
            return;
        }
    }
    int cols = w + (own_r ? 1 : 0), rows = h + (own_b ? 1 : 0);
    uint32_t *dst = c->pixels + (long)(y0 - c->py0) * c->stride + x0;
    ss_fill(dst, c->stride, w, h, cols, rows, ss_wq[w], ss_wq[h], ss_rgb_of(k[0]->color),
            ss_rgb_of(k[1]->color), ss_rgb_of(k[2]->color), ss_rgb_of(k[3]->color));
    /* Points a neighbour traced for its own decisions show their traced colour. They can only
     * lie on the edges this square shares with squares done before it: its top row and left
     * column (nothing is ever traced inside a square that is not split). */
    const rt_sample *sm = &c->lat[(y0 - c->sy) * c->lstride + (x0 - c->sx)];
    for (int i = 1; i < cols; i++)
        if (sm[i].nhits)
            dst[i] = rt_color_pixel(sm[i].color);
    for (int j = 1; j < rows; j++)
        if (sm[j * c->lstride].nhits)
            dst[(long)j * c->stride] = rt_color_pixel(sm[j * c->lstride].color);
}

/* Traces the top-level corners of row y into row[0..ncols]. */
static void ss_corner_row(ss_ctx *c, rt_sample *row, int ncols, int y)
{
    int g = c->params->grid, width = c->view->width;
    for (int i = 0; i <= ncols; i++) {
        int x = ss_corner(i, g, width);
        if (i > 0 && x == ss_corner(i - 1, g, width))
            row[i] = row[i - 1]; /* a one-pixel-wide frame */
        else
            ss_trace(c, x, y, &row[i]);
    }
}

void rt_render_adaptive(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
                        int stride, rt_stats *stats, void *work, uint8_t *traced, int band,
                        int nbands, enum rt_band_memory mem)
{
    const int g = p->grid, width = v->width, height = v->height;
    int ncols = ss_count(width, g), nrows = ss_count(height, g);
    /* This band's rows of squares, and the pixel rows it owns. */
    int r0 = (int)((long)nrows * band / nbands), r1 = (int)((long)nrows * (band + 1) / nbands);
    if (r0 == r1)
        return;
    ss_ctx c = {.scene = s,
                .view = v,
                .params = p,
                .stats = stats,
                .pixels = pixels,
                .stride = stride,
                .py0 = mem == RT_BAND_FRAME ? 0 : ss_corner(r0, g, height),
                .traced = traced,
                .thr8 = r_to_byte(p->threshold),
                .lstride = g + 1};
    for (int n = 1; n <= g; n++)
        for (int i = 0; i <= n; i++)
            c.wt[n][i] = r_from_ratio(i, n);

    /* Two rows of corners: row r of the frame's corners lives in row r % 2 of `work`, so bands
     * rendered in order find their top row where the band before left it (RT_BAND_KEEP). */
    rt_sample *top = work, *bot = top + ncols + 1;
    c.lat = bot + ncols + 1;
    if (r0 % 2) {
        top = bot;
        bot = work;
    }
    if (mem != RT_BAND_KEEP)
        ss_corner_row(&c, top, ncols, ss_corner(r0, g, height));
    for (int r = r0; r < r1; r++) {
        int y0 = ss_corner(r, g, height), h = ss_corner(r + 1, g, height) - y0;
        if (h == 0)
            memcpy(bot, top, (size_t)(ncols + 1) * sizeof *top); /* a one-pixel-high frame */
        else
            ss_corner_row(&c, bot, ncols, y0 + h);
        c.sy = y0;
        int prev_w = -1;
        for (int i = 0; i < ncols; i++) {
            int x0 = ss_corner(i, g, width), w = ss_corner(i + 1, g, width) - x0;
            c.sx = x0;
            for (int ly = 0; ly <= h; ly++) {
                rt_sample *row = c.lat + ly * c.lstride;
                /* The left edge is the square before's right edge: keep what it traced. */
                if (prev_w >= 0)
                    row[0] = row[prev_w];
                for (int lx = prev_w >= 0 ? 1 : 0; lx <= w; lx++)
                    row[lx].nhits = 0;
            }
            c.lat[0] = top[i];
            c.lat[w] = top[i + 1];
            c.lat[h * c.lstride] = bot[i];
            c.lat[h * c.lstride + w] = bot[i + 1];
            ss_square(&c, x0, y0, w, h, 0, i == ncols - 1, r == nrows - 1);
            prev_w = w;
        }
        rt_sample *t = top;
        top = bot;
        bot = t;
    }
}

void rt_render_band_rows(const rt_params *p, int height, int band, int nbands, int *y0, int *rows)
{
    *y0 = *rows = 0;
    if (nbands < 1 || band < 0 || band >= nbands || height < 1)
        return;
    int n = rt_render_band_count(p, height);
    int b0 = (int)((long)n * band / nbands), b1 = (int)((long)n * (band + 1) / nbands);
    if (b0 == b1)
        return;
    if (p->mode != RT_MODE_FULL) {
        /* rows of squares b0 .. b1 - 1: each owns its top row, the last one the frame's end */
        *y0 = ss_corner(b0, p->grid, height);
        *rows = (b1 == n ? height : ss_corner(b1, p->grid, height)) - *y0;
    } else {
        *y0 = b0;
        *rows = b1 - b0;
    }
}
