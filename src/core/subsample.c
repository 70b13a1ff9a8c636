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

FX_BOARD_THUMB unsigned long rt_render_work_size(const rt_params *p, int width)
{
    if (p->mode == RT_MODE_FULL)
        return 0;
    unsigned long row = (unsigned long)ss_count(width, p->grid) + 1;
    unsigned long side = (unsigned long)p->grid + 1;
    return (2 * row + side * side) * sizeof(rt_sample);
}

FX_BOARD_THUMB int rt_render_band_count(const rt_params *p, int height)
{
    return p->mode != RT_MODE_FULL ? ss_count(height, p->grid) : height;
}

/* The contribution bytes of node j of a sample (rt_hit_rec.contrib). */
#define SS_CONTRIB(sm, j) ((sm)->hits[j].contrib)

/* Do the corners' ray trees differ only in faint nodes? Every node below the primary hit that
 * is not the same (object and level) at the same place in corner 0's tree and in another
 * corner's has contributions of at most lim in every channel, and every tree is stored whole. */
static __attribute__((noinline)) int ss_faint_tree(const rt_sample *const k[4], int lim)
{
    const rt_sample *a = k[0];
    for (int i = 0; i < 4; i++)
        if (k[i]->nhits > RT_SAMPLE_MAX_HITS)
            return 0;
    for (int i = 1; i < 4; i++) {
        const rt_sample *b = k[i];
        const int na = a->nhits, nb = b->nhits, n = na > nb ? na : nb;
        for (int j = 1; j < n; j++) {
            if (j < na && j < nb && a->hits[j].object == b->hits[j].object &&
                a->hits[j].level == b->hits[j].level)
                continue;
            for (int ch = 0; ch < 3; ch++)
                if ((j < na && a->hits[j].contrib[ch] > lim) ||
                    (j < nb && b->hits[j].contrib[ch] > lim))
                    return 0;
        }
    }
    return 1;
}

enum rt_split_reason rt_corners_differ(const rt_sample *const k[4], int thr8)
{
    const rt_sample *a = k[0], *b = k[1], *c = k[2], *d = k[3];
    /* The corners' counts, light states, cells and flags as one word each (offsets 12..15):
     * where all four agree (the usual case), only the primary objects are left to compare
     * before the ray trees; else the bytes themselves, in the order of the reasons. */
    const uint32_t wa = a->head, wb = b->head, wc = c->head, wd = d->head;
    const unsigned o = a->hits[0].object;
    if (b->hits[0].object != o || c->hits[0].object != o || d->hits[0].object != o)
        return RT_SPLIT_OBJECT;
    /* the bytes in which some corner differs from corner 0 */
    const union {
        uint32_t w;
        struct {
            uint8_t nhits, lights, cell, flags; /* rt_sample's, in its order */
        } b;
    } diff = {.w = (wa ^ wb) | (wa ^ wc) | (wa ^ wd)};
    /* A difference of structure that need not show in the colours, a light lit at some corners
     * and not at others or a ray tree with other objects, splits only where it does: where the
     * contributions differ by more than half the threshold. A faint shadow (a fill light's,
     * or the sun's at a grazing angle) or a faint reflection edge is interpolated like any
     * gradient. A highlight at some corner always splits (its peak can lie between them). */
    int weak = 0; /* 1: lit and unlit corners, 2: faint tree differences (the reason) */
    int n = a->nhits < RT_SAMPLE_MAX_HITS ? a->nhits : RT_SAMPLE_MAX_HITS;
    if (diff.w) {
        if (diff.b.cell)
            return RT_SPLIT_OBJECT;
        if (diff.b.lights & RT_LIGHTS_HIGHLIGHT)
            return RT_SPLIT_LIGHT;
        weak = diff.b.lights ? 1 : 0;
        if (diff.b.nhits) {
            if (!ss_faint_tree(k, thr8 / 2))
                return RT_SPLIT_SECONDARY;
            weak |= 2;
        }
    }
    if (!(weak & 2))
        for (int j = 1; j < n; j++) {
            const unsigned ob = a->hits[j].object, lv = a->hits[j].level;
            if (b->hits[j].object != ob || c->hits[j].object != ob || d->hits[j].object != ob ||
                b->hits[j].level != lv || c->hits[j].level != lv || d->hits[j].level != lv) {
                if (!ss_faint_tree(k, thr8 / 2))
                    return RT_SPLIT_SECONDARY;
                weak |= 2;
                break;
            }
        }
    if (weak & 2) /* the nodes every corner has (the others are faint) */
        for (int i = 1; i < 4; i++)
            n = k[i]->nhits < n ? k[i]->nhits : n;
    const int lim = weak ? thr8 / 2 : thr8;
    for (int j = 0; j < n; j++) {
        const uint8_t *pa = SS_CONTRIB(a, j), *pb = SS_CONTRIB(b, j), *pc = SS_CONTRIB(c, j),
                      *pd = SS_CONTRIB(d, j);
        for (int ch = 0; ch < 3; ch++) {
            int lo = pa[ch], hi = lo, v = pb[ch];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
            v = pc[ch];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
            v = pd[ch];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
            if (hi - lo > lim)
                return weak & 2 ? RT_SPLIT_SECONDARY : weak ? RT_SPLIT_LIGHT : RT_SPLIT_CONTRIB;
        }
    }
    return RT_SPLIT_NONE;
}

__attribute__((cold)) int rt_centre_smooth(const rt_sample *const k[4], const rt_sample *mid,
                                           int tol)
{
    const rt_sample *a = k[0];
    if (!rt_probe_same(a, mid)) /* its shape: the corners' (rt_corners_differ found them alike) */
        return 0;
    const int n = a->nhits < RT_SAMPLE_MAX_HITS ? a->nhits : RT_SAMPLE_MAX_HITS;
    for (int j = 0; j < n; j++)
        for (int ch = 0; ch < 3; ch++) {
            /* 2 (mid - the mean of each diagonal's ends): no rounding enters */
            const int m = 2 * mid->hits[j].contrib[ch];
            const int d0 = m - a->hits[j].contrib[ch] - k[3]->hits[j].contrib[ch],
                      d1 = m - k[1]->hits[j].contrib[ch] - k[2]->hits[j].contrib[ch];
            if ((unsigned)(d0 + 2 * tol) > (unsigned)(4 * tol) ||
                (unsigned)(d1 + 2 * tol) > (unsigned)(4 * tol)) /* |d| > 2 tol */
                return 0;
        }
    return 1;
}

/* The fill works on integer channels: a colour in [0, 1] as its Q16.16 value, 0..65536
 * (r_unit_to_q16), and weights i / n as Q16.16 integers rounded to nearest. Its arithmetic is
 * the fixed-point build's r_lerp, r_mul and r_to_byte step for step (no intermediate value can
 * saturate), so fixed frames are what they were with those calls, at a fraction of the cost;
 * the float build interpolates the same way from its rounded corners. */

/* ss_wq[n (n - 1) / 2 + i] = i / n as a Q16.16 integer rounded to nearest (r_from_ratio's
 * fixed-point value) for 0 <= i < n <= RT_GRID_MAX (below 2^16: 16 bits each), row n after row
 * n - 1 (ss_wrow): a constant table, no division. */
#define SS_W(i, n) (((i)*65536 + (n) / 2) / (n))
#define SS_T1(n) SS_W(0, n)
#define SS_T2(n) SS_T1(n), SS_W(1, n)
#define SS_T3(n) SS_T2(n), SS_W(2, n)
#define SS_T4(n) SS_T3(n), SS_W(3, n)
#define SS_T5(n) SS_T4(n), SS_W(4, n)
#define SS_T6(n) SS_T5(n), SS_W(5, n)
#define SS_T7(n) SS_T6(n), SS_W(6, n)
#define SS_T8(n) SS_T7(n), SS_W(7, n)
#define SS_T9(n) SS_T8(n), SS_W(8, n)
#define SS_T10(n) SS_T9(n), SS_W(9, n)
#define SS_T11(n) SS_T10(n), SS_W(10, n)
#define SS_T12(n) SS_T11(n), SS_W(11, n)
#define SS_T13(n) SS_T12(n), SS_W(12, n)
#define SS_T14(n) SS_T13(n), SS_W(13, n)
#define SS_T15(n) SS_T14(n), SS_W(14, n)
#define SS_T16(n) SS_T15(n), SS_W(15, n)
#if RT_GRID_MAX != 16
#error "ss_wq is written out for RT_GRID_MAX 16"
#endif
static const uint16_t ss_wq[RT_GRID_MAX * (RT_GRID_MAX + 1) / 2] = {
    SS_T1(1), SS_T2(2),   SS_T3(3),   SS_T4(4),   SS_T5(5),   SS_T6(6),   SS_T7(7),   SS_T8(8),
    SS_T9(9), SS_T10(10), SS_T11(11), SS_T12(12), SS_T13(13), SS_T14(14), SS_T15(15), SS_T16(16)};

/* Row n of ss_wq (0 <= n <= RT_GRID_MAX): i / n at [i], 0 <= i < n. */
static const uint16_t *ss_wrow(int n) { return ss_wq + ((unsigned)(n * (n - 1)) >> 1); }

/* d * t / 2^16 rounded half away from zero (as r_mul rounds), for |d| <= 65536 and
 * 0 <= t < 65536: the product and its rounding fit in 32 unsigned bits. The result lies between
 * 0 and d (|d| t / 2^16 < |d|, an integer). */
static int32_t ss_mul(int32_t d, int32_t t)
{
    uint32_t p = (uint32_t)(d < 0 ? -d : d) * (uint32_t)t;
    int32_t q = (int32_t)((p + 0x8000u) >> 16);
    return d < 0 ? -q : q;
}

/* ss_mul(d, 2^-k) for 1 <= k <= 4 (t = 2^(16 - k), i / n for n = 2^k): |d| t + 2^15 over 2^16
 * is (|d| + 2^(k - 1)) / 2^k, so for d >= 0 it is (d + 2^(k - 1)) >> k, and for d < 0 its
 * negation -floor((|d| + 2^(k - 1)) / 2^k) = ceil((d - 2^(k - 1)) / 2^k) is
 * floor((d + 2^(k - 1) - 1) / 2^k): one sum, the sign's -1 (d >> 31) and an arithmetic shift. */
static inline int32_t ss_shr_round(int32_t d, int k)
{
    return (d + (1 << (k - 1)) + (d >> 31)) >> k;
}

/* ss_mul(d, 1/2): d / 2 rounded half away from zero. */
static int32_t ss_half(int32_t d) { return ss_shr_round(d, 1); }

/* The byte of a channel v (Q16.16) is r_to_byte's: v clamped to [0, 65536], then
 * (v 255 + 2^15) >> 16. The fill keeps each channel as V = v 255 + 2^15
 * instead (SS_V): for -128 <= v <= 65664, V lies in [128, 2^24 - 128], and its bits 16..23
 * are that byte (v <= 0: V < 2^16, so 0; v >= 65536: V >= 255 2^16, so 255; else the formula
 * itself), so a pixel is three masks and shifts (ss_pack), with no clamp. Every V the fill
 * packs is within that range (ss_fill says why). */
#define SS_V(v) ((v)*255 + 0x8000)

static uint32_t ss_pack(int32_t r, int32_t g, int32_t b)
{
    return ((uint32_t)r & 0xFF0000u) | ((uint32_t)g >> 16) << 8 | (uint32_t)b >> 16;
}

/* The pixel of a colour in [0, 1] as the fill gives a corner: r_to_byte of each channel's
 * r_unit_to_q16 (rt_color_pixel's, in the fixed-point build). */
static uint32_t ss_pixel(const rt_color *c)
{
    return ss_pack(SS_V(r_unit_to_q16(c->x)), SS_V(r_unit_to_q16(c->y)), SS_V(r_unit_to_q16(c->z)));
}

/* One channel of a 2x2 fill (ss_fill's rows for w = h = 2, where every weight is 1/2): corners
 * a (0, 0), b (2, 0), c (0, 2), d (2, 2); the bytes of pixels (0, 0), (1, 0), (0, 1) and (1, 1),
 * shifted left by sh, are or'ed into p[0..3]. */
static inline void ss_quad_ch(int32_t a, int32_t b, int32_t c, int32_t d, int sh, uint32_t p[4])
{
    int32_t l = a + ss_half(c - a), r = b + ss_half(d - b);
    p[0] |= (uint32_t)SS_V(a) >> 16 << sh;
    p[1] |= (uint32_t)SS_V(a + ss_half(b - a)) >> 16 << sh;
    p[2] |= (uint32_t)SS_V(l) >> 16 << sh;
    p[3] |= (uint32_t)SS_V(l + ss_half(r - l)) >> 16 << sh;
}

/* One row of the fill: pixel 0 from the V forms v0..v2 (SS_V), pixels 1..n-1 by adding the steps
 * s0..s2 (V units) once per pixel. */
static inline __attribute__((always_inline)) void ss_row(uint32_t *dst, int n, int32_t v0,
                                                         int32_t v1, int32_t v2, int32_t s0,
                                                         int32_t s1, int32_t s2)
{
    dst[0] = ss_pack(v0, v1, v2);
    for (int i = 1; i < n; i++) {
        v0 += s0;
        v1 += s1;
        v2 += s2;
        dst[i] = ss_pack(v0, v1, v2);
    }
}

/* Bilinear fill of `cols` x `rows` pixels from dst (cols <= w + 1, rows <= h + 1) from the
 * colours of the corners k[]: (0, 0), (w, 0), (0, h), (w, h), each in [0, 1]. Row j's ends are
 * l = k0 + ss_mul(k2 - k0, j / h) and r = k1 + ss_mul(k3 - k1, j / h) (k2 and k3 themselves in
 * row h), in [0, 65536] (ss_mul); pixel i of the row, 0 < i < w, is l + i s with
 * s = ss_mul(r - l, 1 / w) by forward differences (added up in the V form: V_i = V_0 + i 255 s,
 * the same integers); column w is r itself. As |s - (r - l) / w| <= 1/2 + |r - l|
 * |1/w - ss_wrow(w)[1] / 2^16| <= 1, pixel i is within i <= 15 of the exact l + i (r - l) / w, a
 * value in [0, 65536]: every channel packed lies in [-15, 65551], inside ss_pack's range. */
static void ss_fill(uint32_t *dst, int stride, int w, int h, int cols, int rows,
                    const rt_color *const k[4])
{
    /* q: the corners' channels, k0 k1 (row 0's ends) then k2 k3 (row h's) */
    int32_t q[12], m[6];
    for (int n = 0; n < 4; n++) {
        q[3 * n] = r_unit_to_q16(k[n]->x);
        q[3 * n + 1] = r_unit_to_q16(k[n]->y);
        q[3 * n + 2] = r_unit_to_q16(k[n]->z);
    }
    if (w == 2 && h == 2 && cols == 2 && rows == 2) {
        /* The usual leaf, a 2x2 square without the frame's last column or row: every weight
         * is 1/2, and ss_mul(d, 1/2) is ss_half(d). The same values as the rows below. */
        uint32_t p[4] = {0, 0, 0, 0};
        for (int ch = 0; ch < 3; ch++)
            ss_quad_ch(q[ch], q[3 + ch], q[6 + ch], q[9 + ch], 16 - 8 * ch, p);
        dst[0] = p[0];
        dst[1] = p[1];
        dst[stride] = p[2];
        dst[stride + 1] = p[3];
        return;
    }
    if (q[0] == q[3] && q[0] == q[6] && q[0] == q[9] && q[1] == q[4] && q[1] == q[7] &&
        q[1] == q[10] && q[2] == q[5] && q[2] == q[8] && q[2] == q[11]) {
        /* One colour (dark or empty parts of a frame): every l, r the rows below compute is
         * that colour and every step 0, so each of the pixels (columns 0..cols-1) gets it. */
        uint32_t px = ss_pack(SS_V(q[0]), SS_V(q[1]), SS_V(q[2]));
        for (int j = 0; j < rows; j++, dst += stride)
            for (int i = 0; i < cols; i++)
                dst[i] = px;
        return;
    }
#ifndef __OPTIMIZE_SIZE__
    if (w >= 2 && h >= 2 && !(w & (w - 1)) && !(h & (h - 1))) {
        /* Sides of 2, 4, 8 or 16 (every square but those that end the frame): the weights are
         * j / h = j 2^(16 - kh) exactly, so row j's ends q + ss_mul(d, j / h) (d the side's
         * difference) are q + ss_shr_round(d j, kh) = (q 2^kh + 2^(kh - 1) + [d < 0 ? -1 : 0]
         * + j d) >> kh: one multiply-accumulate each, which gives q itself at j = 0 and the far
         * corner's at j = h. The step along a row is ss_shr_round(r - l, kw). The same values
         * as the rows below, in fewer instructions (not in builds for size, -Os: the intro
         * player keeps the rows below alone). */
        const int kh = __builtin_ctz((unsigned)h), kw = __builtin_ctz((unsigned)w);
        int32_t e[12]; /* for each end n: e[2n] + j e[2n + 1] is its sum at row j */
        for (int n = 0; n < 6; n++) {
            e[2 * n + 1] = q[n + 6] - q[n];
            e[2 * n] = q[n] * h + (1 << (kh - 1)) + (e[2 * n + 1] >> 31);
        }
        const int right = cols > w, inner = cols < w ? cols : w;
        for (int j = 0; j < rows; j++, dst += stride) {
            const int32_t l0 = (e[0] + j * e[1]) >> kh, l1 = (e[2] + j * e[3]) >> kh,
                          l2 = (e[4] + j * e[5]) >> kh;
            const int32_t r0 = (e[6] + j * e[7]) >> kh, r1 = (e[8] + j * e[9]) >> kh,
                          r2 = (e[10] + j * e[11]) >> kh;
            int32_t v0 = SS_V(l0), v1 = SS_V(l1), v2 = SS_V(l2);
            const int32_t s0 = ss_shr_round(r0 - l0, kw) * 255,
                          s1 = ss_shr_round(r1 - l1, kw) * 255,
                          s2 = ss_shr_round(r2 - l2, kw) * 255;
            ss_row(dst, inner, v0, v1, v2, s0, s1, s2);
            if (right)
                dst[w] = ss_pack(SS_V(r0), SS_V(r1), SS_V(r2));
        }
        return;
    }
#endif
    const uint16_t *wy = ss_wrow(h); /* read at 0 < j < h */
    int32_t sx = ss_wrow(w)[1];      /* w <= 1: ss_wq[1], 0 (unused) */
    int inner = cols < w ? cols : w; /* columns 0..inner-1 come from the left edge and steps */
    int right = cols > w && w > 0;   /* column w: the right edge's colour */
    for (int j = 0; j < rows; j++, dst += stride) {
        const int32_t *e = q; /* the row's ends: l in e[0..2], r in e[3..5] */
        if (j > 0 && j == h)
            e = q + 6;
        else if (j > 0) {
            for (int n = 0; n < 6; n++)
                m[n] = q[n] + ss_mul(q[n + 6] - q[n], wy[j]);
            e = m;
        }
        int32_t v0 = SS_V(e[0]), v1 = SS_V(e[1]), v2 = SS_V(e[2]);
        if (inner > 1)
            ss_row(dst, inner, v0, v1, v2, ss_mul(e[3] - e[0], sx) * 255,
                   ss_mul(e[4] - e[1], sx) * 255, ss_mul(e[5] - e[2], sx) * 255);
        else
            dst[0] = ss_pack(v0, v1, v2);
        if (right)
            dst[w] = ss_pack(SS_V(e[3]), SS_V(e[4]), SS_V(e[5]));
    }
}

void rt_interpolate(uint32_t *dst, int stride, int w, int h, int cols, int rows, rt_color c00,
                    rt_color c10, rt_color c01, rt_color c11)
{
    if (w > RT_GRID_MAX || h > RT_GRID_MAX || cols > w + 1 || rows > h + 1)
        return;
    rt_color c[4] = {c00, c10, c01, c11};
    for (int i = 0; i < 4; i++)
        c[i] = v3(r_clamp(c[i].x, 0, R_ONE), r_clamp(c[i].y, 0, R_ONE), r_clamp(c[i].z, 0, R_ONE));
    const rt_color *const k[4] = {&c[0], &c[1], &c[2], &c[3]};
    ss_fill(dst, stride, w, h, cols, rows, k);
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
    int split;      /* set when a square of the lattice is split (its points traced) */
    /* How ss_quad's points are traced: in adaptive and probe mode, within a top-level square of the
     * full grid, as full mode traces them (p_quad, without the other tone of a checker,
     * rt_sample.alt), since no square ever has one of them as a corner: they lie at odd
     * offsets, where every square split further has its corners at even ones (sizes are
     * powers of two); else as the others (params). */
    const rt_params *quad;
    rt_params p_quad;
    rt_probe_masks opaque; /* probe mode: what rt_probe_opaque tests */
    dir3 ray;              /* ss_hit_at: the last primary ray's direction */
    real wt[RT_GRID_BUILD_MAX + 1][RT_GRID_BUILD_MAX + 1]; /* wt[n][i] = i / n */
    /* The square whose split adds the points traced now, when its corners' local parts can be
     * interpolated (ss_local_ok), else NULL */
    const struct ss_area *area;
    rt_local loc; /* ss_local's result for the point traced */
} ss_ctx;

/* A square split for its secondary rays whose points' local parts are interpolated (ss_local_ok):
 * its corners k[] ((0, 0), (w, 0), (0, h), (w, h)) and its (0, 0) at pixel (x0, y0). */
typedef struct ss_area {
    const rt_sample *const *k;
    int x0, y0, w, h;
} ss_area;

/* The local part of point (x, y) of the square c->area (rt_local), a point its split adds: its
 * corners' primary object, cell and light states, and their node-0 contributions interpolated
 * bilinearly at the point. It lies at 0, half or the whole of each side (ss_local_ok), so its
 * weights are equal over the corners they do not leave out (1, 2 or 4), and each channel is
 * their mean. In integers, the same in both builds: a byte b as b 257 / 2^16 in Q16.16 (within
 * 2^-16 of b / 255), a sum of 4 bytes times 257 (below 2^19) divided by 4, rounded. No other
 * tone is kept (alt_known 0): such points are hardly ever the corners of a texture square
 * (intro frames 0..1200 step 100: 3,200 texture squares instead of 3,207 with the other tone
 * interpolated too, for about 330 bytes more of the board's code). Out of line and cold: off
 * the usual path. */
static __attribute__((cold, noinline)) const rt_local *ss_local(ss_ctx *c, int x, int y)
{
    rt_local *loc = &c->loc;
    const ss_area *a = c->area;
    const rt_sample *const *k = a->k;
    const int i = x - a->x0, j = y - a->y0;
    /* the columns ca..cb and rows ra..rb of the corners its weights keep; the four terms
     * p0..p3 repeat a corner once over for each side it is at the end of: their sum is 4 times
     * the mean */
    const int cb = i != 0, ca = cb && i == a->w, rb = j != 0, ra = rb && j == a->h;
    const uint8_t *p0 = k[2 * ra + ca]->hits[0].contrib, *p1 = k[2 * ra + cb]->hits[0].contrib,
                  *p2 = k[2 * rb + ca]->hits[0].contrib, *p3 = k[2 * rb + cb]->hits[0].contrib;
    int32_t q[3];
    for (int n = 0; n < 3; n++)
        q[n] = ((p0[n] + p1[n] + p2[n] + p3[n]) * 257 + 2) >> 2;
    loc->col = v3(r_from_q16(q[0]), r_from_q16(q[1]), r_from_q16(q[2]));
    loc->id = k[0]->hits[0].object;
    loc->cell = k[0]->cell;
    loc->lights = k[0]->lights;
    return loc;
}

/* Adds `bit` to a point's byte of the traced map. Bands running at the same time both trace the
 * points on the edge between them, so the bit is added atomically: inline where the core has
 * byte atomics, through libatomic on a hosted system without them; plainly only on a
 * freestanding core without them (the ARM926 board, which renders on one thread). */
static inline void ss_mark(uint8_t *t, uint8_t bit)
{
#if (defined(__GCC_ATOMIC_CHAR_LOCK_FREE) && __GCC_ATOMIC_CHAR_LOCK_FREE == 2) || __STDC_HOSTED__
    __atomic_fetch_or(t, bit, __ATOMIC_RELAXED);
#else
    *t |= bit;
#endif
}

/* Shades the point (x, y) in full into *out (in probe mode from the primary hit a probe found,
 * *pri, if not NULL), clamps its colour, marks it (RT_TRACED_FULL, or RT_TRACED_LOCAL where it
 * took its local part from the square's corners), and in probe mode sets its flags. */
static void ss_shade(ss_ctx *c, int x, int y, rt_sample *out, rt_primary *pri)
{
    uint8_t mark = RT_TRACED_FULL;
    if (RT_COMPILED_PROBE && pri) {
        rt_trace_pixel_from(c->scene, c->view, c->params, x, y, pri, c->stats, out);
        out->flags = (uint8_t)rt_probe_opaque(&c->opaque, out);
    } else {
        const rt_local *loc = NULL;
        uint32_t local0 = 0;
        if (c->area) {
            loc = ss_local(c, x, y);
            local0 = c->stats->local_points;
        }
        rt_trace_pixel_local(c->scene, c->view, c->params, x, y, loc, c->stats, out);
        if (loc && c->stats->local_points != local0)
            mark = RT_TRACED_LOCAL;
        out->flags = RT_COMPILED_PROBE && c->params->mode == RT_MODE_PROBE
            ? (uint8_t)rt_probe_opaque(&c->opaque, out)
            : 0;
    }
    /* Interpolate what is shown: colours clamped as the pixel will be. */
    out->color = v3(r_clamp(out->color.x, 0, R_ONE), r_clamp(out->color.y, 0, R_ONE),
                    r_clamp(out->color.z, 0, R_ONE));
    if (c->traced)
        ss_mark(&c->traced[(long)y * c->view->width + x], mark);
}

static void ss_trace(ss_ctx *c, int x, int y, rt_sample *out) { ss_shade(c, x, y, out, NULL); }

/* The sample sm of the current square's lattice, the point (x, y): traced on first use. */
static inline void ss_need(ss_ctx *c, int x, int y, rt_sample *sm)
{
    if (sm->nhits == 0)
        ss_trace(c, x, y, sm);
}

/* Probe mode: the point (x, y) a split adds in the middle of an edge from a to b (at fraction
 * t, span pixels long), not decided yet (rt_probe_point); probed, and shaded in full only when
 * rt_probe_point cannot give its colour. */
FX_BOARD_THUMB
static __attribute__((noinline)) void ss_probe_new(ss_ctx *c, int x, int y, const rt_sample *a,
                                                   const rt_sample *b, real t, int span)
{
    rt_sample *sm = &c->lat[(y - c->sy) * c->lstride + (x - c->sx)];
    rt_primary pri;
    int r = rt_probe_point(c->scene, c->view, c->stats, c->thr8, x, y, a, b, t, span, &pri, sm);
    if (r > 0) {
        if (c->traced)
            ss_mark(&c->traced[(long)y * c->view->width + x], RT_TRACED_PROBE);
    } else if (r == 0) {
        ss_shade(c, x, y, sm, &pri); /* in full, from the primary hit the probe found */
    } /* else not probed: shaded where the squares below need it (ss_need), as adaptive mode does */
}

/* Can an edge from a to b have a point worth probing (rt_probe_point)? Not when both ends are
 * opaque or they disagree on a light. */
static inline int ss_probe_edge(const rt_sample *a, const rt_sample *b)
{
    return !(a->flags & b->flags & RT_SAMPLE_OPAQUE) && a->lights == b->lights;
}

/* Probe mode: the points splitting the square (x0, y0, w, h) into nx by ny adds (k: its
 * corners) in the middles of the edges it halves, each against the ends of its edge. (Not its
 * centre: a probe there against the four corners measured dearer on the board than the shades
 * it saved, docs/probe.md; it is shaded where the squares below need it.) A point some square
 * added before is kept: it got its record from the same context (the ends of its edge), so the
 * frame does not depend on the order squares are visited in. */
static __attribute__((noinline)) void ss_probe_split(ss_ctx *c, int x0, int y0, int w, int h,
                                                     int nx, int ny, const rt_sample *const k[4])
{
    if (k[0]->flags & k[1]->flags & k[2]->flags & k[3]->flags & RT_SAMPLE_OPAQUE)
        return; /* every end opaque: no point is probed (ss_probe_edge) */
    /* the lattice at (x0, y0): a point already decided (nhits) is kept */
    const rt_sample *at = &c->lat[(y0 - c->sy) * c->lstride + (x0 - c->sx)];
    for (int j = 0; j < 2 && nx == 2; j++) /* top, bottom: k[0], k[1] and k[2], k[3] */
        if (!at[j * h * c->lstride + w / 2].nhits && ss_probe_edge(k[2 * j], k[2 * j + 1]))
            ss_probe_new(c, x0 + w / 2, y0 + j * h, k[2 * j], k[2 * j + 1], c->wt[w][w / 2], w);
    for (int i = 0; i < 2 && ny == 2; i++) /* left, right: k[0], k[2] and k[1], k[3] */
        if (!at[h / 2 * c->lstride + i * w].nhits && ss_probe_edge(k[i], k[i + 2]))
            ss_probe_new(c, x0 + i * w, y0 + h / 2, k[i], k[i + 2], c->wt[h][h / 2], h);
}

/* A split 2x2 square that does not end the frame (sm: its (0, 0) in the lattice): what its
 * four unit squares would do in ss_square, without the calls. They trace the five points
 * between the corners, in this order, and each shows its (0, 0) as the fill shows a corner. */
static void ss_quad(ss_ctx *c, rt_sample *sm, int x0, int y0)
{
    const int ls = c->lstride, stride = c->stride;
    uint32_t *row = c->pixels + (long)(y0 - c->py0) * stride + x0;
    rt_sample *m = sm + ls;
    const rt_params *p = c->params;
    c->params = c->quad; /* see ss_ctx */
    ss_need(c, x0 + 1, y0, sm + 1);
    ss_need(c, x0, y0 + 1, m);
    ss_need(c, x0 + 1, y0 + 1, m + 1);
    ss_need(c, x0 + 2, y0 + 1, m + 2);
    ss_need(c, x0 + 1, y0 + 2, m + ls + 1);
    c->params = p;
    row[0] = ss_pixel(&sm->color);
    row[1] = ss_pixel(&sm[1].color);
    row[stride] = ss_pixel(&m->color);
    row[stride + 1] = ss_pixel(&m[1].color);
}

/* Pixel (x, y)'s primary ray and its hit on object `id` as the tracer forms them (rt_view_ray,
 * rt_nearest_primary, the point along the ray): 1 and the point in *at, its distance in *t, or 0
 * for a ray that misses the object (a corner's neighbour, by rounding); the ray's direction in
 * c->ray. */
static __attribute__((noinline)) int ss_hit_at(ss_ctx *c, int id, int x, int y, vec3 *at, real *t)
{
    const rt_view *v = c->view;
    c->ray = rt_view_ray(v, x, y);
#if RT_COMPILED_PROBE
    const rt_scene *s = c->scene;
    if (s->plane_set >> id & 1 ? !rt_plane_primary(s, id, c->ray, t)
                               : rt_nearest_primary(s, c->ray, (uint32_t)1 << id, t) != id)
        return 0; /* a plane: its test alone (rt_plane_primary), the same t */
#else
    if (rt_nearest_primary(c->scene, c->ray, (uint32_t)1 << id, t) != id)
        return 0;
#endif
    *at = v3_along_in(v->eye, c->ray, *t);
    return 1;
}

/* The cell (rt_sample.cell) of the checker of material m on plane `id` at pixel (x, y), where
 * its primary ray meets the plane (ss_hit_at), so the same cell as a full shade finds; 0 for a
 * ray that misses the plane. Counted in texture_pixels. */
static __attribute__((cold, noinline)) uint8_t ss_cell_at(ss_ctx *c, const rt_material *m, int id,
                                                          int x, int y)
{
    c->stats->texture_pixels++;
    vec3 at;
    real t;
    uint8_t cell = 0;
    if (ss_hit_at(c, id, x, y, &at, &t))
        rt_texture_color(m, at, 0, 0, c->stats, &cell);
    return cell;
}

/* A square that rt_corners_differ would split for its primary object (RT_SPLIT_OBJECT), k[] its
 * corners (sm: its (0, 0) in the lattice): when the corners lie on one plane whose material is a
 * two-tone checker and differ only in their cells, the square is not split as long as the
 * corners agree for either tone: with each corner's cell made the same and its primary node's
 * contribution made its whole colour in that tone (its own colour, or rt_sample.alt for the
 * other tone), rt_corners_differ finds no difference (light states, ray tree, secondary
 * contributions, and those colours within the threshold). Shading is linear in the diffuse
 * colour, so each pixel then gets the bilinear interpolation (ss_fill) of the corners' colours
 * in the tone of its own cell, looked up where its primary ray meets the plane (ss_tone_at: a
 * ray and a plane test instead of a full shade). Returns 1 when it filled the pixels the square
 * owns (as ss_fill: `cols` x `rows`; points traced before keep their colour), 0 to split.
 * Out of line (off ss_square's path), compiled for speed on the board. */
static __attribute__((noinline)) int ss_cells(ss_ctx *c, const rt_sample *sm, int x0, int y0, int w,
                                              int h, int own)
{
    const rt_scene *s = c->scene;
    const int id = sm->hits[0].object, cols = w + (own & 1), rows = h + (own >> 1 & 1);
    if (id == RT_NO_OBJECT || !(s->plane_set >> id & 1))
        return 0;
    /* tc[tone][corner]: the corners' colours in either tone, in [0, 1] */
    rt_color tc[2][4];
    rt_sample kk[4];
    const rt_sample *kp[4];
    for (int i = 0; i < 4; i++) {
        const rt_sample *q = sm + (i >> 1) * h * c->lstride + (i & 1) * w; /* corner i */
        if (q->alt_known != 1) /* its other tone's colour is known */
            return 0;
        int t = rt_cell_tone(q->cell);
        tc[t][i] = q->color;
        /* a byte b as the colour b / 255 (b 257 / 2^16 is within 2^-16 of it) */
        tc[!t][i] = v3(r_from_q16(q->alt[0] * 257), r_from_q16(q->alt[1] * 257),
                       r_from_q16(q->alt[2] * 257));
        kk[i] = *q;
        kk[i].cell = 1;
        kp[i] = &kk[i];
    }
    /* tone 0 into the frame, tone 1 aside (a split square's pixels are all written again by its
     * parts); each pixel then takes its own cell's */
    uint32_t *dst = c->pixels + (long)(y0 - c->py0) * c->stride + x0;
    uint32_t other[(RT_GRID_BUILD_MAX + 1) * (RT_GRID_BUILD_MAX + 1)];
    for (int t = 0; t < 2; t++) {
        const rt_color *kc[4];
        for (int i = 0; i < 4; i++) {
            uint32_t px = ss_pixel(&tc[t][i]);
            kk[i].hits[0].contrib[0] = (uint8_t)(px >> 16);
            kk[i].hits[0].contrib[1] = (uint8_t)(px >> 8);
            kk[i].hits[0].contrib[2] = (uint8_t)px;
            kc[i] = &tc[t][i];
        }
        if (rt_corners_differ(kp, c->thr8) != RT_SPLIT_NONE)
            return 0;
        ss_fill(t ? other : dst, t ? RT_GRID_BUILD_MAX + 1 : c->stride, w, h, cols, rows, kc);
    }
    /* Each pixel's cell, coarse to fine over the square's lattice (its pixels, and its right
     * column and bottom row for their neighbours): looked up at the points whose coordinates
     * are multiples of 4, then at the multiples of 2 and of 1 in turn only where the points a
     * step away on either side (left and right, above and below, or the four diagonal ones)
     * are not all in one cell. A cell is a convex square on the plane, and so is its image: a
     * point between two of its points lies in it. (Cell ids repeat every four cells along each
     * axis: cells so small that points four pixels apart are four cells apart have tones no
     * picture resolves.) Points traced before keep their colour and give their cell. */
    const rt_material *m = &s->materials[s->objects[id].material];
    const int cs = RT_GRID_BUILD_MAX + 1;
    uint8_t cid[(RT_GRID_BUILD_MAX + 1) * (RT_GRID_BUILD_MAX + 1)];
    for (int d = 4; d >= 1; d >>= 1)
        for (int j = 0; j <= h && (d > 1 || j < rows); j += d) {
            /* the row's points not done at a coarser step: every d-th, or (a row done at
             * the coarser step) the odd multiples of d; at step 1 only the square's own */
            const int dj = j & d & 3, fine = d < 4 && !dj; /* dj: d or 0 (step 4: 0) */
            const int mrow = j<rows, iend = d> 1 ? w : cols - 1;
            uint8_t *qrow = &cid[j * cs];
            const rt_sample *prow = sm + j * c->lstride;
            uint32_t *drow = dst + (long)j * c->stride;
            const int step = d << fine;
            for (int i = fine ? d : 0; i <= iend; i += step) {
                const int mine = mrow && i < cols;
                uint8_t *q = &qrow[i];
                const rt_sample *pt = prow + i;
                if (pt->nhits) { /* a corner, or a point on the top or left edge */
                    *q = pt->hits[0].object == id ? pt->cell : 0;
                    if (mine)
                        drow[i] = ss_pixel(&pt->color);
                    continue;
                }
                int cell = 0;
                const int di = i & d; /* d or 0: the neighbours' offsets */
                if (d < 4 && i + di <= w && j + dj <= h) {
                    int a = q[-di - dj * cs], b = q[di + dj * cs];
                    if (di && dj && (q[di - dj * cs] != a || q[dj * cs - di] != a))
                        a = 0; /* the other diagonal */
                    cell = a == b ? a : 0;
                }
                if (!cell)
                    cell = ss_cell_at(c, m, id, x0 + i, y0 + j);
                *q = (uint8_t)cell;
                if (mine && cell && rt_cell_tone((uint8_t)cell))
                    drow[i] = other[j * cs + i];
            }
        }
    return 1;
}

/* A square that rt_corners_differ would split for a contribution (RT_SPLIT_CONTRIB: one object,
 * the same light states and ray tree), k[] its corners (sm: its (0, 0) in the lattice): when
 * every corner lies on a noise texture with its A and B kept (rt_sample.alt_known 2: no
 * secondary ray) and they agree within the threshold on the part of their colour the texture
 * does not change, t A + B for one texture colour t (the corners' mean, sum (C - B) / sum A
 * clamped to [0, 1]; in bytes, multiplied out by sum A), the square is not split for the
 * texture's colour: each pixel gets b x A + B, A and B interpolated bilinearly from the corners'
 * (ss_fill, as bytes: A / 2 and B are within [0, 1]: A <= RT_NOISE_A_MAX) and b the texture at
 * the pixel's own hit (ss_hit_at: a ray and the object's test, no shading; the tracer's octave
 * rule). Returns 1 when it filled the pixels the square owns (as ss_fill:
 * `cols` x `rows`; points traced before keep their colour), 0 to split (also when a pixel's ray
 * misses the object: the split writes every pixel again). In integers: A in Q15 (byte x 257,
 * below 2), b and B in Q16.16, b x A below 2^32; the criterion's terms below 2^20. 1.2 kB of
 * stack, less than the nested shading it replaces. */
static __attribute__((noinline)) int ss_noise(ss_ctx *c, const rt_sample *sm,
                                              const rt_sample *const k[4], int x0, int y0, int w,
                                              int h, int own)
{
    /* ab[corner]: A / 2 and B as colours (a byte b as b 257 / 2^16, within 2^-16 of b / 255) */
    rt_color ab[2][4];
    const rt_color *ka[4], *kb[4];
    int32_t num[3] = {0, 0, 0}, den[3] = {0, 0, 0};
    for (int i = 0; i < 4; i++) {
        const rt_sample *p = k[i];
        const uint8_t *a = p->alt, *b = p->hits[1].contrib;
        if (p->alt_known != 2)
            return 0;
        const uint32_t px = ss_pixel(&p->color);
        for (int ch = 0; ch < 3; ch++) {
            num[ch] += (int32_t)(px >> (16 - 8 * ch) & 255) - b[ch];
            den[ch] += 2 * a[ch];
        }
        ab[0][i] = v3(r_from_q16(a[0] * 257), r_from_q16(a[1] * 257), r_from_q16(a[2] * 257));
        ab[1][i] = v3(r_from_q16(b[0] * 257), r_from_q16(b[1] * 257), r_from_q16(b[2] * 257));
        ka[i] = &ab[0][i];
        kb[i] = &ab[1][i];
    }
    for (int ch = 0; ch < 3; ch++) { /* d (t A + B) = n 2 A + d B with t = n / d */
        const int32_t d = den[ch] > 0 ? den[ch] : 1;
        int32_t n = num[ch] > 0 ? num[ch] : 0, lo = 1 << 30, hi = -lo;
        n = n < d ? n : d;
        for (int i = 0; i < 4; i++) {
            const int32_t v = 2 * n * k[i]->alt[ch] + d * k[i]->hits[1].contrib[ch];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        if (hi - lo > c->thr8 * d)
            return 0;
    }
    /* A / 2 aside and B into the frame, as ss_fill interpolates colours, as bytes; each pixel
     * then gets b x A + B from them */
    const int id = sm->hits[0].object, cols = w + (own & 1), rows = h + (own >> 1 & 1),
              cs = RT_GRID_BUILD_MAX + 1;
    const rt_material *m = &c->scene->materials[c->scene->objects[id].material];
    const rt_params *p = c->params;
    const real tmax = r_muli(R_SCENE_MAX, 2);
    uint32_t *dst = c->pixels + (long)(y0 - c->py0) * c->stride + x0;
    uint32_t half_a[(RT_GRID_BUILD_MAX + 1) * (RT_GRID_BUILD_MAX + 1)];
    ss_fill(half_a, cs, w, h, cols, rows, ka);
    ss_fill(dst, c->stride, w, h, cols, rows, kb);
    for (int j = 0; j < rows; j++, dst += c->stride)
        for (int i = 0; i < cols; i++) {
            const rt_sample *pt = sm + j * c->lstride + i;
            vec3 at;
            real t;
            if (pt->nhits) { /* a corner, or a point a neighbour traced */
                dst[i] = ss_pixel(&pt->color);
                continue;
            }
            c->stats->noise_pixels++;
            if (!ss_hit_at(c, id, x0 + i, y0 + j, &at, &t))
                return 0; /* a miss, by rounding */
            /* the texture as trace_ray finds it: its octaves, and with the footprint the view's
             * pixel times the distance, capped as trace_ray caps a path */
            const real fp = p->footprint ? r_mul(c->view->pixel, t < tmax ? t : tmax) : 0;
            uint8_t cell;
            const rt_color b = rt_texture_color(m, at, p->octaves, fp, c->stats, &cell);
            const uint32_t bq[3] = {(uint32_t)r_unit_to_q16(b.x), (uint32_t)r_unit_to_q16(b.y),
                                    (uint32_t)r_unit_to_q16(b.z)};
            uint32_t px = 0;
            for (int ch = 0, sh = 16; ch < 3; ch++, sh -= 8) {
                /* b (Q16.16) x A (Q15: 2 byte / 255 as byte x 257) + B (Q16.16) */
                const int32_t v =
                    (int32_t)((bq[ch] * ((half_a[j * cs + i] >> sh & 255) * 257) + 0x4000u) >> 15) +
                    (int32_t)(dst[i] >> sh & 255) * 257;
                px |= (uint32_t)SS_V(v < 65536 ? v : 65536) >> 16 << sh;
            }
            dst[i] = px;
        }
    return 1;
}

/* Shadow pixels: the largest square side filled so (ss_shadow; measured on the board: larger
 * squares cost more per pixel tested than their split). */
#define SS_SHADOW_MAX 4

/* Light i at pixel (x, y)'s primary hit on sm's primary object, a plane, found and formed as
 * trace_ray forms it (ss_hit_at; the plane's normal, d . n, the point lifted off the surface;
 * the diffuse colour, the material's or its checker's in sm's cell), seen by trace_light
 * (rt_light_term): with term
 * NULL its state as the pixel's full shade decides it, else its state and its term where nothing
 * would occlude it, in *term; -1 for a ray that misses the object or meets it from behind (where
 * trace_ray turns the normal). */
static __attribute__((noinline)) int ss_light(ss_ctx *c, const rt_sample *sm, int i, int x, int y,
                                              rt_color *term)
{
    const int id = sm->hits[0].object, cell = sm->cell;
    const rt_scene *s = c->scene;
    const rt_object *o = &s->objects[id];
    rt_hit h;
    real t;
    if (!ss_hit_at(c, id, x, y, &h.p, &t))
        return -1;
    h.d = c->ray;
    h.n = o->normal; /* a plane's (rt_shapes' plane normal) */
    h.dn = d3_dot(h.d, h.n);
    if (h.dn > 0)
        return -1;
    h.m = &s->materials[o->material];
    h.id = id;
    h.inside = 0;
    h.p_out = v3_along_in(h.p, h.n, R_EPS_OFFSET);
    h.base = cell && rt_cell_tone((uint8_t)cell) ? h.m->tex.color2 : h.m->diffuse;
    return rt_light_term(s, c->stats, &h, i, term);
}

/* Do colours k[0..3] (in [0, 1]) differ by more than lim (Q16.16) in some channel? */
static int ss_spread(const rt_color *const k[4], int32_t lim)
{
    for (int ch = 0; ch < 3; ch++) {
        int32_t lo = 65536, hi = 0;
        for (int n = 0; n < 4; n++) {
            const int32_t v = r_unit_to_q16(ch == 0 ? k[n]->x : ch == 1 ? k[n]->y : k[n]->z);
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        if (hi - lo > lim)
            return 1;
    }
    return 0;
}

/* A square of at most SS_SHADOW_MAX a side, not on the frame's last row or column, that
 * rt_corners_differ splits for its lights (RT_SPLIT_LIGHT), k[] its corners (k[0]: its (0, 0) in
 * the lattice): when the corners lie on a plane and differ only in light i, lit at some and
 * unlit at others, with no highlight at any corner, each corner's colour is C = D + s T: s 1
 * where light i lights it, T the light's term there as trace_light would add it if nothing
 * occluded the light (ss_light:
 * the corner's primary hit again, trace_light's Lambert and Phong terms, no shadow ray), D its
 * colour without it. Each corner gets its colour unlit, D, and lit, L = D + T: its own colour
 * for its own state, C - T or C + T in the other, within [0, 1] (a lit corner clamped at 1 gives
 * a D darker than its own: the range test below sees most of that). Where D and L each agree
 * within the threshold over the corners (as an unsplit square's contributions do;
 * rt_corners_differ found the same ray tree at every corner) and the light faces every corner,
 * the square is not split: D and L are interpolated as colours are (ss_fill: D into the frame,
 * L aside), and each pixel takes D or L as light i lights its own primary hit or not, decided
 * as its full shade decides it (ss_light: its ray, the object's test, trace_light with its
 * shadow ray). Returns 1 when it filled the w x h pixels the square owns (points traced before
 * keep their colour), 0 to split (also when a pixel's ray misses the object). Not on a noise
 * texture (its colour is not the corners' in between: ss_noise's) nor where the view's eye is
 * not the prepared one (ss_hit_at). Not on a sphere either: a sphere's lit and unlit corners
 * are nearly always either side of its terminator, where the light stops facing it (measured
 * over the intro's 13 benchmark frames: 4 of 2,906 squares filled were on spheres, for many
 * tries that failed at their corners' terms). 64 bytes of stack for the lit colours. */
static __attribute__((noinline)) int ss_shadow(ss_ctx *c, const rt_sample *const k[4], int x0,
                                               int y0, int w, int h)
{
    const rt_sample *sm = k[0];
    const unsigned l0 = k[0]->lights,
                   diff = (l0 ^ k[1]->lights) | (l0 ^ k[2]->lights) | (l0 ^ k[3]->lights);
    const int li = diff ? __builtin_ctz(diff) >> 1 : 0; /* the light that differs */
    /* exactly one light differs (one bit: lit or not), no highlight at any corner (at corner 0,
     * or where the bit that differs is a highlight's); rt_nearest_primary needs the prepared eye */
    const int id = sm->hits[0].object;
    const rt_material *m = &c->scene->materials[c->scene->objects[id].material];
    if (w > SS_SHADOW_MAX || diff != 1u << (2 * li) || (l0 & RT_LIGHTS_HIGHLIGHT) ||
        (m->tex.active && !sm->cell) || !(c->scene->plane_set >> id & 1) ||
        !rt_scene_at_eye(c->scene, c->view->eye))
        return 0;
    rt_color dl[2][4]; /* D and L */
    const rt_color *kd[2][4];
    for (int n = 0; n < 4; n++) {
        const int lit = rt_light_state(k[n], li);
        rt_color t;
        if (ss_light(c, sm, li, x0 + (n & 1) * w, y0 + (n >> 1) * h, &t) != 1)
            return 0; /* a miss, a highlight, or a corner the light does not face */
        const int32_t cq[3] = {r_unit_to_q16(k[n]->color.x), r_unit_to_q16(k[n]->color.y),
                               r_unit_to_q16(k[n]->color.z)},
                      tq[3] = {r_unit_to_q16(t.x), r_unit_to_q16(t.y), r_unit_to_q16(t.z)};
        int32_t d[3], l[3];
        for (int ch = 0; ch < 3; ch++) {
            d[ch] = !lit ? cq[ch] : cq[ch] > tq[ch] ? cq[ch] - tq[ch] : 0;
            l[ch] = lit ? cq[ch] : cq[ch] < 65536 - tq[ch] ? cq[ch] + tq[ch] : 65536;
        }
        dl[0][n] = v3(r_from_q16(d[0]), r_from_q16(d[1]), r_from_q16(d[2]));
        dl[1][n] = v3(r_from_q16(l[0]), r_from_q16(l[1]), r_from_q16(l[2]));
        kd[0][n] = &dl[0][n];
        kd[1][n] = &dl[1][n];
    }
    /* D and L each within the threshold over the corners (a byte is 257 in Q16.16) */
    for (int j = 0; j < 2; j++)
        if (ss_spread(kd[j], c->thr8 * 257))
            return 0;
    const int cs = SS_SHADOW_MAX;
    uint32_t *dst = c->pixels + (long)(y0 - c->py0) * c->stride + x0;
    uint32_t lit_px[SS_SHADOW_MAX * SS_SHADOW_MAX];
    ss_fill(dst, c->stride, w, h, w, h, kd[0]);
    ss_fill(lit_px, cs, w, h, w, h, kd[1]);
    for (int j = 0; j < h; j++, dst += c->stride)
        for (int i = 0; i < w; i++) {
            const rt_sample *pt = sm + j * c->lstride + i;
            if (pt->nhits) { /* a corner, or a point a neighbour traced */
                dst[i] = ss_pixel(&pt->color);
                continue;
            }
            c->stats->shadow_pixels++;
            const int lit = ss_light(c, sm, li, x0 + i, y0 + j, NULL);
            if (lit < 0)
                return 0; /* a miss, by rounding */
            if (lit)
                dst[i] = lit_px[j * cs + i];
        }
    return 1;
}

/* A 2x2 square that does not end the frame, split by rt_corners_differ for a contribution
 * (RT_SPLIT_CONTRIB: one object and cell, the same light states and ray tree), k[] its corners
 * (sm: its (0, 0) in the lattice): the centre test. Traces its centre, one of the five points
 * the split traces (as ss_quad traces it), and when rt_centre_smooth finds it of the corners'
 * shape with every contribution within half the threshold of both diagonals' means, the colour
 * varies smoothly there: fills the square's four pixels from its corners (ss_fill), the centre
 * and the points a neighbour traced (the middles of its top and left edges) showing their
 * traced colour as the fill shows a corner, takes the centre's record out of the lattice
 * (which holds nothing inside a square that is not split) and returns 1. Else 0: split (the
 * centre is kept for it). Half the threshold: where an edge cuts one corner off (the fill would
 * smear it over the edges' middles), that corner's step, more than the threshold (the split's
 * own reason), puts the centre more than half of it off that diagonal's mean, on either side of
 * the edge, so such a square always splits. Out of line and cold (for size). */
static __attribute__((cold, noinline)) int ss_centre(ss_ctx *c, rt_sample *sm,
                                                     const rt_sample *const k[4], int x0, int y0)
{
    const int ls = c->lstride, stride = c->stride;
    rt_sample *mid = sm + ls + 1;
    const rt_params *p = c->params;
    const ss_area *a = c->area;
    c->params = c->quad;
    c->area = NULL; /* a split for a contribution: its points are shaded in full */
    ss_need(c, x0 + 1, y0 + 1, mid);
    c->params = p;
    c->area = a;
    c->stats->centre_tests++;
    if (!rt_centre_smooth(k, mid, c->thr8 / 2))
        return 0;
    c->stats->contrib_kept++;
    uint32_t *dst = c->pixels + (long)(y0 - c->py0) * stride + x0;
    const rt_color *const kc[4] = {&k[0]->color, &k[1]->color, &k[2]->color, &k[3]->color};
    ss_fill(dst, stride, 2, 2, 2, 2, kc);
    dst[stride + 1] = ss_pixel(&mid->color);
    if (sm[1].nhits)
        dst[1] = ss_pixel(&sm[1].color);
    if (sm[ls].nhits)
        dst[stride] = ss_pixel(&sm[ls].color);
    mid->nhits = 0;
    return 1;
}

/* The largest side of a square whose split's points take their local parts from its corners
 * (ss_local_ok). A point that takes its local part takes the corners' light states too, so no
 * square inside the split can see a highlight the corners do not: on a top-level square (8) a
 * highlight between its corners on a glossy mirror or glass sphere was lost whole (intro frame
 * 1012: 193 levels off, where the split had found it). At 4 the points are as close to a shaded
 * corner as in the squares adaptive mode leaves unsplit, whose colours are interpolated the
 * same way: frames 787, 1012, 1037 and 1100 then have the worst pixel they had before the local
 * parts (against --mode full --min-contrib 0; over8 the same or one more, PSNR 0.01 to 0.04 dB
 * lower), keeping about 90% of the local points there. */
#define SS_LOCAL_MAX 4

/* Adaptive and probe mode, a square split for its secondary rays (RT_SPLIT_SECONDARY: one
 * primary object and cell), k[] its corners, w x h its size: 1 when the local parts of the
 * points its split adds can be interpolated from the corners' (ss_local), as an unsplit square's
 * colours would be: its sides are at most SS_LOCAL_MAX, the corners agree on every light's state,
 * with no highlight (its peak can lie between them), their primary object has no noise texture,
 * the sides are 0 or powers of two (every square but some that end the frame: the points then
 * lie at 0, half or the whole of each side), and their node-0 contributions lie within the
 * threshold in every channel. Cold: off the usual path. */
static __attribute__((cold, noinline)) int ss_local_ok(const ss_ctx *c, const rt_sample *const k[4],
                                                       int w, int h)
{
    const unsigned id = k[0]->hits[0].object, lights = k[0]->lights;
    if (w > SS_LOCAL_MAX || h > SS_LOCAL_MAX || id == RT_NO_OBJECT ||
        (lights & RT_LIGHTS_HIGHLIGHT) || (w & (w - 1)) || (h & (h - 1)))
        return 0;
    const rt_texture *tx = &c->scene->materials[c->scene->objects[id].material].tex;
    if (tx->active && tx->kind != RT_TEX_CHECKER)
        return 0;
    for (int m = 1; m < 4; m++)
        if (k[m]->lights != lights)
            return 0;
    for (int ch = 0; ch < 3; ch++) {
        int lo = 255, hi = 0;
        for (int m = 0; m < 4; m++) {
            const int v = k[m]->hits[0].contrib[ch];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        if (hi - lo > c->thr8)
            return 0;
    }
    return 1;
}

/* The square with corners (x0, y0) and (x0 + w, y0 + h), at subdivision `level` (sm: its
 * (0, 0) in the lattice). It writes the pixels it owns: [x0, x0 + w) x [y0, y0 + h), plus its
 * right column and bottom row where it ends the frame (`own` bit 0 and bit 1). Every pixel is
 * thus written once, whatever the order. */
static void ss_square(ss_ctx *c, rt_sample *sm, int x0, int y0, int w, int h, int level, int own)
{
    const int ls = c->lstride;
    rt_sample *k2 = sm + h * ls;
    ss_need(c, x0, y0, sm);
    ss_need(c, x0 + w, y0, sm + w);
    ss_need(c, x0, y0 + h, k2);
    ss_need(c, x0 + w, y0 + h, k2 + w);
    if (w > 1 || h > 1) { /* some pixel is not a corner */
        int li = level < RT_GRID_LEVELS ? level : RT_GRID_LEVELS - 1;
        rt_stats *st = c->stats;
        st->squares[li]++;
        const rt_sample *k[4] = {sm, sm + w, k2, k2 + w};
        enum rt_split_reason why = rt_corners_differ(k, c->thr8);
        if (why != RT_SPLIT_NONE) {
            if (why == RT_SPLIT_OBJECT && sm->cell && ss_cells(c, sm, x0, y0, w, h, own)) {
                st->texture_squares++; /* filled by cell instead */
                return;
            }
            if ((RT_COMPILED_EFFECTS & RT_FX_NOISE) && why == RT_SPLIT_CONTRIB &&
                sm->alt_known == 2 && ss_noise(c, sm, k, x0, y0, w, h, own)) {
                st->noise_squares++; /* filled with each pixel's texture instead */
                return;
            }
            if (why == RT_SPLIT_CONTRIB && w == 2 && h == 2 && !own && ss_centre(c, sm, k, x0, y0))
                return; /* smooth at its centre: filled unsplit */
            if (why == RT_SPLIT_LIGHT && !own && ss_shadow(c, k, x0, y0, w, h)) {
                st->shadow_squares++; /* filled with each pixel's own light test instead */
                return;
            }
            st->split[li]++;
            st->split_by[why]++;
            c->split = 1;
            int nx = w >= 2 ? 2 : 1, ny = h >= 2 ? 2 : 1;
            if (RT_COMPILED_PROBE && c->params->mode == RT_MODE_PROBE)
                ss_probe_split(c, x0, y0, w, h, nx, ny, k);
            /* the points it adds: their local parts interpolated where its corners allow */
            const ss_area *outer = c->area;
            const ss_area here = {k, x0, y0, w, h};
            c->area = why == RT_SPLIT_SECONDARY && ss_local_ok(c, k, w, h) ? &here : NULL;
            if (w == 2 && h == 2 && !own) {
                ss_quad(c, sm, x0, y0);
                c->area = outer;
                return;
            }
            int hw = w / 2, hh = h / 2;
            if (nx == 2 && ny == 2) { /* the four halves, row by row */
                rt_sample *sb = sm + hh * ls;
                ss_square(c, sm, x0, y0, hw, hh, level + 1, 0);
                ss_square(c, sm + hw, x0 + hw, y0, w - hw, hh, level + 1, own & 1);
                ss_square(c, sb, x0, y0 + hh, hw, h - hh, level + 1, own & 2);
                ss_square(c, sb + hw, x0 + hw, y0 + hh, w - hw, h - hh, level + 1, own);
            } else if (nx == 2) { /* left and right halves of a square 0 or 1 high */
                ss_square(c, sm, x0, y0, hw, h, level + 1, own & 2);
                ss_square(c, sm + hw, x0 + hw, y0, w - hw, h, level + 1, own);
            } else { /* top and bottom halves of a square 0 or 1 wide */
                rt_sample *sb = sm + hh * ls;
                ss_square(c, sm, x0, y0, w, hh, level + 1, own & 1);
                ss_square(c, sb, x0, y0 + hh, w, h - hh, level + 1, own);
            }
            c->area = outer;
            return;
        }
    }
    int cols = w + (own & 1), rows = h + (own >> 1 & 1);
    uint32_t *dst = c->pixels + (long)(y0 - c->py0) * c->stride + x0;
    const rt_color *const kc[4] = {&sm->color, &sm[w].color, &k2->color, &k2[w].color};
    ss_fill(dst, c->stride, w, h, cols, rows, kc);
    /* Points a neighbour traced for its own decisions show their traced colour. They can only
     * lie on the edges this square shares with squares done before it: its top row and left
     * column (nothing is ever traced inside a square that is not split). */
    for (int i = 1; i < cols; i++)
        if (sm[i].nhits)
            dst[i] = rt_color_pixel(sm[i].color);
    for (int j = 1; j < rows; j++)
        if (sm[j * ls].nhits)
            dst[(long)j * c->stride] = rt_color_pixel(sm[j * ls].color);
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
    if (r0 == r1 || (RT_GRID_BUILD_MAX < RT_GRID_MAX && g > RT_GRID_BUILD_MAX))
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
                .lstride = g + 1,
                .p_quad = *p};
    for (int n = 1; n <= g; n++)
        for (int i = 0; i <= n; i++)
            c.wt[n][i] = r_from_ratio(i, n);
    if (p->mode != RT_MODE_FULL)
        c.p_quad.mode = RT_MODE_FULL;
    if (RT_COMPILED_PROBE && p->mode == RT_MODE_PROBE)
        c.opaque = rt_probe_masks_of(s);

    /* Two rows of corners: row r of the frame's corners lives in row r % 2 of `work`, so bands
     * rendered in order find their top row where the band before left it (RT_BAND_KEEP). */
    rt_sample *top = work, *bot = top + ncols + 1;
    rt_sample *const lat = bot + ncols + 1;
    const int ls = c.lstride;
    c.lat = lat;
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
        /* The lattice holds no traced point but its corners (the square before was not split
         * and its left edge held none): then only the corners move. */
        int clean = 0;
        for (int i = 0; i < ncols; i++) {
            int x0 = ss_corner(i, g, width), w = ss_corner(i + 1, g, width) - x0;
            c.sx = x0;
            rt_sample *row = lat, *hrow = lat + h * ls; /* the lattice's rows 0 and h */
            int edge = 0;                               /* traced points inside the left edge */
            if (clean && w == prev_w) {
                lat[0] = lat[w];
                hrow[0] = hrow[w];
            } else {
                for (int ly = 0; ly <= h; ly++, row += ls) {
                    /* The left edge is the square before's right edge: keep what it traced
                     * (its corners too: they are top[i] and bot[i], copied there before). */
                    if (prev_w >= 0 && row[prev_w].nhits) {
                        row[0] = row[prev_w];
                        edge |= ly != 0 && ly != h;
                    } else {
                        row[0].nhits = 0;
                    }
                    rt_sample *q = row + 1, *e = row + w; /* columns 1..w, two at a time */
                    for (; q < e; q += 2) {
                        q[0].nhits = 0;
                        q[1].nhits = 0;
                    }
                    if (q == e)
                        q->nhits = 0;
                }
            }
            if (prev_w < 0) {
                lat[0] = top[i];
                hrow[0] = bot[i];
            }
            lat[w] = top[i + 1];
            hrow[w] = bot[i + 1];
            c.split = 0;
            c.quad = w == g && h == g ? &c.p_quad : p;
            ss_square(&c, lat, x0, y0, w, h, 0, (i == ncols - 1) | (r == nrows - 1) << 1);
            clean = !c.split && !edge;
            prev_w = w;
        }
        rt_sample *t = top;
        top = bot;
        bot = t;
    }
}

FX_BOARD_THUMB
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
