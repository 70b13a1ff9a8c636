/* test_noise.c: Perlin noise, fBm and palettes of the build against the same formulas in double. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>

#include "noise.h"
#include "rt_local.h"

#if REAL_FIXED
static double to_d(real r) { return r / 65536.0; }
static real from_d(double x) { return (real)llround(x * 65536.0); }
#else
static double to_d(real r) { return r; }
static real from_d(double x) { return (real)x; }
#endif
/* Both builds evaluate the noise in the same integers: Q16.16 lattice coordinates (a float
 * coordinate rounded down to 2^-16 first: up to 3 x 2^-16 x |gradient| < 5e-5), fades within
 * 2 LSB, a rounding per interpolation: measured worst 4e-5 (fixed), 6e-5 (float). */
#define NOISE_TOL 1e-4
/* plus one rounding per octave, and in float the wrap of a negative coordinate (r + 256):
 * measured worst 6e-5 (fixed), 1.1e-4 (float) */
#define FBM_TOL 2e-4

/* The gradient set of src/core/noise.c (twelve cube edges, four repeated). */
static const int grad[16][3] = {
    {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
    {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}, {1, 1, 0}, {0, -1, 1}, {-1, 1, 0}, {0, -1, -1},
};

static double o_dot(int32_t i, int32_t j, int32_t k, double x, double y, double z)
{
    const int *g = grad[(rt_noise_hash(i, j, k) >> 8) & 15];
    return g[0] * x + g[1] * y + g[2] * z;
}

/* The integer noise as first written, step by step: the kernel in src/core/noise.c is a
 * rearranged form of it and must give exactly the same Q16.16 values. */
static int32_t ref_fade(uint32_t t)
{
    uint64_t t3 = ((uint64_t)t * t * t + 0x8000) >> 16;
    uint64_t inner = 10 * 65536 - (((uint64_t)t * (15 * 65536 - 6 * t) + 0x8000) >> 16);
    return (int32_t)((t3 * inner + 0x80000000u) >> 32);
}

static int32_t ref_lerp(int32_t a, int32_t b, int32_t t)
{
    return a + (int32_t)(((int64_t)(b - a) * t + 0x8000) >> 16);
}

static int32_t ref_dot(uint32_t i, uint32_t j, uint32_t k, int32_t x, int32_t y, int32_t z)
{
    const int *g = grad[(rt_noise_hash((int32_t)i, (int32_t)j, (int32_t)k) >> 8) & 15];
    return g[0] * x + g[1] * y + g[2] * z;
}

/* Noise at Q16.16 lattice coordinates in [0, 2^24). */
static int32_t ref_noise(uint32_t cx, uint32_t cy, uint32_t cz)
{
    uint32_t i = cx >> 16, j = cy >> 16, k = cz >> 16;
    int32_t x = (int32_t)(cx & 0xFFFF), y = (int32_t)(cy & 0xFFFF), z = (int32_t)(cz & 0xFFFF);
    int32_t x1 = x - 65536, y1 = y - 65536, z1 = z - 65536;
    int32_t u = ref_fade((uint32_t)x), v = ref_fade((uint32_t)y), w = ref_fade((uint32_t)z);
    int32_t a = ref_lerp(ref_dot(i, j, k, x, y, z), ref_dot(i + 1, j, k, x1, y, z), u);
    int32_t b = ref_lerp(ref_dot(i, j + 1, k, x, y1, z), ref_dot(i + 1, j + 1, k, x1, y1, z), u);
    int32_t c = ref_lerp(ref_dot(i, j, k + 1, x, y, z1), ref_dot(i + 1, j, k + 1, x1, y, z1), u);
    int32_t d =
        ref_lerp(ref_dot(i, j + 1, k + 1, x, y1, z1), ref_dot(i + 1, j + 1, k + 1, x1, y1, z1), u);
    return ref_lerp(ref_lerp(a, b, v), ref_lerp(c, d, v), w);
}

/* fBm / turbulence over `octaves` full octaves on the same lattice coordinates. */
static int32_t ref_octaves(uint32_t cx, uint32_t cy, uint32_t cz, int octaves, int absolute)
{
    int32_t sum = 0;
    for (int o = 0; o < octaves; o++) {
        int32_t n = ref_noise(cx, cy, cz);
        if (absolute && n < 0)
            n = -n;
        sum += (n + ((1 << o) >> 1)) >> o;
        cx = (cx << 1) & 0xFFFFFF, cy = (cy << 1) & 0xFFFFFF, cz = (cz << 1) & 0xFFFFFF;
    }
    return sum;
}

static double o_fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }

static double o_lerp(double a, double b, double t) { return a + (b - a) * t; }

static double o_noise(double px, double py, double pz)
{
    double fx = floor(px), fy = floor(py), fz = floor(pz);
    int32_t i = (int32_t)fx, j = (int32_t)fy, k = (int32_t)fz;
    double x = px - fx, y = py - fy, z = pz - fz;
    double u = o_fade(x), v = o_fade(y), w = o_fade(z);
    double a = o_lerp(o_dot(i, j, k, x, y, z), o_dot(i + 1, j, k, x - 1, y, z), u);
    double b = o_lerp(o_dot(i, j + 1, k, x, y - 1, z), o_dot(i + 1, j + 1, k, x - 1, y - 1, z), u);
    double c = o_lerp(o_dot(i, j, k + 1, x, y, z - 1), o_dot(i + 1, j, k + 1, x - 1, y, z - 1), u);
    double d = o_lerp(o_dot(i, j + 1, k + 1, x, y - 1, z - 1),
                      o_dot(i + 1, j + 1, k + 1, x - 1, y - 1, z - 1), u);
    return o_lerp(o_lerp(a, b, v), o_lerp(c, d, v), w);
}

static double o_wrap(double x)
{
    double r = fmod(x, RT_NOISE_PERIOD);
    return r < 0 ? r + RT_NOISE_PERIOD : r;
}

static double o_fbm(double x, double y, double z, int octaves)
{
    double sum = 0, amp = 1;
    x = o_wrap(x), y = o_wrap(y), z = o_wrap(z);
    for (int o = 0; o < octaves; o++) {
        sum += amp * o_noise(x, y, z);
        amp *= 0.5;
        x = o_wrap(2 * x), y = o_wrap(2 * y), z = o_wrap(2 * z);
    }
    return sum;
}

static uint32_t rng_state = 777;
static double rnd(double lo, double hi)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return lo + (hi - lo) * ((rng_state >> 8) / 16777216.0);
}

static void test_hash_period(void **state)
{
    (void)state;
    for (int i = -300; i < 300; i += 7)
        for (int j = -5; j < 5; j++) {
            assert_int_equal(rt_noise_hash(i, j, 3), rt_noise_hash(i + RT_NOISE_PERIOD, j, 3));
            assert_int_equal(rt_noise_hash(i, j, 3),
                             rt_noise_hash(i, j - RT_NOISE_PERIOD, 3 + RT_NOISE_PERIOD));
        }
    /* neighbouring lattice points get different gradients often enough */
    int same = 0;
    for (int i = 0; i < 256; i++)
        same += ((rt_noise_hash(i, 0, 0) >> 8) & 15) == ((rt_noise_hash(i + 1, 0, 0) >> 8) & 15);
    assert_true(same < 64);
}

static void test_noise_lattice_zero(void **state)
{
    (void)state;
    for (int i = -20; i <= 20; i += 3)
        assert_int_equal(rt_noise(v3(r_from_int(i), r_from_int(2 * i), r_from_int(-i))), 0);
}

static void test_noise_vs_double(void **state)
{
    (void)state;
    double worst = 0, lo = 0, hi = 0;
    fx_events_reset();
    for (int n = 0; n < 50000; n++) {
        /* most points near the origin, some anywhere in the scene range */
        double span = n % 10 == 0 ? 4000 : 50;
        vec3 p = v3(from_d(rnd(-span, span)), from_d(rnd(-span, span)), from_d(rnd(-span, span)));
        double want = o_noise(to_d(p.x), to_d(p.y), to_d(p.z));
        double got = to_d(rt_noise(p));
        double err = fabs(got - want);
        if (err > NOISE_TOL)
            fail_msg("noise(%g, %g, %g) = %g, double gives %g", to_d(p.x), to_d(p.y), to_d(p.z),
                     got, want);
        worst = err > worst ? err : worst;
        lo = got < lo ? got : lo;
        hi = got > hi ? got : hi;
    }
    print_message("noise: 50000 points, worst error %.3g, range [%.3f, %.3f]\n", worst, lo, hi);
    assert_true(lo > -1.1 && hi < 1.1);
    assert_true(lo < -0.5 && hi > 0.5); /* it does vary */
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW] + fx_event_count[FX_EV_DOMAIN], 0);
}

/* Its own generator, so that the other tests keep drawing the same points. */
static uint32_t rng_state_u32 = 4242;
static uint32_t rnd_u32(void)
{
    rng_state_u32 = rng_state_u32 * 1664525u + 1013904223u;
    uint32_t hi = rng_state_u32 >> 16;
    rng_state_u32 = rng_state_u32 * 1664525u + 1013904223u;
    return hi << 16 | rng_state_u32 >> 16;
}

/* A lattice coordinate: anywhere in [0, 2^24), or at the ends of a cell (fades at 0 and 1). */
static uint32_t rnd_coord(int n)
{
    uint32_t c = rnd_u32() & 0xFFFFFF;
    switch (n % 8) {
    case 0: return c & 0xFF0000;
    case 1: return c | 0xFFFF;
    case 2: return (c & 0xFF0000) | (c & 7);
    default: return c;
    }
}

static real coord_real(uint32_t c, int n)
{
    /* exact in both builds (24 bits); every other point from the negative side of the wrap */
    return r_from_q16(n & 1 ? (int32_t)c - (1 << 24) : (int32_t)c);
}

static void test_noise_vs_reference(void **state)
{
    (void)state;
    int32_t lo = 0, hi = 0;
    for (int n = 0; n < 400000; n++) {
        uint32_t cx = rnd_coord(n), cy = rnd_coord(n / 8), cz = rnd_coord(n / 64);
        vec3 p = v3(coord_real(cx, n), coord_real(cy, n / 2), coord_real(cz, n / 4));
        int32_t want = ref_noise(cx, cy, cz);
        real got = rt_noise(p);
        if (got != r_from_q16(want))
            fail_msg("noise at Q16.16 (%u, %u, %u): %.8g, the reference gives %d / 65536", cx, cy,
                     cz, (double)to_d(got), want);
        lo = want < lo ? want : lo;
        hi = want > hi ? want : hi;
    }
    print_message("noise = reference on 400000 lattice points, range [%d, %d] / 65536\n", lo, hi);
    assert_true(lo < -40000 && hi > 40000); /* the points reach well into both signs */
    for (int n = 0; n < 40000; n++) {
        uint32_t cx = rnd_coord(n), cy = rnd_coord(n + 3), cz = rnd_coord(n + 5);
        vec3 p = v3(coord_real(cx, n), coord_real(cy, n), coord_real(cz, n));
        int oct = 1 + n % RT_NOISE_MAX_OCTAVES;
        assert_true(rt_fbm(p, oct) == r_from_q16(ref_octaves(cx, cy, cz, oct, 0)));
        assert_true(rt_turbulence(p, oct) == r_from_q16(ref_octaves(cx, cy, cz, oct, 1)));
    }
}

static void test_noise_continuity(void **state)
{
    (void)state;
    /* |grad| of this noise is below 3, so a step of 1e-3 moves it by less than 3e-3 */
    for (int n = 0; n < 5000; n++) {
        double x = rnd(-20, 20), y = rnd(-20, 20), z = rnd(-20, 20);
        double a = to_d(rt_noise(v3(from_d(x), from_d(y), from_d(z))));
        double b = to_d(rt_noise(v3(from_d(x + 1e-3), from_d(y), from_d(z))));
        assert_true(fabs(a - b) < 3e-3 + 2 * NOISE_TOL);
    }
}

static void test_fbm_vs_double(void **state)
{
    (void)state;
    double worst = 0;
    fx_events_reset();
    for (int n = 0; n < 20000; n++) {
        int oct = 1 + n % RT_NOISE_MAX_OCTAVES;
        vec3 p = v3(from_d(rnd(-3000, 3000)), from_d(rnd(-300, 300)), from_d(rnd(-30, 30)));
        double want = o_fbm(to_d(p.x), to_d(p.y), to_d(p.z), oct);
        double got = to_d(rt_fbm(p, oct));
        double err = fabs(got - want);
        if (err > FBM_TOL)
            fail_msg("fbm(%g, %g, %g; %d) = %g, double gives %g", to_d(p.x), to_d(p.y), to_d(p.z),
                     oct, got, want);
        worst = err > worst ? err : worst;
    }
    print_message("fbm: 20000 points, 1-8 octaves, worst error %.3g\n", worst);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW] + fx_event_count[FX_EV_DOMAIN], 0);
}

/* The detail's level: octaves summed, the last counted by its weight (in 1/256 octave). */
static int32_t level(rt_noise_detail d)
{
    return d.octaves == 0 ? 0 : (d.octaves - 1) * RT_NOISE_WEIGHT_ONE + d.last;
}

static void test_detail_rule(void **state)
{
    (void)state;
    for (int oct = 1; oct <= RT_NOISE_MAX_OCTAVES; oct++) {
        /* no footprint, or one finer than the last octave: every octave in full */
        rt_noise_detail d = rt_noise_detail_for(0, oct);
        assert_true(d.octaves == oct && d.total == oct && d.last == RT_NOISE_WEIGHT_ONE);
        d = rt_noise_detail_for(from_d(ldexp(1.0, -(oct + 1))), oct);
        assert_true(d.octaves == oct && d.last == RT_NOISE_WEIGHT_ONE);
        /* a footprint of 1 (the first octave's wavelength) or more: none */
        assert_int_equal(rt_noise_detail_for(R_ONE, oct).octaves, 0);
        assert_int_equal(rt_noise_detail_for(R(300.0), oct).octaves, 0);
        assert_int_equal(rt_noise_detail_for(R(300.0), oct).total, oct);
    }
    /* At footprint 2^-k the first k octaves are summed in full; at 1.5 x 2^-k (the linear
     * reading of log2 between powers of two) the k-th is summed at half weight. */
    for (int k = 1; k <= RT_NOISE_MAX_OCTAVES; k++) {
        rt_noise_detail d = rt_noise_detail_for(from_d(ldexp(1.0, -k)), RT_NOISE_MAX_OCTAVES);
        assert_true(d.octaves == k && d.last == RT_NOISE_WEIGHT_ONE);
        d = rt_noise_detail_for(from_d(1.5 * ldexp(1.0, -k)), RT_NOISE_MAX_OCTAVES);
        assert_true(d.octaves == k && d.last == RT_NOISE_WEIGHT_ONE / 2);
    }
    /* The level never rises as the footprint grows, and it moves by small steps only (no
     * octave pops in or out): within 2/256 octave per step of 1/256 of the footprint. */
    int32_t prev = level(rt_noise_detail_for(R_LSB, RT_NOISE_MAX_OCTAVES));
    for (double f = ldexp(1.0, -12); f < 2; f *= 1.0 + 1.0 / 256) {
        int32_t l = level(rt_noise_detail_for(from_d(f), RT_NOISE_MAX_OCTAVES));
        assert_true(l <= prev && prev - l <= 2 + (f < ldexp(1.0, -8) ? 2 : 0));
        prev = l;
    }
    assert_int_equal(prev, 0);
}

static void test_detail_sum(void **state)
{
    (void)state;
    fx_events_reset();
    for (int n = 0; n < 5000; n++) {
        vec3 p = v3(from_d(rnd(-100, 100)), from_d(rnd(-100, 100)), from_d(rnd(-100, 100)));
        int oct = 1 + n % RT_NOISE_MAX_OCTAVES;
        int32_t w = 1 + (int32_t)rnd(0, RT_NOISE_WEIGHT_ONE);
        rt_noise_detail full = {oct, oct, RT_NOISE_WEIGHT_ONE}, part = {oct, oct, w};
        /* full weight: rt_fbm exactly */
        assert_int_equal(rt_fbm_detail(p, full), rt_fbm(p, oct));
        assert_int_equal(rt_turbulence_detail(p, full), rt_turbulence(p, oct));
        /* the last octave faded: between the sums without and with it, in proportion */
        double lo = to_d(rt_fbm(p, oct - 1)), hi = to_d(rt_fbm(p, oct));
        double want = lo + (hi - lo) * w / RT_NOISE_WEIGHT_ONE;
        assert_true(fabs(to_d(rt_fbm_detail(p, part)) - want) < 1e-4);
        /* turbulence: what is left out counts at the mean of |noise|, 0.2203 per octave */
        rt_noise_detail none = {0, oct, RT_NOISE_WEIGHT_ONE};
        double mean = 0.2203 * (2 - ldexp(1.0, 1 - oct));
        assert_true(fabs(to_d(rt_turbulence_detail(p, none)) - mean) < 1e-3);
        assert_true(rt_fbm_detail(p, none) == 0);
    }
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW] + fx_event_count[FX_EV_DOMAIN], 0);
}

static void test_palette(void **state)
{
    (void)state;
    for (int id = 0; id < RT_PAL_COUNT; id++) {
        vec3 a = rt_palette(id, 0), b = rt_palette(id, R_ONE);
        /* clamped outside [0, 1] */
        vec3 c = rt_palette(id, R(-3.0)), d = rt_palette(id, R(7.0));
        assert_true(a.x == c.x && a.y == c.y && a.z == c.z);
        assert_true(b.x == d.x && b.y == d.y && b.z == d.z);
        /* every colour stays in [0, 1] and changes smoothly */
        vec3 prev = a;
        for (int i = 1; i <= 100; i++) {
            vec3 e = rt_palette(id, r_from_ratio(i, 100));
            assert_true(to_d(e.x) >= 0 && to_d(e.x) <= 1 && to_d(e.y) >= 0 && to_d(e.z) <= 1);
            assert_true(fabs(to_d(e.x) - to_d(prev.x)) < 0.05);
            prev = e;
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hash_period),      cmocka_unit_test(test_noise_lattice_zero),
        cmocka_unit_test(test_noise_vs_double),  cmocka_unit_test(test_noise_vs_reference),
        cmocka_unit_test(test_noise_continuity), cmocka_unit_test(test_fbm_vs_double),
        cmocka_unit_test(test_detail_rule),      cmocka_unit_test(test_detail_sum),
        cmocka_unit_test(test_palette),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
