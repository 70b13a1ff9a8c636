/* test_subsample.c: adaptive subsampling: split criteria, interpolation, edges followed down to single pixels. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "knobs.h"
#include "rt_local.h"
#include "subsample.h"

/* The default threshold of the programs (knobs.h). */
static const knobs ts_knobs = KNOBS_DEFAULTS;
#define TS_THRESHOLD (knobs_params(&ts_knobs, 0).threshold)

#if REAL_FIXED
static real from_d(double x) { return (real)llround(x * 65536.0); }
#else
static real from_d(double x) { return (real)x; }
#endif

static vec3 vd(double x, double y, double z) { return v3(from_d(x), from_d(y), from_d(z)); }

/* ---- split criteria on constructed corner records ------------------------------------------ */

/* A sample on object 1 with a reflection of object 2, both lights lit. */
static rt_sample base_sample(void)
{
    rt_sample s;
    memset(&s, 0, sizeof s);
    s.color = vd(0.5, 0.5, 0.5);
    s.nhits = 2;
    s.lights = 1 | 1 << 2; /* lights 0 and 1 lit */
    s.hits[0] = (rt_hit_rec){.object = 1, .level = 0, .contrib = {100, 120, 140}};
    s.hits[1] = (rt_hit_rec){.object = 2, .level = 1, .contrib = {30, 30, 30}};
    return s;
}

static enum rt_split_reason compare_with(const rt_sample *odd, int which, int thr8)
{
    rt_sample a = base_sample();
    const rt_sample *k[4] = {&a, &a, &a, &a};
    k[which] = odd;
    return rt_corners_differ(k, thr8);
}

static void test_criteria(void **state)
{
    (void)state;
    rt_sample s = base_sample();
    /* agreeing corners do not split, even with colours that differ (they are interpolated) */
    assert_int_equal(compare_with(&s, 2, 16), RT_SPLIT_NONE);
    s.color = vd(0.9, 0.1, 0.3);
    assert_int_equal(compare_with(&s, 2, 16), RT_SPLIT_NONE);

    for (int which = 0; which < 4; which++) {
        /* 1. primary object */
        s = base_sample();
        s.hits[0].object = 3;
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_OBJECT);
        s = base_sample();
        s.hits[0].object = RT_NO_OBJECT;
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_OBJECT);
        /* ... or another cell of its checkerboard */
        s = base_sample();
        s.cell = 5;
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_OBJECT);
        /* 2. a highlight at some corner, always; lit and unlit corners where their
         * contributions differ by more than half the threshold (a shadow edge that shows) */
        s = base_sample();
        s.lights = 2 | 1 << 2; /* a highlight of light 0 */
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_LIGHT);
        s = base_sample();
        s.lights = 1; /* light 1 unlit */
        /* same colours: the totals are compared, so a shadow of one light that another
         * light's opposite change hides is interpolated across (the accepted limit) */
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_NONE);
        s.hits[0].contrib[2] = 140 - 8;
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_NONE);
        s.hits[0].contrib[2] = 140 - 9; /* a faint shadow is interpolated, a darker one splits */
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_LIGHT);
        s.hits[0].contrib[2] = 140;
        s.hits[1].contrib[0] = 30 + 9; /* at any node */
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_LIGHT);

        /* 3. an object at a secondary level, or the shape of the ray tree, where a node that
         * differs contributes more than half the threshold (node 1: 30) */
        s = base_sample();
        s.hits[1].object = 4;
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_SECONDARY);
        s = base_sample();
        s.hits[1].level = 2;
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_SECONDARY);
        s = base_sample();
        s.nhits = 3;
        s.hits[2] = (rt_hit_rec){.object = 5, .level = 1, .contrib = {0, 9, 0}};
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_SECONDARY);
        s.hits[2].contrib[1] = 8; /* a faint node more: interpolated */
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_NONE);
        s.hits[0].contrib[0] = 100 + 9; /* and then the others within half the threshold */
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_SECONDARY);
        {
            /* a faint reflection seen at some corners (node 1: 8 at most on either side) */
            rt_sample f = base_sample(), g = base_sample();
            f.hits[1].contrib[0] = f.hits[1].contrib[1] = f.hits[1].contrib[2] = 8;
            g.hits[1] = (rt_hit_rec){.object = RT_NO_OBJECT, .level = 1, .contrib = {2, 3, 4}};
            const rt_sample *kf[4] = {&f, &f, &f, &f};
            kf[which] = &g;
            assert_int_equal(rt_corners_differ(kf, 16), RT_SPLIT_NONE);
            g.hits[1].contrib[2] = 9;
            assert_int_equal(rt_corners_differ(kf, 16), RT_SPLIT_SECONDARY);
        }
        /* nodes beyond the stored ones still count through nhits */
        rt_sample big = base_sample(), big2;
        big.nhits = RT_SAMPLE_MAX_HITS + 3;
        for (int j = 2; j < RT_SAMPLE_MAX_HITS; j++)
            big.hits[j] = (rt_hit_rec){.object = 2, .level = 1};
        big2 = big;
        big2.nhits = RT_SAMPLE_MAX_HITS + 4;
        const rt_sample *kb[4] = {&big, &big, &big, &big};
        assert_int_equal(rt_corners_differ(kb, 16), RT_SPLIT_NONE);
        kb[which] = &big2;
        assert_int_equal(rt_corners_differ(kb, 16), RT_SPLIT_SECONDARY);
        /* 4. a contribution beyond the threshold, at the primary or a secondary level */
        s = base_sample();
        s.hits[0].contrib[1] = 120 + 16;
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_NONE);
        s.hits[0].contrib[1] = 120 + 17;
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_CONTRIB);
        s = base_sample();
        s.hits[1].contrib[2] = 30 - 17;
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_CONTRIB);
        assert_int_equal(compare_with(&s, which, 17), RT_SPLIT_NONE);
        assert_int_equal(compare_with(&s, which, 255), RT_SPLIT_NONE);
        /* the order of the checks: object before highlight before secondary before shadow
         * before contribution */
        s = base_sample();
        s.lights = 1 << 2; /* light 0 unlit */
        s.hits[0].contrib[0] = 0;
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_LIGHT);
        s.hits[1].object = 4;
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_SECONDARY);
        s.lights = 2 | 1 << 2; /* a highlight of light 0 */
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_LIGHT);
        s.hits[0].object = 7;
        assert_int_equal(compare_with(&s, which, 16), RT_SPLIT_OBJECT);
    }
}

/* The centre test (rt_centre_smooth) on constructed records: corners whose contributions
 * differ by more than the threshold (a split for contributions) and a centre on, near and off
 * the means of both diagonals' ends, or of another shape. */
static void test_centre_smooth(void **state)
{
    (void)state;
    const int thr8 = 16, tol = thr8 / 2;
    rt_sample c[4], m = base_sample();
    const rt_sample *k[4] = {&c[0], &c[1], &c[2], &c[3]};
    for (int i = 0; i < 4; i++) {
        c[i] = base_sample();
        c[i].hits[0].contrib[0] = (uint8_t)(100 + 20 * i); /* 100, 120, 140, 160: mean 130 */
        c[i].hits[1].contrib[2] = (uint8_t)(30 + 4 * i);   /* 30, 34, 38, 42: mean 36 */
    }
    assert_int_equal(rt_corners_differ(k, thr8), RT_SPLIT_CONTRIB);
    m.hits[0].contrib[0] = 130;
    m.hits[1].contrib[2] = 36;
    assert_true(rt_centre_smooth(k, &m, tol)); /* on the mean: smooth, not split */
    m.hits[0].contrib[0] = 130 + 8;
    assert_true(rt_centre_smooth(k, &m, tol)); /* at the tolerance */
    m.hits[0].contrib[0] = 130 - 8;
    assert_true(rt_centre_smooth(k, &m, tol));
    /* off the mean by more than the tolerance, in any node and channel: split */
    m.hits[0].contrib[0] = 130 + 9;
    assert_false(rt_centre_smooth(k, &m, tol));
    m.hits[0].contrib[0] = 130 - 9;
    assert_false(rt_centre_smooth(k, &m, tol));
    m.hits[0].contrib[0] = 130;
    m.hits[1].contrib[2] = 36 + 9; /* the reflection's blue */
    assert_false(rt_centre_smooth(k, &m, tol));
    m.hits[1].contrib[2] = 36;
    m.hits[0].contrib[1] = 120 + 9; /* a channel the corners agree on */
    assert_false(rt_centre_smooth(k, &m, tol));
    m.hits[0].contrib[1] = 120;
    assert_true(rt_centre_smooth(k, &m, tol));
    /* a centre of another shape splits, however close its contributions */
    rt_sample o = m;
    o.hits[1].object = 3; /* something else in the mirror */
    assert_false(rt_centre_smooth(k, &o, tol));
    o = m;
    o.lights = 1 << 2; /* in light 0's shadow */
    assert_false(rt_centre_smooth(k, &o, tol));
    o = m;
    o.cell = 2; /* another checker cell */
    assert_false(rt_centre_smooth(k, &o, tol));
    o = m;
    o.nhits = 3; /* a longer ray tree */
    o.hits[2] = (rt_hit_rec){.object = 4, .level = 2, .contrib = {0, 0, 0}};
    assert_false(rt_centre_smooth(k, &o, tol));
    /* tolerance 0: only the mean itself */
    assert_true(rt_centre_smooth(k, &m, 0));
    m.hits[0].contrib[2] = 141;
    assert_false(rt_centre_smooth(k, &m, 0));
    /* near the bilinear mean but off a diagonal's: an edge that cuts one corner off (a step
     * just over the threshold: a centre on either side is within a quarter of it of the
     * corners' mean, and half of it off a diagonal's), and a twist */
    for (int i = 0; i < 4; i++)
        c[i] = base_sample();
    c[3].hits[0].contrib[0] = 100 + 17; /* the others 100 */
    assert_int_equal(rt_corners_differ(k, thr8), RT_SPLIT_CONTRIB);
    o = c[0]; /* the centre on the flat side: 4.25 from the bilinear mean, 104.25 */
    assert_false(rt_centre_smooth(k, &o, tol));
    assert_true(rt_centre_smooth(k, &o, 9)); /* half the step: 8.5 from a diagonal's mean */
    o.hits[0].contrib[0] = 117;              /* on the step's side */
    assert_false(rt_centre_smooth(k, &o, tol));
    c[3].hits[0].contrib[0] = 100;
    c[1].hits[0].contrib[0] = c[2].hits[0].contrib[0] = 130;
    assert_int_equal(rt_corners_differ(k, thr8), RT_SPLIT_CONTRIB);
    o.hits[0].contrib[0] = 115; /* the bilinear mean itself, 15 from either diagonal's */
    assert_false(rt_centre_smooth(k, &o, tol));
    assert_true(rt_centre_smooth(k, &o, 15));
}

/* ---- interpolation ------------------------------------------------------------------------- */

/* A linear gradient over a square comes out exactly, within one 8-bit level. */
static void test_interpolate_gradient(void **state)
{
    (void)state;
    static uint32_t px[(RT_GRID_MAX + 1) * (RT_GRID_MAX + 1)];
    const int sizes[][2] = {{1, 1},  {2, 2},  {4, 4}, {8, 8}, {16, 16}, {7, 3},
                            {5, 16}, {16, 1}, {0, 4}, {3, 0}, {13, 11}};
    int worst = 0;
    for (size_t n = 0; n < sizeof sizes / sizeof sizes[0]; n++) {
        int w = sizes[n][0], h = sizes[n][1];
        /* channel value a + bx*x/w + by*y/h, one gradient per channel */
        const double a[3] = {0.1, 0.9, 0.3}, bx[3] = {0.8, -0.7, 0.0}, by[3] = {0.05, 0.1, 0.6};
        rt_color c[4];
        for (int k = 0; k < 4; k++) {
            double v[3];
            for (int ch = 0; ch < 3; ch++)
                v[ch] = a[ch] + bx[ch] * (k & 1) + by[ch] * (k >> 1);
            c[k] = vd(v[0], v[1], v[2]);
        }
        for (size_t i = 0; i < sizeof px / sizeof px[0]; i++)
            px[i] = 0xDEADBEEF;
        rt_interpolate(px, RT_GRID_MAX + 1, w, h, w + 1, h + 1, c[0], c[1], c[2], c[3]);
        for (int y = 0; y <= h; y++) {
            for (int x = 0; x <= w; x++) {
                uint32_t p = px[y * (RT_GRID_MAX + 1) + x];
                assert_int_equal(p >> 24, 0); /* written */
                for (int ch = 0; ch < 3; ch++) {
                    double fx = w ? (double)x / w : 0, fy = h ? (double)y / h : 0;
                    double want = (a[ch] + bx[ch] * fx + by[ch] * fy) * 255.0;
                    int got = (int)(p >> (16 - 8 * ch) & 0xFF);
                    if (fabs(got - want) > worst)
                        worst = (int)ceil(fabs(got - want));
                    assert_true(fabs(got - want) <= 1.0);
                }
            }
        }
    }
    /* outside the region asked for, nothing is touched */
    for (size_t i = 0; i < sizeof px / sizeof px[0]; i++)
        px[i] = 0xDEADBEEF;
    rt_interpolate(px, RT_GRID_MAX + 1, 8, 8, 8, 8, vd(0, 0, 0), vd(1, 1, 1), vd(0, 0, 0),
                   vd(1, 1, 1));
    assert_int_equal(px[8], 0xDEADBEEF);                     /* column 8 of row 0 */
    assert_int_equal(px[8 * (RT_GRID_MAX + 1)], 0xDEADBEEF); /* row 8 */
    assert_int_equal(px[7] & 0xFF, 223);                     /* 7/8 of the way: 223.1 */
    print_message("interpolation: worst error %d level(s)\n", worst);
}

/* The fill as it was written before it kept its channels as 255 v + 2^15 (ss_pack): per
 * channel r_to_byte of l + i s, with l, r and s from the rounded products; rt_interpolate must
 * give exactly these bytes. */
static int32_t ref_mul(int32_t d, int32_t t)
{
    uint32_t p = (uint32_t)(d < 0 ? -d : d) * (uint32_t)t;
    int32_t q = (int32_t)((p + 0x8000u) >> 16);
    return d < 0 ? -q : q;
}

static uint32_t ref_byte(int32_t v)
{
    return v <= 0 ? 0 : v >= 65536 ? 255 : ((uint32_t)v * 255u + 0x8000u) >> 16;
}

static int32_t ref_w(int i, int n) { return n > 0 ? (i * 65536 + n / 2) / n : 0; }

static void ref_fill(uint32_t *dst, int stride, int w, int h, int cols, int rows,
                     const int32_t c[4][3])
{
    int inner = cols < w ? cols : w;
    for (int j = 0; j < rows; j++) {
        int32_t l[3], r[3];
        for (int ch = 0; ch < 3; ch++) {
            if (j == 0) {
                l[ch] = c[0][ch];
                r[ch] = c[1][ch];
            } else if (j == h) {
                l[ch] = c[2][ch];
                r[ch] = c[3][ch];
            } else {
                l[ch] = c[0][ch] + ref_mul(c[2][ch] - c[0][ch], ref_w(j, h));
                r[ch] = c[1][ch] + ref_mul(c[3][ch] - c[1][ch], ref_w(j, h));
            }
        }
        uint32_t *row = dst + j * stride;
        row[0] = ref_byte(l[0]) << 16 | ref_byte(l[1]) << 8 | ref_byte(l[2]);
        int32_t v[3] = {l[0], l[1], l[2]}, s[3];
        for (int ch = 0; ch < 3; ch++)
            s[ch] = ref_mul(r[ch] - l[ch], ref_w(1, w));
        for (int i = 1; i < inner; i++) {
            for (int ch = 0; ch < 3; ch++)
                v[ch] += s[ch];
            row[i] = ref_byte(v[0]) << 16 | ref_byte(v[1]) << 8 | ref_byte(v[2]);
        }
        if (cols > w && w > 0)
            row[w] = ref_byte(r[0]) << 16 | ref_byte(r[1]) << 8 | ref_byte(r[2]);
    }
}

static uint32_t ts_rand_state = 12345;
static uint32_t ts_rand(void)
{
    ts_rand_state = ts_rand_state * 1664525u + 1013904223u;
    return ts_rand_state >> 8;
}

/* A channel value in [0, 1]: uniform, or one of the ends and their neighbours, where the
 * rounding and clamping are tightest. */
static int32_t rand_q16(void)
{
    static const int32_t ends[] = {0,     1,     2,     127,   128,   129,  32767,
                                   32768, 32896, 65407, 65408, 65535, 65536};
    uint32_t u = ts_rand();
    if (u & 1)
        return ends[(u >> 1) % (sizeof ends / sizeof ends[0])];
    return (int32_t)((u >> 1) % 65537);
}

/* Every square size and region (cols w or w + 1, rows h or h + 1), random corner colours (and
 * some with one colour, equal rows or equal columns): the bytes are the reference formula's,
 * and nothing outside the region is written. */
static void test_interpolate_exact(void **state)
{
    (void)state;
    enum { S = RT_GRID_MAX + 2 };
    static uint32_t got[S * S], want[S * S];
    long pixels = 0;
    for (int w = 0; w <= RT_GRID_MAX; w++)
        for (int h = 0; h <= RT_GRID_MAX; h++)
            for (int region = 0; region < 4; region++) {
                int cols = w + (region & 1), rows = h + (region >> 1);
                if (cols < 1 || rows < 1)
                    continue;
                for (int trial = 0; trial < 48; trial++) {
                    int32_t c[4][3];
                    rt_color k[4];
                    for (int n = 0; n < 4; n++) {
                        for (int ch = 0; ch < 3; ch++)
                            c[n][ch] = rand_q16();
#if REAL_FIXED
                        k[n] = v3(c[n][0], c[n][1], c[n][2]);
#else
                        /* the float build's channel near it, and the Q16.16 value it
                         * rounds to */
                        real f[3];
                        for (int ch = 0; ch < 3; ch++) {
                            f[ch] = (real)c[n][ch] / 65536.0f +
                                (real)((int)(ts_rand() % 64) - 32) * 1e-7f;
                            f[ch] = f[ch] < 0 ? 0 : f[ch] > 1 ? 1 : f[ch];
                            c[n][ch] = r_unit_to_q16(f[ch]);
                        }
                        k[n] = v3(f[0], f[1], f[2]);
#endif
                    }
                    /* inputs: one colour (the fill's shortcut), equal rows, equal columns */
                    static const int same[3][4] = {{0, 0, 0, 0}, {0, 0, 2, 2}, {0, 1, 0, 1}};
                    if (trial < 3)
                        for (int n = 1; n < 4; n++) {
                            k[n] = k[same[trial][n]];
                            memcpy(c[n], c[same[trial][n]], sizeof c[n]);
                        }
                    for (int i = 0; i < S * S; i++)
                        got[i] = want[i] = 0xDEADBEEF;
                    ref_fill(want, S, w, h, cols, rows, c);
                    rt_interpolate(got, S, w, h, cols, rows, k[0], k[1], k[2], k[3]);
                    if (memcmp(got, want, sizeof got) != 0) {
                        for (int i = 0; i < S * S; i++)
                            if (got[i] != want[i])
                                fail_msg("%dx%d square, %dx%d pixels: pixel (%d, %d) is %06x, "
                                         "the reference %06x",
                                         w, h, cols, rows, i % S, i / S, got[i], want[i]);
                    }
                    pixels += (long)cols * rows;
                }
            }
    print_message("interpolation: %ld pixels equal to the reference formula's\n", pixels);
}

/* ---- rendered cases ------------------------------------------------------------------------ */

#define W 96
#define H 72
/* The error allowed on a reflection's edge where the local parts were interpolated (ss_local):
 * measured 1 level in both builds. */
#define TS_LOCAL_ERR 1

static rt_sample full[H][W];
static uint32_t fullpx[H * W], adpx[H * W];
static uint8_t traced[H * W];
static rt_sample work[2 * (W / 2 + 2) + (RT_GRID_MAX + 1) * (RT_GRID_MAX + 1)];

static void scene_base(rt_scene *s)
{
    memset(s, 0, sizeof *s);
    s->background = vd(0.1, 0.15, 0.3);
    s->ambient = vd(0.2, 0.2, 0.2);
    s->depth = 4;
    s->lights[0] = (rt_light){vd(4, 10, 6), vd(0.9, 0.9, 0.9)};
    s->nlights = 1;
}

static int add_material(rt_scene *s, rt_material m)
{
    if (m.ior == 0)
        m.ior = from_d(1.0);
    s->materials[s->nmaterials] = m;
    return s->nmaterials++;
}

static void add_sphere(rt_scene *s, int mat, double x, double y, double z, double r)
{
    rt_object *o = &s->objects[s->nobjects++];
    *o = (rt_object){.kind = RT_SPHERE, .material = (uint8_t)mat};
    o->center = vd(x, y, z);
    o->radius = from_d(r);
}

static void add_floor(rt_scene *s, int mat)
{
    rt_object *o = &s->objects[s->nobjects++];
    *o = (rt_object){.kind = RT_PLANE, .material = (uint8_t)mat};
    o->axis = vd(0, 1, 0);
}

/* The shadow of a sphere on a matte floor (no highlight, no reflection). */
static void shadow_scene(rt_scene *s)
{
    scene_base(s);
    int mf = add_material(s, (rt_material){.diffuse = vd(0.7, 0.7, 0.6), .ambient = from_d(1)});
    int ms = add_material(s, (rt_material){.diffuse = vd(0.2, 0.6, 0.2), .ambient = from_d(1)});
    add_floor(s, mf);
    add_sphere(s, ms, -0.5, 2.0, 0, 1.0);
    s->lights[0].pos = vd(-3, 9, -2);
    s->camera = (rt_camera){vd(0, 7, 5), vd(0.5, 0, 0.5), vd(0, 1, 0), from_d(45)};
}

/* A yellow sphere above a mirror floor (light and camera set by the caller). */
static void mirror_scene(rt_scene *s)
{
    scene_base(s);
    int mf = add_material(
        s,
        (rt_material){.diffuse = vd(0.3, 0.3, 0.3), .ambient = from_d(1), .reflect = from_d(0.7)});
    int ms = add_material(s, (rt_material){.diffuse = vd(0.9, 0.8, 0.1), .ambient = from_d(1)});
    add_floor(s, mf);
    add_sphere(s, ms, 0, 3.5, -3, 1.0);
}

/* A matte sphere of radius r at (x, y, -10), seen head-on from the origin. */
static void one_sphere_scene(rt_scene *s, double x, double y, double r)
{
    scene_base(s);
    int m = add_material(s, (rt_material){.diffuse = vd(0.8, 0.3, 0.2), .ambient = from_d(1)});
    add_sphere(s, m, x, y, -10, r);
    s->camera = (rt_camera){vd(0, 0, 0), vd(0, 0, -10), vd(0, 1, 0), from_d(40)};
}

/* Are two pixels within one level in every channel? */
static int px_near(uint32_t a, uint32_t b)
{
    for (int sh = 0; sh < 24; sh += 8) {
        const int d = (int)(a >> sh & 255) - (int)(b >> sh & 255);
        if (d > 1 || d < -1)
            return 0;
    }
    return 1;
}

/* The largest difference of two pixels in a channel, in levels. */
static int px_diff(uint32_t a, uint32_t b)
{
    int m = 0;
    for (int sh = 0; sh < 24; sh += 8) {
        const int d = abs((int)(a >> sh & 255) - (int)(b >> sh & 255));
        m = d > m ? d : m;
    }
    return m;
}

/* Renders the scene in full (every sample kept) and adaptive mode. For every pair of
 * neighbouring pixels whose full samples differ for `reason` (as the adaptive render's own
 * threshold sees them: a shadow or reflection too faint to show is no edge), checks that the
 * adaptive render traced both pixels (the squares along the edge were split down to 1x1) and shows
 * the full render's colours there (within a level where check_edge says; within TS_LOCAL_ERR
 * levels at the points that took their local parts from their square's corners, marked
 * RT_TRACED_LOCAL in `traced`). Returns the number of such pairs. */
static int check_edge(rt_scene *s, enum rt_split_reason reason, int min_percent, const char *name)
{
    rt_scene_prepare(s);
    /* Shadow pixels (test_shadow_pixels) fill 2x2 and 4x4 squares on a shadow's edge instead of
     * splitting them; with the view's eye not the prepared one they do not: the split path. */
    if (reason == RT_SPLIT_LIGHT)
        s->cull.eye_at.x = r_add(s->cull.eye_at.x, from_d(1));
    rt_view v;
    rt_view_init(&v, &s->camera, W, H);
    const rt_params pf = {.depth = s->depth, .mode = RT_MODE_FULL};
    const rt_params pa = {
        .depth = s->depth, .mode = RT_MODE_ADAPTIVE, .grid = 8, .threshold = TS_THRESHOLD};
    rt_stats st = {0}, sa = {0};
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            rt_trace_pixel(s, &v, &pf, x, y, &st, &full[y][x]);
    rt_render(s, &v, &pf, fullpx, W, &st, NULL, NULL);
    assert_true(rt_render_work_size(&pa, W) <= sizeof work);
    rt_render(s, &v, &pa, adpx, W, &sa, work, traced);

    int pairs = 0, both = 0, exact = 0, boundary = 0, other_pairs = 0, local_err = 0;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            for (int d = 0; d < 2; d++) {
                int x2 = x + (d == 0), y2 = y + (d == 1);
                if (x2 >= W || y2 >= H)
                    continue;
                const rt_sample *k[4] = {&full[y][x], &full[y][x], &full[y2][x2], &full[y2][x2]};
                enum rt_split_reason why = rt_corners_differ(k, r_to_byte(pa.threshold));
                if (why == RT_SPLIT_NONE)
                    continue;
                if (why != reason) {
                    other_pairs++;
                    continue;
                }
                pairs++;
                int p = y * W + x, q = y2 * W + x2;
                if (traced[p] && traced[q]) {
                    both++;
                    /* exact, but on a grid row's boundary (y a multiple of the grid), where
                     * within a level (below) */
                    const int dp = px_diff(adpx[p], fullpx[p]), dq = px_diff(adpx[q], fullpx[q]);
                    local_err = dp > local_err ? dp : local_err;
                    local_err = dq > local_err ? dq : local_err;
                    const int ep = !dp || ((traced[p] & RT_TRACED_LOCAL) && dp <= TS_LOCAL_ERR) ||
                        (y % pa.grid == 0 && px_near(adpx[p], fullpx[p]));
                    const int eq = !dq || ((traced[q] & RT_TRACED_LOCAL) && dq <= TS_LOCAL_ERR) ||
                        (y2 % pa.grid == 0 && px_near(adpx[q], fullpx[q]));
                    exact += ep && eq;
                    boundary += (ep && adpx[p] != fullpx[p]) || (eq && adpx[q] != fullpx[q]);
                }
            }
        }
    }
    print_message(
        "%s: %d neighbour pairs differ by that criterion (%d by others), %d traced "
        "on both sides, %d of those exact (%d within a level: on a grid row's boundary, or "
        "with interpolated local parts); "
        "%lu of %d pixels traced (%lu with interpolated local parts), %lu 2x2 squares "
        "split; largest error on the edge %d levels\n",
        name, pairs, other_pairs, both, exact, boundary, (unsigned long)sa.rays_primary, W * H,
        (unsigned long)sa.local_points, (unsigned long)sa.split[2], local_err);
    assert_true(pairs >= 40); /* the scene does show that kind of edge */
    /* Every pixel on either side of it was traced, except where a curved outline bulges
     * between two corners that agree: what no corner sees, no criterion can split for. */
    assert_true(both * 100 >= pairs * min_percent);
    /* and a traced pixel shows its traced colour: where the square that owns it was split. A
     * point the row of squares above traced on their shared edge (a grid row's boundary) is not
     * kept (docs/tracer.md): where the square below is not split (its corners agree, or only
     * its contributions differ and its centre lies on their mean: the centre test), it shows
     * the fill's colour, within a level of the traced one (`traced` marks it all the same).
     * Everywhere else, exact. */
    assert_int_equal(exact, both);
    assert_true(sa.split[2] > 0);                     /* squares were split down to single pixels */
    assert_true(sa.rays_primary < (uint32_t)(W * H)); /* and not everything was traced */
    return pairs;
}

/* The outline of a sphere against the background. */
static void test_object_edge(void **state)
{
    (void)state;
    static rt_scene s;
    one_sphere_scene(&s, 0.3, 0.2, 2.5);
    check_edge(&s, RT_SPLIT_OBJECT, 100, "object edge");
}

/* The shadow of a sphere on a matte floor (no highlight, no reflection), followed by splitting
 * (shadow pixels off: check_edge). */
static void test_shadow_edge(void **state)
{
    (void)state;
    static rt_scene s;
    shadow_scene(&s);
    check_edge(&s, RT_SPLIT_LIGHT, 100, "shadow edge");
}

/* A sphere seen only in a mirror floor: the camera looks down and the sphere is above its view,
 * so every difference is at the secondary level. */
static void test_reflected_outline(void **state)
{
    (void)state;
    static rt_scene s;
    mirror_scene(&s);
    s.lights[0].pos = vd(0, 20, 20); /* the sphere's shadow falls behind the view */
    s.camera = (rt_camera){vd(0, 3, 6), vd(0, 0, 0), vd(0, 1, 0), from_d(40)};
    check_edge(&s, RT_SPLIT_SECONDARY, 90, "reflected outline");
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            assert_int_equal(full[y][x].hits[0].object, 0); /* the sphere is not seen directly */
}

/* Local parts are interpolated only on a surface without a noise texture (ss_local_ok): the
 * reflected-outline scene takes them on its plain mirror floor; the same floor with a noise
 * texture gets none, though its squares still split for their secondary rays. The texture
 * varies slowly (scale 0.2), so the corners' contributions stay within the threshold and only
 * ss_local_ok's texture test keeps the local parts out. */
static void test_local_not_on_noise(void **state)
{
    (void)state;
    static rt_scene s;
    for (int noisy = 0; noisy < 2; noisy++) {
        mirror_scene(&s);
        s.lights[0].pos = vd(0, 20, 20);
        s.camera = (rt_camera){vd(0, 3, 6), vd(0, 0, 0), vd(0, 1, 0), from_d(40)};
        if (noisy) /* materials[0]: mirror_scene's floor */
            s.materials[0].tex = (rt_texture){
                .kind = RT_TEX_NOISE, .palette = 0, .octaves = 2, .scale = from_d(0.2)};
        rt_scene_prepare(&s);
        rt_view v;
        rt_view_init(&v, &s.camera, W, H);
        const rt_params pa = {
            .depth = s.depth, .mode = RT_MODE_ADAPTIVE, .grid = 8, .threshold = TS_THRESHOLD};
        rt_stats sa = {0};
        assert_true(rt_render_work_size(&pa, W) <= sizeof work);
        rt_render(&s, &v, &pa, adpx, W, &sa, work, traced);
        print_message("mirror floor%s: %lu splits for secondary rays, %lu points with local "
                      "parts\n",
                      noisy ? " with noise" : "", (unsigned long)sa.split_by[RT_SPLIT_SECONDARY],
                      (unsigned long)sa.local_points);
        /* the traced map marks them RT_TRACED_LOCAL (a point traced twice counts twice) */
        long marked = 0;
        for (int i = 0; i < W * H; i++)
            marked += (traced[i] & RT_TRACED_LOCAL) != 0;
        assert_true(sa.split_by[RT_SPLIT_SECONDARY] > 20);
        assert_true(marked <= (long)sa.local_points && marked * 10 >= (long)sa.local_points * 9);
        if (noisy)
            assert_int_equal(sa.local_points, 0);
        else
            assert_true(sa.local_points > 20);
    }
}

/* rt_trace_pixel_local: a point whose primary hit is on the object and cell given takes the
 * local part given (node 0's contribution, the light states) and traces its secondary rays as a
 * full shade does; any other point (another object, the background, another checker cell) is
 * shaded in full, its record and colour those of rt_trace_pixel. */
static void test_local_part(void **state)
{
    (void)state;
    static rt_scene s;
    mirror_scene(&s);
    /* a two-tone checker on the mirror floor: cells to tell apart */
    s.materials[0].tex =
        (rt_texture){.kind = RT_TEX_CHECKER, .scale = from_d(0.5), .color2 = vd(0.5, 0.2, 0.2)};
    s.lights[0].pos = vd(3, 12, 4);
    s.camera = (rt_camera){vd(0, 2.5, 6), vd(0, 1.5, -3), vd(0, 1, 0), from_d(50)};
    rt_scene_prepare(&s);
    rt_view v;
    rt_view_init(&v, &s.camera, W, H);
    const rt_params p = {.depth = s.depth, .mode = RT_MODE_ADAPTIVE};
    const real g[2] = {from_d(0.25), from_d(0.75)};
    int taken = 0, reflecting = 0, other = 0, other_cell = 0;
    for (int y = 0; y < H; y += 3)
        for (int x = 0; x < W; x += 3) {
            rt_sample f, l[2];
            rt_stats sf = {0};
            rt_trace_pixel(&s, &v, &p, x, y, &sf, &f);
            /* the nodes stored (those past them are not written) */
            const size_t nodes = f.nhits < RT_SAMPLE_MAX_HITS ? f.nhits : RT_SAMPLE_MAX_HITS;
            for (int cell = 0; cell < 2; cell++) {
                /* given for the floor, its cell (the point's own, or another), lights unlike the
                 * point's own */
                const uint8_t given_cell = (uint8_t)(cell ? f.cell % 64 + 1 : f.cell);
                rt_stats sl[2] = {{0}, {0}};
                for (int n = 0; n < 2; n++) {
                    const rt_local loc = {.col = v3(g[n], g[n], g[n]),
                                          .id = 0,
                                          .cell = given_cell,
                                          .lights = (uint8_t)(f.lights ^ 1)};
                    rt_trace_pixel_local(&s, &v, &p, x, y, &loc, &sl[n], &l[n]);
                }
                if (f.hits[0].object != 0 || given_cell != f.cell) {
                    /* shaded in full: the same record and colour */
                    for (int n = 0; n < 2; n++) {
                        assert_int_equal(sl[n].local_points, 0);
                        assert_int_equal(l[n].head, f.head);
                        assert_int_equal(l[n].alt_known, f.alt_known);
                        assert_memory_equal(l[n].hits, f.hits, nodes * sizeof f.hits[0]);
                        assert_memory_equal(&l[n].color, &f.color, sizeof f.color);
                    }
                    other += f.hits[0].object != 0 && !cell;
                    other_cell += f.hits[0].object == 0 && given_cell != f.cell;
                    continue;
                }
                taken++;
                reflecting += f.nhits > 1;
                for (int n = 0; n < 2; n++) {
                    assert_int_equal(sl[n].local_points, 1);
                    assert_int_equal(l[n].lights, f.lights ^ 1);
                    assert_int_equal(l[n].cell, f.cell);
                    assert_int_equal(l[n].nhits, f.nhits);
                    assert_int_equal(l[n].alt_known, 0); /* no other tone */
                    for (int ch = 0; ch < 3; ch++)
                        assert_int_equal(l[n].hits[0].contrib[ch], r_to_byte(g[n]));
                    /* the secondary nodes as the full shade's */
                    if (nodes > 1)
                        assert_memory_equal(&l[n].hits[1], &f.hits[1],
                                            (nodes - 1) * sizeof f.hits[0]);
                    /* no light's term at the primary hit: at most its shadow rays fewer */
                    assert_true(sl[n].rays_shadow <= sf.rays_shadow);
                    assert_int_equal(sl[n].rays_reflect, sf.rays_reflect);
                }
                /* the colour is the local part given plus the secondary rays' */
                const int32_t d = r_unit_to_q16(r_sub(l[1].color.x, l[0].color.x)) -
                    r_unit_to_q16(r_sub(g[1], g[0]));
                assert_true(d >= -1 && d <= 1);
            }
        }
    print_message("local parts: %d points took the one given (%d with a reflection); %d on "
                  "another object, %d in another cell shaded in full\n",
                  taken, reflecting, other, other_cell);
    assert_true(reflecting > 20 && other > 20 && other_cell > 20);
}

/* ---- the adaptive recursion against a plain reference ------------------------------------ */

/* The thesis' recursion written plainly: corners every g pixels, a square halved while
 * rt_corners_differ finds a reason, a leaf filled by rt_interpolate over the pixels it owns,
 * where points known before on its top row and left column show their traced colour. Known:
 * traced within this grid square, its grid corners, and its left side as the square before in
 * the row left it (the points a square of the row above traced on the shared side are not kept:
 * the lattice holds one grid square). A point is traced (into cur[][]) when a square first needs
 * it: in full (full[][]), or, where a square split for its secondary rays whose corners agree
 * on their primary hit's lights and local part (ref_local_ok) adds it, with its local part the
 * bilinear interpolation of theirs (rt_trace_pixel_local). rt_render_adaptive's bookkeeping
 * (corner rows, the lattice and what it keeps from the square before, the 2x2 and one-colour
 * shortcuts, ss_local's means) must give exactly these pixels and this set of traced points. */
static uint32_t refpx[H * W];
static uint8_t refused[H * W], refknown[H * W];
static long ref_kept;  /* 2x2 squares the centre test filled unsplit */
static long ref_local; /* points traced with their local part interpolated */
static rt_sample cur[H][W];
static const rt_scene *ref_scene;
static const rt_view *ref_view;
static const rt_params *ref_params;
/* The square whose split adds the points traced now, when its corners qualify: its corners and
 * its (0, 0) and size; ref_area_k[0] NULL: none. */
static const rt_sample *ref_area_k[4];
static int ref_area[4];

/* May the points a square split for its secondary rays adds (corners k[], w x h) take their
 * local parts from the corners? The rule as docs/tracer.md states it, written out. */
static int ref_local_ok(const rt_sample *const k[4], int w, int h, int thr8)
{
    const int id = k[0]->hits[0].object;
    if (id == RT_NO_OBJECT || (k[0]->lights & RT_LIGHTS_HIGHLIGHT))
        return 0;
    const rt_texture *tx = &ref_scene->materials[ref_scene->objects[id].material].tex;
    if (tx->active && tx->kind != RT_TEX_CHECKER)
        return 0;                          /* a noise texture */
    for (int side = 0; side < 2; side++) { /* 0, 1, 2 or 4: at most 4 a side */
        const int n = side ? h : w;
        if (n != 0 && n != 1 && n != 2 && n != 4)
            return 0;
    }
    for (int i = 1; i < 4; i++)
        if (k[i]->lights != k[0]->lights)
            return 0;
    for (int ch = 0; ch < 3; ch++)
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++)
                if (k[i]->hits[0].contrib[ch] - k[j]->hits[0].contrib[ch] > thr8)
                    return 0;
    return 1;
}

/* Point (x, y), traced the first time a square needs it (see above); returns its sample. */
static const rt_sample *ref_need(int wi, int x, int y)
{
    const int at = y * wi + x;
    if (!refknown[at]) {
        if (ref_area_k[0]) {
            /* bilinear weights at the point, each side's n = 1 where it is 0 long */
            const int x0 = ref_area[0], y0 = ref_area[1], w = ref_area[2], h = ref_area[3];
            const int wx[2] = {w ? x0 + w - x : 1, x - x0}, wy[2] = {h ? y0 + h - y : 1, y - y0};
            const long n = (long)(wx[0] + wx[1]) * (wy[0] + wy[1]);
            rt_local loc = {.id = ref_area_k[0]->hits[0].object,
                            .cell = ref_area_k[0]->cell,
                            .lights = ref_area_k[0]->lights};
            real q[3];
            for (int ch = 0; ch < 3; ch++) {
                long sum = 0;
                for (int m = 0; m < 4; m++)
                    sum += (long)ref_area_k[m]->hits[0].contrib[ch] * wx[m & 1] * wy[m >> 1];
                /* the byte b as b 257 / 2^16, the mean rounded to nearest */
                q[ch] = r_from_q16((int32_t)((sum * 257 + n / 2) / n));
            }
            loc.col = v3(q[0], q[1], q[2]);
            rt_stats st = {0};
            rt_trace_pixel_local(ref_scene, ref_view, ref_params, x, y, &loc, &st, &cur[y][x]);
            ref_local += st.local_points;
        } else {
            cur[y][x] = full[y][x];
        }
    }
    refused[at] = refknown[at] = 1;
    return &cur[y][x];
}

static int ref_corner(int i, int g, int n)
{
    int c = i * g;
    return c < n - 1 ? c : n - 1;
}

static void ref_square(int wi, int x0, int y0, int w, int h, int own_r, int own_b, int thr8)
{
    const rt_sample *k[4];
    k[0] = ref_need(wi, x0, y0);
    k[1] = ref_need(wi, x0 + w, y0);
    k[2] = ref_need(wi, x0, y0 + h);
    k[3] = ref_need(wi, x0 + w, y0 + h);
    const enum rt_split_reason why = w > 1 || h > 1 ? rt_corners_differ(k, thr8) : RT_SPLIT_NONE;
    if (why == RT_SPLIT_CONTRIB && w == 2 && h == 2 && !own_r && !own_b) {
        /* the centre test: the centre traced first (in full); on the corners' mean within half
         * the threshold, the square is filled unsplit, traced points showing their colour as
         * the fill shows a corner */
        const rt_sample *area0 = ref_area_k[0];
        ref_area_k[0] = NULL;
        const rt_sample *mid = ref_need(wi, x0 + 1, y0 + 1);
        ref_area_k[0] = area0;
        if (rt_centre_smooth(k, mid, thr8 / 2)) {
            uint32_t *dst = refpx + y0 * wi + x0;
            ref_kept++;
            rt_interpolate(dst, wi, 2, 2, 2, 2, k[0]->color, k[1]->color, k[2]->color, k[3]->color);
            for (int j = 0; j < 2; j++)
                for (int i = 0; i < 2; i++)
                    if ((i || j) && refknown[(y0 + j) * wi + x0 + i]) {
                        const rt_color col = cur[y0 + j][x0 + i].color;
                        rt_interpolate(dst + j * wi + i, wi, 1, 1, 1, 1, col, col, col, col);
                    }
            return;
        }
    }
    if (why != RT_SPLIT_NONE) {
        /* the points this split adds: local parts interpolated where its corners qualify */
        const rt_sample *outer_k[4];
        int outer[4];
        memcpy(outer_k, ref_area_k, sizeof outer_k);
        memcpy(outer, ref_area, sizeof outer);
        ref_area_k[0] = NULL;
        if (why == RT_SPLIT_SECONDARY && ref_local_ok(k, w, h, thr8)) {
            memcpy(ref_area_k, k, sizeof ref_area_k);
            ref_area[0] = x0;
            ref_area[1] = y0;
            ref_area[2] = w;
            ref_area[3] = h;
        }
        int xs[3] = {x0, x0 + w, x0 + w}, ys[3] = {y0, y0 + h, y0 + h}, nx = 1, ny = 1;
        if (w >= 2) {
            xs[1] = x0 + w / 2;
            nx = 2;
        }
        if (h >= 2) {
            ys[1] = y0 + h / 2;
            ny = 2;
        }
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++)
                ref_square(wi, xs[i], ys[j], xs[i + 1] - xs[i], ys[j + 1] - ys[j],
                           i == nx - 1 && own_r, j == ny - 1 && own_b, thr8);
        memcpy(ref_area_k, outer_k, sizeof outer_k);
        memcpy(ref_area, outer, sizeof outer);
        return;
    }
    int cols = w + (own_r ? 1 : 0), rows = h + (own_b ? 1 : 0);
    uint32_t *dst = refpx + y0 * wi + x0;
    rt_interpolate(dst, wi, w, h, cols, rows, k[0]->color, k[1]->color, k[2]->color, k[3]->color);
    /* points known before, on the top row and left column, show their traced colour */
    for (int i = 1; i < cols; i++)
        if (refknown[y0 * wi + x0 + i])
            dst[i] = rt_color_pixel(cur[y0][x0 + i].color);
    for (int j = 1; j < rows; j++)
        if (refknown[(y0 + j) * wi + x0])
            dst[j * wi] = rt_color_pixel(cur[y0 + j][x0].color);
}

static void test_adaptive_reference(void **state)
{
    (void)state;
    static rt_scene s;
    scene_base(&s);
    int mf = add_material(&s,
                          (rt_material){.diffuse = vd(0.5, 0.45, 0.4),
                                        .ambient = from_d(0.5),
                                        .reflect = from_d(0.4)});
    int mr = add_material(&s,
                          (rt_material){.diffuse = vd(0.9, 0.2, 0.1),
                                        .ambient = from_d(0.5),
                                        .specular = from_d(0.8),
                                        .shininess = 40});
    int mm = add_material(&s,
                          (rt_material){.diffuse = vd(0.1, 0.1, 0.1),
                                        .ambient = from_d(0.3),
                                        .reflect = from_d(0.8)});
    add_floor(&s, mf);
    add_sphere(&s, mr, -1.2, 1.0, -1, 1.0);
    add_sphere(&s, mm, 1.3, 0.8, 0.5, 0.8);
    add_sphere(&s, mr, 0.2, 0.3, 2.0, 0.3);
    s.lights[1] = (rt_light){vd(-6, 4, 3), vd(0.5, 0.4, 0.3)};
    s.nlights = 2;
    s.camera = (rt_camera){vd(0.5, 2.5, 7), vd(0, 0.6, 0), vd(0, 1, 0), from_d(50)};
    rt_scene_prepare(&s);
    /* the plain recursion: no shadow pixels (test_shadow_pixels), which a view whose eye is not
     * the prepared one does not fill */
    s.cull.eye_at.x = r_add(s.cull.eye_at.x, from_d(1));
    const int sizes[][2] = {{W, H}, {W - 1, H - 1}, {37, 29}, {17, 33}, {61, 5}, {3, 3}};
    const int grids[] = {2, 4, 8, 16};
    long pixels = 0, used = 0, kept = 0, local = 0;
    ref_scene = &s;
    for (size_t n = 0; n < sizeof sizes / sizeof sizes[0]; n++) {
        int w = sizes[n][0], h = sizes[n][1];
        rt_view v;
        rt_view_init(&v, &s.camera, w, h);
        const rt_params pf = {.depth = s.depth, .mode = RT_MODE_FULL};
        rt_stats st = {0};
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                rt_trace_pixel(&s, &v, &pf, x, y, &st, &full[y][x]);
        ref_view = &v;
        ref_params = &pf;
        for (size_t g = 0; g < sizeof grids / sizeof grids[0]; g++) {
            const rt_params pa = {.depth = s.depth,
                                  .mode = RT_MODE_ADAPTIVE,
                                  .grid = grids[g],
                                  .threshold = TS_THRESHOLD,
                                  .min_contrib = 0};
            int gr = grids[g], thr8 = r_to_byte(pa.threshold);
            int ncols = w > 1 ? (w - 1 + gr - 1) / gr : 1,
                nrows = h > 1 ? (h - 1 + gr - 1) / gr : 1;
            memset(refused, 0, sizeof refused);
            memset(refknown, 0, sizeof refknown);
            const long kept0 = ref_kept, local0 = ref_local;
            ref_area_k[0] = NULL;
            for (int r = 0; r < nrows; r++)
                for (int i = 0; i < ncols; i++) {
                    int x0 = ref_corner(i, gr, w), y0 = ref_corner(r, gr, h);
                    int x1 = ref_corner(i + 1, gr, w), y1 = ref_corner(r + 1, gr, h);
                    for (int y = y0; y <= y1; y++)
                        for (int x = i > 0 ? x0 + 1 : x0; x <= x1; x++)
                            refknown[y * w + x] = 0;
                    ref_square(w, x0, y0, ref_corner(i + 1, gr, w) - x0,
                               ref_corner(r + 1, gr, h) - y0, i == ncols - 1, r == nrows - 1, thr8);
                }
            assert_true(rt_render_work_size(&pa, w) <= sizeof work);
            rt_stats sa = {0};
            rt_render(&s, &v, &pa, adpx, w, &sa, work, traced);
            assert_int_equal(sa.contrib_kept, ref_kept - kept0);
            assert_int_equal(sa.local_points, ref_local - local0);
            kept += sa.contrib_kept;
            local += sa.local_points;
            for (int i = 0; i < w * h; i++) {
                if (adpx[i] != refpx[i] || (traced[i] != 0) != refused[i])
                    fail_msg("%dx%d grid %d: pixel (%d, %d) is %06x traced %d, the plain "
                             "recursion's %06x traced %d",
                             w, h, gr, i % w, i / w, (unsigned)adpx[i], traced[i],
                             (unsigned)refpx[i], refused[i]);
                used += refused[i];
            }
            pixels += w * h;
        }
    }
    /* the scene has edges of every kind: a good share of the points is traced */
    assert_true(used * 10 > pixels);
    /* and smooth 2x2 squares split for their contributions alone that were filled unsplit */
    assert_true(kept > 0);
    /* and points of reflections' edges whose local parts were interpolated */
    assert_true(local > 0);
    print_message("adaptive recursion: %ld pixels (%ld traced, %ld 2x2 squares kept by the centre "
                  "test, %ld points with interpolated local parts) equal to the plain "
                  "recursion's\n",
                  pixels, used, kept, local);
}

/* ---- probe mode ----------------------------------------------------------------------------- */

/* Renders the scene in full, adaptive and probe mode. Checks that at least min_percent of the
 * pixels next to a pixel of another record (rt_probe_same) that the split criteria tell apart
 * were shaded or probed, that no pixel is off by more than
 * max_err levels from the full render (exact_edges: pixels on those edges not at all), and
 * that probe mode shaded no more points than adaptive mode and (probed: 1) probed some or (0)
 * none. Returns the shaded points. */
static uint32_t check_probe(rt_scene *s, int exact_edges, int max_err, int min_percent,
                            const char *name, int unprepared, int probed)
{
    rt_scene_prepare(s);
    if (unprepared) /* the view's eye not the prepared one: no shadow pixels */
        s->cull.eye_at.x = r_add(s->cull.eye_at.x, from_d(1));
    rt_view v;
    rt_view_init(&v, &s->camera, W, H);
    const rt_params pf = {.depth = s->depth, .mode = RT_MODE_FULL};
    rt_params pa = {
        .depth = s->depth, .mode = RT_MODE_ADAPTIVE, .grid = 8, .threshold = TS_THRESHOLD};
    rt_stats st = {0}, sa = {0}, sp = {0};
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            rt_trace_pixel(s, &v, &pf, x, y, &st, &full[y][x]);
    rt_render(s, &v, &pf, fullpx, W, &st, NULL, NULL);
    rt_render(s, &v, &pa, adpx, W, &sa, work, NULL);
    pa.mode = RT_MODE_PROBE;
    assert_true(rt_render_work_size(&pa, W) <= sizeof work);
    rt_render(s, &v, &pa, adpx, W, &sp, work, traced);
    int worst = 0, edge = 0, followed = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int p = y * W + x, on_edge = 0;
            for (int d = 0; d < 4; d++) {
                int x2 = x + (d == 0) - (d == 1), y2 = y + (d == 2) - (d == 3);
                if (x2 >= 0 && y2 >= 0 && x2 < W && y2 < H &&
                    !rt_probe_same(&full[y][x], &full[y2][x2])) {
                    /* an edge the split criteria see at the render's threshold (a shadow or
                     * a reflection too faint to show is none) */
                    const rt_sample *k[4] = {&full[y][x], &full[y][x], &full[y2][x2],
                                             &full[y2][x2]};
                    on_edge |= rt_corners_differ(k, r_to_byte(pa.threshold)) != RT_SPLIT_NONE;
                }
            }
            for (int ch = 0; ch < 3; ch++) {
                int e =
                    abs((int)(adpx[p] >> (8 * ch) & 0xFF) - (int)(fullpx[p] >> (8 * ch) & 0xFF));
                worst = e > worst ? e : worst;
            }
            if (on_edge) {
                edge++;
                followed += traced[p] != 0;
                if (exact_edges && traced[p])
                    assert_int_equal(adpx[p], fullpx[p]);
            }
        }
    print_message("%s: %d edge pixels, shaded %u (adaptive %u), probes %u, worst %d level(s)\n",
                  name, edge, (unsigned)sp.rays_primary, (unsigned)sa.rays_primary,
                  (unsigned)sp.probes, worst);
    assert_true(edge > 0);
    assert_true(followed * 100 >= edge * min_percent);
    assert_true(worst <= max_err);
    assert_true(sp.rays_primary <= sa.rays_primary);
    assert_true(probed ? sp.probes > 0 : sp.probes == 0);
    return sp.rays_primary;
}

/* Flat-shaded surfaces (no light: each object one colour): a slanted wall standing on the
 * floor, seen from above at an angle. */
static void wall_scene(rt_scene *s)
{
    scene_base(s);
    s->nlights = 0;
    int mf = add_material(s, (rt_material){.diffuse = vd(0.7, 0.7, 0.6), .ambient = from_d(1)});
    int mw = add_material(s, (rt_material){.diffuse = vd(0.2, 0.3, 0.8), .ambient = from_d(1)});
    add_floor(s, mf);
    rt_object *o = &s->objects[s->nobjects++];
    *o = (rt_object){.kind = RT_PLANE, .material = (uint8_t)mw};
    o->axis = vd(1, 0, 0.4);
    s->camera = (rt_camera){vd(-2, 4, 8), vd(1, 0, 0), vd(0, 1, 0), from_d(50)};
}

/* Flat-shaded surfaces (no light: each object one colour) cut by a straight edge, a slanted wall
 * standing on the floor: both sides come out exactly, with fewer points shaded. */
static void test_probe_straight_edge(void **state)
{
    (void)state;
    static rt_scene s;
    wall_scene(&s);
    uint32_t shaded = check_probe(&s, 1, 0, 100, "probe: straight edge", 0, 1);
    rt_stats sa = {0};
    rt_params pa = {
        .depth = s.depth, .mode = RT_MODE_ADAPTIVE, .grid = 8, .threshold = TS_THRESHOLD};
    rt_view v;
    rt_view_init(&v, &s.camera, W, H);
    rt_render(&s, &v, &pa, adpx, W, &sa, work, NULL);
    assert_true(shaded * 8 <= sa.rays_primary * 7); /* at most 7/8 of adaptive's */
}

/* The shadow of a sphere on a matte floor: the shadow's edge followed to the pixel (by full
 * shades: a light state is not probed, that would cost as much as the shade), the sphere's
 * outline by probes, the lit side interpolated within twice the split threshold. */
static void test_probe_shadow_edge(void **state)
{
    (void)state;
    static rt_scene s;
    shadow_scene(&s);
    /* split (shadow pixels off: those are test_shadow_pixels') */
    check_probe(&s, 0, 32, 100, "probe: shadow edge", 1, 1); /* twice the split threshold */
}

/* A sphere seen only in a mirror floor: the reflected outline is followed to the pixel where
 * adaptive mode follows it (90%: by full shades, a ray tree is not probed); the sphere's own
 * outline lies against the mirror, which casts a secondary ray: nothing is probed. */
static void test_probe_reflected_edge(void **state)
{
    (void)state;
    static rt_scene s;
    mirror_scene(&s);
    s.lights[0].pos = vd(0, 20, 20);
    s.camera = (rt_camera){vd(0, 3, 6), vd(0, 0, 0), vd(0, 1, 0), from_d(40)};
    /* (its floor shows the sphere's shadow too: split, shadow pixels off) */
    check_probe(&s, 0, 64, 90, "probe: reflected edge", 1, 0); /* what adaptive mode misses too */
}

/* Pixel (x, y) traced as probe mode shades it (its record, its flags: rt_probe_opaque). */
static rt_sample probe_shade(const rt_scene *s, const rt_view *v, int x, int y)
{
    const rt_params p = {
        .depth = s->depth, .mode = RT_MODE_PROBE, .grid = 8, .threshold = TS_THRESHOLD};
    const rt_probe_masks mk = rt_probe_masks_of(s);
    rt_stats st = {0};
    rt_sample sm;
    rt_trace_pixel(s, v, &p, x, y, &st, &sm);
    sm.flags = (uint8_t)rt_probe_opaque(&mk, &sm);
    return sm;
}

/* rt_probe_point on one edge, against what full shades give. The straight edge (flat-shaded
 * floor and wall): an edge across the outline is not probed (-1: its ends' records differ), nor
 * an edge of 4 pixels with both ends on one side, and an edge of 2 with both ends on one side
 * gives the ends' colour mixed; a point of the other side between them is probed and shaded
 * (0). The shadow scene: a lit point between two ends in the shadow is not probed on an edge of
 * 4 pixels, and on one of 2 takes the ends' record with no ray. The mirror floor: ends whose ray
 * trees differ are not probed (-1). */
static void test_probe_point_edge(void **state)
{
    (void)state;
    static rt_scene s;
    wall_scene(&s);
    rt_scene_prepare(&s);
    rt_view v;
    rt_view_init(&v, &s.camera, W, H);
    const int thr8 = r_to_byte(TS_THRESHOLD), y = H / 2;
    const real half = r_from_ratio(1, 2);
    int x0 = -1, flat_ok = 0;
    for (int x = 0; x + 8 < W && x0 < 0; x++) {
        rt_sample a = probe_shade(&s, &v, x, y), b = probe_shade(&s, &v, x + 4, y);
        if (a.hits[0].object != b.hits[0].object)
            x0 = x;
    }
    assert_true(x0 >= 0);
    {
        rt_sample a = probe_shade(&s, &v, x0, y), b = probe_shade(&s, &v, x0 + 4, y), out;
        rt_stats st = {0};
        rt_primary pri;
        assert_int_equal(rt_probe_point(&s, &v, &st, thr8, x0 + 2, y, &a, &b, half, 4, &pri, &out),
                         -1);
        rt_sample m2 = probe_shade(&s, &v, x0 + 2, y);
        const int same = m2.hits[0].object == a.hits[0].object; /* the outline: after x0 + 2 */
        assert_int_equal(rt_probe_point(&s, &v, &st, thr8, x0 + 1 + 2 * same, y, same ? &m2 : &a,
                                        same ? &b : &m2, half, 2, &pri, &out),
                         -1);
        assert_int_equal(st.probes, 0); /* not probed */
        /* a point of the other side between two ends on one side: probed, then shaded */
        assert_int_equal(rt_probe_point(&s, &v, &st, thr8, x0 + 4, y, &a, &a, half, 2, &pri, &out),
                         0);
        assert_int_equal(pri.id, b.hits[0].object); /* its primary hit, for the full shade */
        assert_int_equal(st.probes, 1);
    }
    for (int x = 0; x + 4 < W; x++) { /* an edge on one side: the mixed colour */
        rt_sample a = probe_shade(&s, &v, x, y), b = probe_shade(&s, &v, x + 2, y),
                  m = probe_shade(&s, &v, x + 1, y), out;
        if (!rt_probe_same(&a, &b) || !rt_probe_same(&a, &m))
            continue;
        rt_stats st = {0};
        rt_primary pri;
        assert_int_equal(rt_probe_point(&s, &v, &st, thr8, x + 1, y, &a, &b, half, 4, &pri, &out),
                         -1);
        assert_int_equal(rt_probe_point(&s, &v, &st, thr8, x + 1, y, &a, &b, half, 2, &pri, &out),
                         1);
        assert_int_equal(out.flags, RT_SAMPLE_PROBED);
        assert_int_equal(rt_color_pixel(out.color), rt_color_pixel(m.color)); /* flat */
        flat_ok = 1;
        break;
    }
    assert_true(flat_ok);

    /* a lit point between two ends in a shadow (the same floor record) */
    shadow_scene(&s);
    rt_scene_prepare(&s);
    rt_view_init(&v, &s.camera, W, H);
    int lit = -1, dark = -1;
    for (int p = 0; p < W * H && (lit < 0 || dark < 0); p++) {
        rt_sample m = probe_shade(&s, &v, p % W, p / W);
        if (m.hits[0].object != 0 || m.nhits != 1)
            continue;
        if (rt_light_state(&m, 0) == 1 && lit < 0)
            lit = p;
        if (rt_light_state(&m, 0) == 0 && dark < 0)
            dark = p;
    }
    assert_true(lit >= 0 && dark >= 0);
    {
        rt_sample a = probe_shade(&s, &v, dark % W, dark / W), out;
        rt_stats st = {0};
        rt_primary pri;
        assert_int_equal(
            rt_probe_point(&s, &v, &st, thr8, lit % W, lit / W, &a, &a, half, 4, &pri, &out), -1);
        assert_int_equal(st.probes, 0);
        assert_int_equal(
            rt_probe_point(&s, &v, &st, thr8, lit % W, lit / W, &a, &a, half, 2, &pri, &out), 1);
        assert_int_equal(st.rays_shadow, 0);
        assert_true(rt_probe_same(&out, &a));
    }

    /* ends on a mirror floor whose reflections differ: no probe */
    mirror_scene(&s);
    s.camera = (rt_camera){vd(0, 3, 6), vd(0, 0, 0), vd(0, 1, 0), from_d(40)};
    rt_scene_prepare(&s);
    rt_view_init(&v, &s.camera, W, H);
    int found = 0;
    for (int p = 0; p + 4 < W * H && !found; p++) {
        if (p % W + 4 >= W)
            continue;
        rt_sample a = probe_shade(&s, &v, p % W, p / W), b = probe_shade(&s, &v, p % W + 4, p / W),
                  out;
        if (a.hits[0].object != 0 || b.hits[0].object != 0 || a.nhits < 2 || b.nhits < 2 ||
            a.hits[1].object == b.hits[1].object || a.lights != b.lights)
            continue;
        rt_stats st = {0};
        rt_primary pri;
        assert_int_equal(
            rt_probe_point(&s, &v, &st, thr8, p % W + 2, p / W, &a, &b, half, 4, &pri, &out), -1);
        found = 1;
    }
    assert_true(found);
}

/* Every frame size, multiple of the grid or not, down to a single pixel: every pixel written,
 * the corners of the grid traced, and a flat picture comes out exactly as in full mode. */
static void test_sizes(void **state)
{
    (void)state;
    static rt_scene s;
    one_sphere_scene(&s, 0, 0, 2.0);
    rt_scene_prepare(&s);
    const int sizes[][2] = {{1, 1},   {1, 7},   {7, 1}, {2, 2},         {9, 9},
                            {17, 17}, {13, 10}, {W, H}, {W - 1, H - 3}, {33, 65}};
    const int grids[] = {2, 4, 8, 16};
    for (size_t n = 0; n < sizeof sizes / sizeof sizes[0]; n++) {
        for (size_t g = 0; g < sizeof grids / sizeof grids[0]; g++) {
            int w = sizes[n][0], h = sizes[n][1], grid = grids[g];
            rt_view v;
            rt_view_init(&v, &s.camera, w, h);
            const rt_params pf = {.depth = 2, .mode = RT_MODE_FULL};
            const rt_params pa = {
                .depth = 2, .mode = RT_MODE_ADAPTIVE, .grid = grid, .threshold = TS_THRESHOLD};
            rt_stats st = {0};
            assert_true(rt_render_work_size(&pa, w) <= sizeof work);
            for (int i = 0; i < w * h; i++)
                adpx[i] = 0xFF000000;
            rt_render(&s, &v, &pa, adpx, w, &st, work, traced);
            int written = 0, ntraced = 0;
            for (int i = 0; i < w * h; i++) {
                written += adpx[i] >> 24 == 0;
                ntraced += traced[i] != 0;
            }
            assert_int_equal(written, w * h);
            /* the four frame corners and the grid's corners are traced */
            assert_true(traced[0] && traced[w - 1] && traced[(h - 1) * w] && traced[h * w - 1]);
            for (int y = 0; y < h; y += grid)
                for (int x = 0; x < w; x += grid)
                    assert_true(traced[y * w + x]);
            /* each point is traced once, except sub-square points on the edge between two
             * bands (both bands may need them) */
            int ncols = w > 1 ? (w - 1 + grid - 1) / grid : 1;
            int nrows = h > 1 ? (h - 1 + grid - 1) / grid : 1;
            assert_true(st.rays_primary >= (uint32_t)ntraced);
            assert_true(st.rays_primary <= (uint32_t)(ntraced + w * (nrows - 1)));
            /* without the sphere the picture is flat: identical to full mode */
            s.nobjects = 0;
            rt_stats sf = {0};
            rt_render(&s, &v, &pf, fullpx, w, &sf, NULL, NULL);
            rt_render(&s, &v, &pa, adpx, w, &sf, work, NULL);
            assert_memory_equal(adpx, fullpx, (size_t)(w * h) * sizeof *adpx);
            s.nobjects = 1;
            /* the squares and the splits add up */
            if (w > 2 && h > 2 && (w - 1) % grid == 0 && (h - 1) % grid == 0)
                assert_int_equal(st.squares[0], (uint32_t)(ncols * nrows));
            for (int l = 0; l < RT_GRID_LEVELS; l++)
                assert_true(st.split[l] <= st.squares[l]);
        }
    }
}

/* Bands: a frame rendered as 1, 2, 3, ... bands (in any order, as threads would) equals the
 * frame rendered whole, pixels and traced map, in both modes, for every grid. */
static void test_bands(void **state)
{
    (void)state;
    static rt_scene s;
    one_sphere_scene(&s, 0, 0, 2.0);
    rt_scene_prepare(&s);
    static uint32_t bandpx[W * H];
    static uint8_t bandtr[W * H];
    const int sizes[][2] = {{1, 1}, {7, 1}, {1, 9}, {W, H}, {W - 1, H - 3}, {33, 65}};
    const int grids[] = {2, 4, 8, 16};
    for (size_t n = 0; n < sizeof sizes / sizeof sizes[0]; n++) {
        for (size_t g = 0; g < sizeof grids / sizeof grids[0]; g++) {
            for (int mode = RT_MODE_FULL; mode <= RT_MODE_PROBE; mode++) {
                int w = sizes[n][0], h = sizes[n][1];
                const rt_params p = {
                    .depth = 2, .mode = mode, .grid = grids[g], .threshold = TS_THRESHOLD};
                rt_view v;
                rt_view_init(&v, &s.camera, w, h);
                rt_stats st = {0};
                rt_render(&s, &v, &p, adpx, w, &st, work, traced);
                int count = rt_render_band_count(&p, h);
                assert_true(count >= 1);
                for (int nb = 1; nb <= count + 2; nb++) {
                    memset(bandpx, 0xAB, sizeof bandpx);
                    memset(bandtr, 0, sizeof bandtr);
                    for (int b = nb - 1; b >= 0; b--) /* last band first */
                        rt_render_band(&s, &v, &p, bandpx, w, &st, work, bandtr, b, nb);
                    assert_memory_equal(bandpx, adpx, (size_t)(w * h) * sizeof *adpx);
                    if (mode == RT_MODE_ADAPTIVE)
                        assert_memory_equal(bandtr, traced, (size_t)(w * h));
                }
            }
        }
    }
}

/* Bands in order into memory that holds one band (rt_render_band_into), as a board without a
 * frame in RAM renders: with the shared rows of corners kept, the frame and every statistic
 * equal one rt_render's; without, the pixels are the same but the corners on the edges between
 * bands are traced twice. No band writes outside its rows. */
static void test_bands_into(void **state)
{
    (void)state;
    static rt_scene s;
    one_sphere_scene(&s, 0.4, -0.3, 2.0);
    rt_scene_prepare(&s);
    static uint32_t frame[W * H], band[W * (RT_GRID_MAX + 2)];
    const int sizes[][2] = {{1, 1}, {7, 1}, {1, 9}, {W, H}, {W - 1, H - 3}, {33, 65}, {W, 64}};
    const int grids[] = {2, 4, 8, 16};
    for (size_t n = 0; n < sizeof sizes / sizeof sizes[0]; n++) {
        for (size_t g = 0; g < sizeof grids / sizeof grids[0]; g++) {
            for (int mode = RT_MODE_FULL; mode <= RT_MODE_PROBE; mode++) {
                int w = sizes[n][0], h = sizes[n][1];
                const rt_params p = {
                    .depth = 2, .mode = mode, .grid = grids[g], .threshold = TS_THRESHOLD};
                rt_view v;
                rt_view_init(&v, &s.camera, w, h);
                rt_stats whole = {0};
                rt_render(&s, &v, &p, adpx, w, &whole, work, NULL);
                int count = rt_render_band_count(&p, h);
                for (int keep = 0; keep <= 1; keep++) {
                    rt_stats st = {0};
                    memset(frame, 0xAB, sizeof frame);
                    int next = 0;
                    for (int b = 0; b < count; b++) {
                        int y0, rows;
                        rt_render_band_rows(&p, h, b, count, &y0, &rows);
                        assert_int_equal(y0, next); /* in order, no gap, no overlap */
                        assert_true(rows >= 1 && rows <= (mode ? grids[g] + 1 : 1));
                        next = y0 + rows;
                        memset(band, 0xCD, sizeof band);
                        rt_render_band_into(&s, &v, &p, band, w, &st, work, NULL, b, count,
                                            keep && b);
                        for (size_t i = (size_t)(rows * w); i < sizeof band / sizeof *band; i++)
                            assert_int_equal(band[i], 0xCDCDCDCD);
                        memcpy(frame + y0 * w, band, (size_t)(rows * w) * sizeof *band);
                    }
                    assert_int_equal(next, h);
                    assert_memory_equal(frame, adpx, (size_t)(w * h) * sizeof *adpx);
                    if (keep || mode == RT_MODE_FULL || count == 1)
                        assert_memory_equal(&st, &whole, sizeof st);
                    else
                        assert_int_equal(
                            st.rays_primary,
                            whole.rays_primary +
                                (uint32_t)((count - 1) * (w > 1 ? (w - 2) / grids[g] + 2 : 1)));
                }
            }
        }
    }
}

/* Adaptive recursion control: rays weighing less than min_contrib are not cast, and their
 * share is all the picture loses. */
static void test_min_contrib(void **state)
{
    (void)state;
    static rt_scene s;
    scene_base(&s);
    int mm = add_material(
        &s,
        (rt_material){.diffuse = vd(0.1, 0.1, 0.1), .ambient = from_d(1), .reflect = from_d(0.5)});
    add_sphere(&s, mm, -1.2, 0, -8, 1.0);
    add_sphere(&s, mm, 1.2, 0, -8, 1.0);
    s.depth = 8;
    s.camera = (rt_camera){vd(0, 0, 0), vd(0, 0, -8), vd(0, 1, 0), from_d(40)};
    rt_scene_prepare(&s);
    rt_view v;
    rt_view_init(&v, &s.camera, W, H);
    uint32_t count[5];
    const double limits[] = {0, 0.01, 0.1, 0.3, 0.6};
    for (size_t i = 0; i < sizeof limits / sizeof limits[0]; i++) {
        rt_params p = {.depth = 8, .mode = RT_MODE_FULL, .min_contrib = from_d(limits[i])};
        rt_stats st = {0};
        rt_render(&s, &v, &p, adpx, W, &st, NULL, NULL);
        count[i] = st.rays_reflect;
        print_message("min_contrib %.2f: %lu reflected rays\n", limits[i],
                      (unsigned long)st.rays_reflect);
        if (i > 0)
            assert_true(count[i] <= count[i - 1]);
    }
    assert_true(count[3] < count[0]); /* 0.3 > 0.25: the second bounce is cut */
    assert_true(count[3] > 0);        /* 0.3 < 0.5: the first is not */
    assert_int_equal(count[4], 0);    /* 0.6 > 0.5: not even the first bounce */
}

/* A checkerboard whose two colours are equal has no cell edges to find: adaptive and probe
 * renders of the shadow scene (its ball a two-tone checker) with such a floor trace the same
 * points and give the same pixels as with a plain floor; with two colours, squares the floor's
 * cell edges cross are filled by cell in both modes (texture squares, test_checker_cells). */
static void test_one_tone_checker(void **state)
{
    (void)state;
    static rt_scene plain, one, two;
    static uint32_t px_plain[H * W];
    shadow_scene(&plain);
    /* the ball is a two-tone checker in all three (so texturing is on in each) */
    plain.materials[1].tex =
        (rt_texture){.kind = RT_TEX_CHECKER, .scale = from_d(3), .color2 = vd(0.6, 0.2, 0.2)};
    one = plain;
    one.materials[0].tex = (rt_texture){
        .kind = RT_TEX_CHECKER, .scale = from_d(2), .color2 = one.materials[0].diffuse};
    two = one;
    two.materials[0].tex.color2 = vd(0.2, 0.3, 0.4);
    rt_scene_prepare(&plain);
    rt_scene_prepare(&one);
    rt_scene_prepare(&two);
    assert_int_equal(one.materials[0].tex.active, 0);
    assert_int_equal(two.materials[0].tex.active, 1);
    rt_view v;
    rt_view_init(&v, &plain.camera, W, H);
    for (int mode = RT_MODE_ADAPTIVE; mode <= RT_MODE_PROBE; mode++) {
        if (mode == RT_MODE_PROBE && !RT_COMPILED_PROBE)
            continue;
        const rt_params p = {
            .depth = plain.depth, .mode = mode, .grid = 8, .threshold = TS_THRESHOLD};
        rt_stats sp = {0}, s1 = {0}, s2 = {0};
        assert_true(rt_render_work_size(&p, W) <= sizeof work);
        rt_render(&plain, &v, &p, px_plain, W, &sp, work, NULL);
        rt_render(&one, &v, &p, adpx, W, &s1, work, NULL);
        assert_memory_equal(px_plain, adpx, sizeof adpx);
        assert_int_equal(sp.rays_primary, s1.rays_primary);
        rt_render(&two, &v, &p, adpx, W, &s2, work, NULL);
        print_message("mode %d: %lu points traced with a plain or one-tone checker floor, %lu with "
                      "two tones\n",
                      mode, (unsigned long)s1.rays_primary, (unsigned long)s2.rays_primary);
        assert_int_equal(s1.texture_squares, 0);
        assert_true(s2.texture_squares > 0);
    }
}

/* Texture squares: a two-tone checker floor under one light (nothing casts a shadow). Adaptive
 * mode fills a square whose corners differ only in their cells pixel by pixel, each pixel with
 * the corners' colours for its own cell's tone, instead of splitting it down to single pixels
 * along every cell edge. Compared with full mode and with the old splitting (which the renderer
 * falls back to when the view's eye is not the prepared one: eye_at moved away). */
static void test_checker_cells(void **state)
{
    (void)state;
    static rt_scene s, split, plain;
    static uint32_t px_split[H * W];
    scene_base(&s);
    int mf = add_material(&s, (rt_material){.diffuse = vd(0.85, 0.8, 0.7), .ambient = from_d(0.4)});
    s.materials[mf].tex =
        (rt_texture){.kind = RT_TEX_CHECKER, .scale = from_d(0.5), .color2 = vd(0.1, 0.2, 0.45)};
    add_floor(&s, mf);
    s.lights[0].pos = vd(1, 12, -4);
    s.camera = (rt_camera){vd(0, 5, 5), vd(0, 0, -1), vd(0, 1, 0), from_d(50)}; /* no horizon */
    rt_scene_prepare(&s);
    assert_int_equal(s.materials[mf].tex.active, 1);
    plain = s; /* the same floor without its checker */
    plain.materials[mf].tex.kind = RT_TEX_NONE;
    rt_scene_prepare(&plain);
    split = s;
    split.cull.eye_at.x =
        r_add(split.cull.eye_at.x, from_d(1)); /* views from the camera: not prepared */
    rt_view v;
    rt_view_init(&v, &s.camera, W, H);
    const rt_params pf = {.depth = s.depth, .mode = RT_MODE_FULL};
    const rt_params pa = {
        .depth = s.depth, .mode = RT_MODE_ADAPTIVE, .grid = 8, .threshold = TS_THRESHOLD};
    rt_stats sf = {0}, sa = {0}, ss = {0};
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            rt_trace_pixel(&s, &v, &pf, x, y, &sf, &full[y][x]);
    rt_render(&s, &v, &pf, fullpx, W, &sf, NULL, NULL);
    rt_render(&s, &v, &pa, adpx, W, &sa, work, traced);
    rt_render(&split, &v, &pa, px_split, W, &ss, work, NULL);
    rt_stats sp = {0};
    rt_render(&plain, &v, &pa, px_split, W, &sp, work, NULL);
    int worst = 0, pairs = 0, looked_up = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            for (int ch = 0; ch < 24; ch += 8) {
                int d = (int)(adpx[y * W + x] >> ch & 255) - (int)(fullpx[y * W + x] >> ch & 255);
                worst = d < 0 ? (-d > worst ? -d : worst) : (d > worst ? d : worst);
            }
            /* a cell edge between x and x + 1 (full mode's cells) where the tones lie far apart
             * (40 levels or more in some channel): counted, and whether both pixels were looked
             * up (a pixel off by more than the bound below took the wrong tone) */
            if (x + 1 < W && full[y][x].cell && full[y][x + 1].cell &&
                rt_cell_tone(full[y][x].cell) != rt_cell_tone(full[y][x + 1].cell)) {
                int contrast = 0;
                for (int ch = 0; ch < 24; ch += 8) {
                    int d = (int)(fullpx[y * W + x] >> ch & 255) -
                        (int)(fullpx[y * W + x + 1] >> ch & 255);
                    contrast =
                        d < 0 ? (-d > contrast ? -d : contrast) : (d > contrast ? d : contrast);
                }
                if (contrast < 40) /* (under the highlight both tones are near white) */
                    continue;
                pairs++;
                looked_up += !traced[y * W + x] && !traced[y * W + x + 1];
            }
        }
    print_message("checker cells: %lu points traced (%lu with the cells split, %lu on a plain "
                  "floor, %lu in full), %lu squares filled by cell, %lu pixels looked up; %d "
                  "cell-edge pairs, %d of them looked up on both sides; worst pixel %d levels "
                  "from full mode's\n",
                  (unsigned long)sa.rays_primary, (unsigned long)ss.rays_primary,
                  (unsigned long)sp.rays_primary, (unsigned long)sf.rays_primary / 2,
                  (unsigned long)sa.texture_squares, (unsigned long)sa.texture_pixels, pairs,
                  looked_up, worst);
    assert_int_equal(ss.texture_squares, 0);
    assert_true(sa.texture_squares > 0 && sa.texture_pixels > 0);
    /* far fewer points traced than with the cells split: as few as on a plain floor */
    assert_true(sa.rays_primary * 8 <= ss.rays_primary);
    assert_true(sa.rays_primary <= sp.rays_primary + sp.rays_primary / 8);
    assert_true(pairs >= 100);
    assert_true(looked_up * 4 >= pairs * 3); /* most edges are no longer traced */
    assert_true(worst <= 6); /* and each pixel took its own cell's tone (40 levels apart) */
}

/* The worst channel difference between two frames and the number of pixels that differ by more
 * than 8 levels in some channel. */
static int frame_diff(const uint32_t *a, const uint32_t *b, int *over8)
{
    int worst = 0;
    *over8 = 0;
    for (int i = 0; i < W * H; i++) {
        int m = 0;
        for (int ch = 0; ch < 24; ch += 8) {
            int d = abs((int)(a[i] >> ch & 255) - (int)(b[i] >> ch & 255));
            m = d > m ? d : m;
        }
        worst = m > worst ? m : worst;
        *over8 += m > 8;
    }
    return worst;
}

/* A marble sphere filling most of the frame, lit by one light with a highlight. */
static void noise_scene(rt_scene *s, double scale, int octaves)
{
    scene_base(s);
    int m = add_material(s,
                         (rt_material){.ambient = from_d(0.6),
                                       .specular = from_d(0.3),
                                       .shininess = 20,
                                       .tex = {.kind = RT_TEX_MARBLE,
                                               .palette = RT_PAL_MARBLE,
                                               .octaves = (uint8_t)octaves,
                                               .scale = from_d(scale),
                                               .turbulence = from_d(1.2)}});
    add_sphere(s, m, 0, 0, 0, 2.0);
    s->camera = (rt_camera){vd(0, 0.5, 6), vd(0, 0, 0), vd(0, 1, 0), from_d(45)};
    rt_scene_prepare(s);
}

/* Noise textures shaded per pixel: adaptive mode does not split a square on a noise texture down
 * to single pixels for the texture's colour when its corners agree on the lighting A and the
 * rest B (colour = texture x A + B); each pixel gets the texture at its own hit with A and B
 * interpolated. Against full mode (every pixel shaded) the frame stays within a bound that a
 * texture evaluated wrongly per pixel breaks: full frames of the same sphere with its texture
 * shifted by 2% in scale, or with fewer octaves, are compared with the same bound and must fail
 * it. The old splitting (a view whose eye is not the prepared one) traces far more points. */
static void test_noise_pixels(void **state)
{
    (void)state;
    static rt_scene s, split, scaled, coarse;
    static uint32_t px_split[H * W], px_scaled[H * W], px_coarse[H * W];
    noise_scene(&s, 2.2, 4);
    noise_scene(&scaled, 2.2 * 1.02, 4);
    noise_scene(&coarse, 2.2, 2);
    split = s;
    split.cull.eye_at.x =
        r_add(split.cull.eye_at.x, from_d(1)); /* views from the camera: not prepared */
    rt_view v;
    rt_view_init(&v, &s.camera, W, H);
    const rt_params pf = {.depth = s.depth, .mode = RT_MODE_FULL, .footprint = 1};
    const rt_params pa = {.depth = s.depth,
                          .mode = RT_MODE_ADAPTIVE,
                          .grid = 8,
                          .threshold = TS_THRESHOLD,
                          .footprint = 1};
    rt_stats sf = {0}, sa = {0}, ss = {0}, sx = {0};
    rt_render(&s, &v, &pf, fullpx, W, &sf, NULL, NULL);
    rt_render(&s, &v, &pa, adpx, W, &sa, work, traced);
    rt_render(&split, &v, &pa, px_split, W, &ss, work, NULL);
    rt_render(&scaled, &v, &pf, px_scaled, W, &sx, NULL, NULL);
    rt_render(&coarse, &v, &pf, px_coarse, W, &sx, NULL, NULL);
    int o_a, o_s, o_scaled, o_coarse, untraced = 0;
    const int w_a = frame_diff(adpx, fullpx, &o_a), w_s = frame_diff(px_split, fullpx, &o_s);
    const int w_scaled = frame_diff(px_scaled, fullpx, &o_scaled),
              w_coarse = frame_diff(px_coarse, fullpx, &o_coarse);
    for (int i = 0; i < W * H; i++)
        untraced += !traced[i];
    print_message("noise pixels: %lu points traced (%lu with the texture split, %d pixels), %lu "
                  "squares filled per pixel, %lu pixels textured; against full mode: worst %d "
                  "levels, %d pixels over 8 (split: %d, %d); texture 2%% larger: %d, %d; 2 "
                  "octaves: %d, %d\n",
                  (unsigned long)sa.rays_primary, (unsigned long)ss.rays_primary, W * H,
                  (unsigned long)sa.noise_squares, (unsigned long)sa.noise_pixels, w_a, o_a, w_s,
                  o_s, w_scaled, o_scaled, w_coarse, o_coarse);
    assert_int_equal(ss.noise_squares, 0);
    assert_true(sa.noise_squares > 0 && sa.noise_pixels > 0);
    assert_true(sa.noise_pixels <= (uint32_t)untraced);
    /* fewer points traced than with the texture split */
    assert_true(sa.rays_primary * 5 <= ss.rays_primary * 4);
    /* the bound, and a wrong texture per pixel would break it */
    const int bound_worst = 40, bound_over8 = W * H / 100;
    assert_true(w_a <= bound_worst && o_a <= bound_over8);
    assert_true(w_scaled > bound_worst || o_scaled > bound_over8);
    assert_true(w_coarse > bound_worst || o_coarse > bound_over8);
}

/* ss_noise_seen on constructed records, its decisions known in closed form: object 1 has a noise
 * texture, objects 0 and 3 are flat (a plane, a sphere around the eye), object 2 is not. A square
 * whose corners agree is split where a noise node's contribution at some corner exceeds twice
 * the threshold and its parent (the last node before it a level up) is flat. */
static void test_noise_seen(void **state)
{
    (void)state;
    ss_ctx c = {.thr8 = 16, .noise_beyond = 1u << 1, .flat_view = 1u << 0 | 1u << 3};
    rt_sample a;
    memset(&a, 0, sizeof a);
    a.nhits = 2;
    a.hits[0] = (rt_hit_rec){.object = 0, .level = 0, .contrib = {10, 10, 10}};
    a.hits[1] = (rt_hit_rec){.object = 1, .level = 1, .contrib = {32, 32, 32}};
    rt_sample b = a;
    const rt_sample *k[4] = {&a, &a, &a, &b};
    assert_int_equal(ss_noise_seen(&c, k), 0); /* 2 x 16: not over twice the threshold */
    b.hits[1].contrib[2] = 33;                 /* one channel of one corner over it */
    assert_int_equal(ss_noise_seen(&c, k), 1);
    c.noise_beyond = 0; /* the same node on a plain object */
    assert_int_equal(ss_noise_seen(&c, k), 0);
    c.noise_beyond = 1u << 1;
    a.hits[0].object = b.hits[0].object = 2; /* seen off a sphere from outside */
    assert_int_equal(ss_noise_seen(&c, k), 0);
    /* a deeper node: its parent is the node a level up just before it, not an earlier one */
    a.nhits = b.nhits = 5;
    a.hits[1] = (rt_hit_rec){.object = 3, .level = 1, .contrib = {5, 5, 5}};
    a.hits[2] = (rt_hit_rec){.object = 2, .level = 1, .contrib = {5, 5, 5}};
    a.hits[3] = (rt_hit_rec){.object = 1, .level = 2, .contrib = {90, 90, 90}};
    a.hits[4] = (rt_hit_rec){.object = 0, .level = 2, .contrib = {5, 5, 5}};
    memcpy(b.hits, a.hits, sizeof a.hits);
    assert_int_equal(ss_noise_seen(&c, k), 0); /* its parent is object 2 */
    a.hits[2].object = b.hits[2].object = 3;
    assert_int_equal(ss_noise_seen(&c, k), 1); /* now object 3 */
    /* a node only some corners have (a faint difference of the trees) is read where it is */
    b.nhits = 3;
    a.hits[3].contrib[0] = a.hits[3].contrib[1] = a.hits[3].contrib[2] = 20;
    assert_int_equal(ss_noise_seen(&c, k), 0);
}

/* A marble wall seen through a clear pane (a plane of index 1 that transmits everything and adds
 * no colour of its own): in full mode every pixel shows what it shows without the pane (its
 * refracted ray goes straight on), so the texture lies beyond the primary hit, where the noise
 * pixels (ss_noise) do not reach. Adaptive mode splits the squares whose corners agree there
 * (ss_noise_seen) and stays within the noise pixels' bound against full mode
 * (test_noise_pixels); interpolating the texture over those squares breaks it (measured: 89
 * levels, 130 pixels over 8). */
static void test_noise_beyond(void **state)
{
    (void)state;
    static rt_scene direct, pane;
    static uint32_t px_direct[H * W];
    scene_base(&direct);
    int mw = add_material(&direct,
                          (rt_material){.ambient = from_d(0.6),
                                        .tex = {.kind = RT_TEX_MARBLE,
                                                .palette = RT_PAL_MARBLE,
                                                .octaves = 4,
                                                .scale = from_d(0.9),
                                                .turbulence = from_d(1.2)}});
    rt_object *o = &direct.objects[direct.nobjects++];
    *o = (rt_object){.kind = RT_PLANE, .material = (uint8_t)mw};
    o->axis = vd(0, 0, 1);
    o->offset = from_d(-4);
    direct.lights[0].pos = vd(2, 4, -1); /* between the pane and the wall: no shadow */
    direct.camera = (rt_camera){vd(0, 1, 3), vd(0, 1, -4), vd(0, 1, 0), from_d(55)};
    pane = direct;
    int mp = add_material(&pane, (rt_material){.transmit = from_d(1), .ior = from_d(1)});
    o = &pane.objects[pane.nobjects++];
    *o = (rt_object){.kind = RT_PLANE, .material = (uint8_t)mp};
    o->axis = vd(0, 0, 1);
    o->offset = from_d(1);
    rt_scene_prepare(&direct);
    rt_scene_prepare(&pane);
    rt_view v;
    rt_view_init(&v, &direct.camera, W, H);
    const rt_params pf = {.depth = 4, .mode = RT_MODE_FULL, .footprint = 1};
    const rt_params pa = {
        .depth = 4, .mode = RT_MODE_ADAPTIVE, .grid = 8, .threshold = TS_THRESHOLD, .footprint = 1};
    rt_stats sd = {0}, sf = {0}, sa = {0};
    rt_render(&direct, &v, &pf, px_direct, W, &sd, NULL, NULL);
    rt_render(&pane, &v, &pf, fullpx, W, &sf, NULL, NULL);
    rt_render(&pane, &v, &pa, adpx, W, &sa, work, NULL);
    int o_p, o_a;
    const int w_p = frame_diff(fullpx, px_direct, &o_p), w_a = frame_diff(adpx, fullpx, &o_a);
    print_message("noise beyond a pane: full mode against no pane: worst %d levels; adaptive "
                  "against full: worst %d, %d over 8, %lu of %d points traced, %lu splits for "
                  "secondary rays\n",
                  w_p, w_a, o_a, (unsigned long)sa.rays_primary, W * H,
                  (unsigned long)sa.split_by[RT_SPLIT_SECONDARY]);
    assert_true(w_p <= 2);      /* the pane changes nothing but rounding */
    for (int y = 0; y < H; y++) /* and every primary ray meets it */
        for (int x = 0; x < W; x++) {
            rt_trace_pixel(&pane, &v, &pf, x, y, &sf, &full[y][x]);
            assert_int_equal(full[y][x].hits[0].object, pane.nobjects - 1);
        }
    const int bound_worst = 40, bound_over8 = W * H / 100;
    assert_true(sa.split_by[RT_SPLIT_SECONDARY] > 0);
    assert_true(w_a <= bound_worst && o_a <= bound_over8);
}

/* Shadow pixels: on the shadow of a sphere on a matte floor, lit by a second light as well,
 * adaptive mode fills the 2x2 and 4x4 squares on the shadow's edge from each corner's colour
 * unlit and lit (its own, and the other from the light's term there) with each pixel's own light
 * test instead of splitting them (ss_shadow). Every pixel stays within a few levels of full
 * mode's, and so do the pixels on either side of the edge, untraced ones included: a pixel on the
 * wrong side, or a wrong term, is off by the light's contrast, some 100 levels. Fewer points are
 * traced than with the edge split (a view whose eye is not the prepared one), and probe mode
 * fills them too. */
static void test_shadow_pixels(void **state)
{
    (void)state;
    static rt_scene s, split;
    shadow_scene(&s);
    s.lights[1] = (rt_light){vd(6, 8, 6), vd(0.3, 0.3, 0.35)};
    s.nlights = 2;
    rt_scene_prepare(&s);
    split = s;
    split.cull.eye_at.x =
        r_add(split.cull.eye_at.x, from_d(1)); /* views from the camera: not prepared */
    rt_view v;
    rt_view_init(&v, &s.camera, W, H);
    const rt_params pf = {.depth = s.depth, .mode = RT_MODE_FULL};
    rt_params pa = {
        .depth = s.depth, .mode = RT_MODE_ADAPTIVE, .grid = 8, .threshold = TS_THRESHOLD};
    rt_stats st = {0}, sa = {0}, ss = {0}, sp = {0};
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            rt_trace_pixel(&s, &v, &pf, x, y, &st, &full[y][x]);
    rt_render(&s, &v, &pf, fullpx, W, &st, NULL, NULL);
    rt_render(&split, &v, &pa, adpx, W, &ss, work, NULL);
    rt_render(&s, &v, &pa, adpx, W, &sa, work, traced);
    const int bound = 6;
    int over8, worst = frame_diff(adpx, fullpx, &over8), pairs = 0, untraced = 0, wrong = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x + 1 < W; x++) {
            /* neighbours that differ in light 0 alone, lit and unlit */
            const rt_sample *a = &full[y][x], *b = &full[y][x + 1];
            if (a->hits[0].object != b->hits[0].object || (a->lights ^ b->lights) != 1)
                continue;
            pairs++;
            for (int q = 0; q < 2; q++) {
                const int p = y * W + x + q;
                untraced += !traced[p];
                int m = 0;
                for (int ch = 0; ch < 24; ch += 8) {
                    const int d = abs((int)(adpx[p] >> ch & 255) - (int)(fullpx[p] >> ch & 255));
                    m = d > m ? d : m;
                }
                wrong += m > bound;
            }
        }
    print_message("shadow pixels: %lu points traced (%lu with the edge split), %lu squares filled "
                  "per pixel, %lu pixels tested; against full mode: worst %d levels, %d over 8; "
                  "%d edge pairs, %d of their pixels untraced, %d off by more than %d\n",
                  (unsigned long)sa.rays_primary, (unsigned long)ss.rays_primary,
                  (unsigned long)sa.shadow_squares, (unsigned long)sa.shadow_pixels, worst, over8,
                  pairs, untraced, wrong, bound);
    assert_int_equal(ss.shadow_squares, 0);
    assert_true(sa.shadow_squares > 0 && sa.shadow_pixels > 0);
    assert_true(pairs >= 40 && untraced * 4 >= pairs); /* the edge was filled, not traced */
    assert_int_equal(wrong, 0);                        /* every pixel on its own side */
    assert_true(worst <= bound);
    assert_true(sa.rays_primary * 5 <= ss.rays_primary * 4); /* fewer points traced */
    /* probe mode fills them too, within test_probe_shadow_edge's bound for its probes */
    pa.mode = RT_MODE_PROBE;
    rt_render(&s, &v, &pa, adpx, W, &sp, work, NULL);
    assert_true(sp.shadow_squares > 0);
    assert_true(frame_diff(adpx, fullpx, &over8) <= 32);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_criteria),
        cmocka_unit_test(test_centre_smooth),
        cmocka_unit_test(test_interpolate_gradient),
        cmocka_unit_test(test_interpolate_exact),
        cmocka_unit_test(test_object_edge),
        cmocka_unit_test(test_shadow_edge),
        cmocka_unit_test(test_reflected_outline),
        cmocka_unit_test(test_sizes),
        cmocka_unit_test(test_bands),
        cmocka_unit_test(test_bands_into),
        cmocka_unit_test(test_min_contrib),
        cmocka_unit_test(test_one_tone_checker),
        cmocka_unit_test(test_checker_cells),
        cmocka_unit_test(test_noise_pixels),
        cmocka_unit_test(test_noise_seen),
        cmocka_unit_test(test_noise_beyond),
        cmocka_unit_test(test_shadow_pixels),
        cmocka_unit_test(test_local_part),
        cmocka_unit_test(test_local_not_on_noise),
        cmocka_unit_test(test_adaptive_reference),
        cmocka_unit_test(test_probe_straight_edge),
        cmocka_unit_test(test_probe_shadow_edge),
        cmocka_unit_test(test_probe_reflected_edge),
        cmocka_unit_test(test_probe_point_edge),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
