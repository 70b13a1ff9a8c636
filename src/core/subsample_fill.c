/* subsample_fill.c: the integer bilinear fills of adaptive subsampling (ss_fill, rt_interpolate). */
#include "subsample.h"

/* The fill works on integer channels: a colour in [0, 1] as its Q16.16 value, 0..65536
 * (r_unit_to_q16), and weights i / n as Q16.16 integers rounded to nearest. Its arithmetic is
 * the fixed-point build's r_lerp, r_mul and r_to_byte step for step (no intermediate value can
 * saturate), so fixed frames are what they were with those calls, at a fraction of the cost;
 * the float build interpolates the same way from its rounded corners. */

/* ss_wq[n (n - 1) / 2 + i] = i / n as a Q16.16 integer rounded to nearest, (i 65536 + n / 2) / n
 * (r_from_ratio's fixed-point value), for 0 <= i < n <= RT_GRID_MAX (below 2^16: 16 bits each),
 * row n after row n - 1 (ss_wrow): a constant table, no division. */
#if RT_GRID_MAX != 16
#error "ss_wq is written out for RT_GRID_MAX 16"
#endif
/* clang-format off */
static const uint16_t ss_wq[RT_GRID_MAX * (RT_GRID_MAX + 1) / 2] = {
    /* n =  1 */     0,
    /* n =  2 */     0, 32768,
    /* n =  3 */     0, 21845, 43691,
    /* n =  4 */     0, 16384, 32768, 49152,
    /* n =  5 */     0, 13107, 26214, 39322, 52429,
    /* n =  6 */     0, 10923, 21845, 32768, 43691, 54613,
    /* n =  7 */     0,  9362, 18725, 28087, 37449, 46811, 56174,
    /* n =  8 */     0,  8192, 16384, 24576, 32768, 40960, 49152, 57344,
    /* n =  9 */     0,  7282, 14564, 21845, 29127, 36409, 43691, 50972,
                 58254,
    /* n = 10 */     0,  6554, 13107, 19661, 26214, 32768, 39322, 45875,
                 52429, 58982,
    /* n = 11 */     0,  5958, 11916, 17873, 23831, 29789, 35747, 41705,
                 47663, 53620, 59578,
    /* n = 12 */     0,  5461, 10923, 16384, 21845, 27307, 32768, 38229,
                 43691, 49152, 54613, 60075,
    /* n = 13 */     0,  5041, 10082, 15124, 20165, 25206, 30247, 35289,
                 40330, 45371, 50412, 55454, 60495,
    /* n = 14 */     0,  4681,  9362, 14043, 18725, 23406, 28087, 32768,
                 37449, 42130, 46811, 51493, 56174, 60855,
    /* n = 15 */     0,  4369,  8738, 13107, 17476, 21845, 26214, 30583,
                 34953, 39322, 43691, 48060, 52429, 56798, 61167,
    /* n = 16 */     0,  4096,  8192, 12288, 16384, 20480, 24576, 28672,
                 32768, 36864, 40960, 45056, 49152, 53248, 57344, 61440,
};
/* clang-format on */

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

uint32_t ss_pixel(const rt_color *c) { return ss_pixel_in(c); }

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
static inline __attribute__((always_inline)) void ss_row(rt_px *dst, int n, int32_t v0, int32_t v1,
                                                         int32_t v2, int32_t s0, int32_t s1,
                                                         int32_t s2)
{
    rt_px_set(dst, ss_pack(v0, v1, v2));
    for (int i = 1; i < n; i++) {
        v0 += s0;
        v1 += s1;
        v2 += s2;
        rt_px_set(RT_PX(dst, i), ss_pack(v0, v1, v2));
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
void ss_fill(rt_px *dst, int stride, int w, int h, int cols, int rows, const rt_color *const k[4])
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
        rt_px_set(dst, p[0]);
        rt_px_set(RT_PX(dst, 1), p[1]);
        rt_px_set(RT_PX(dst, stride), p[2]);
        rt_px_set(RT_PX(dst, stride + 1), p[3]);
        return;
    }
    if (q[0] == q[3] && q[0] == q[6] && q[0] == q[9] && q[1] == q[4] && q[1] == q[7] &&
        q[1] == q[10] && q[2] == q[5] && q[2] == q[8] && q[2] == q[11]) {
        /* One colour (dark or empty parts of a frame): every l, r the rows below compute is
         * that colour and every step 0, so each of the pixels (columns 0..cols-1) gets it. */
        uint32_t px = ss_pack(SS_V(q[0]), SS_V(q[1]), SS_V(q[2]));
        for (int j = 0; j < rows; j++, dst = RT_PX(dst, stride))
            for (int i = 0; i < cols; i++)
                rt_px_set(RT_PX(dst, i), px);
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
        for (int j = 0; j < rows; j++, dst = RT_PX(dst, stride)) {
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
                rt_px_set(RT_PX(dst, w), ss_pack(SS_V(r0), SS_V(r1), SS_V(r2)));
        }
        return;
    }
#endif
    const uint16_t *wy = ss_wrow(h); /* read at 0 < j < h */
    int32_t sx = ss_wrow(w)[1];      /* w <= 1: ss_wq[1], 0 (unused) */
    int inner = cols < w ? cols : w; /* columns 0..inner-1 come from the left edge and steps */
    int right = cols > w && w > 0;   /* column w: the right edge's colour */
    for (int j = 0; j < rows; j++, dst = RT_PX(dst, stride)) {
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
            rt_px_set(dst, ss_pack(v0, v1, v2));
        if (right)
            rt_px_set(RT_PX(dst, w), ss_pack(SS_V(e[3]), SS_V(e[4]), SS_V(e[5])));
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
    ss_fill((rt_px *)dst, stride, w, h, cols, rows, k);
}
