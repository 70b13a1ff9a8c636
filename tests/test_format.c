/* test_format.c: the fixed-point unit format a build was made with (FX_UNIT_FRAC), and its unit-vector operations against double in steps of that format. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>

#include "real.h"

#if !REAL_FIXED || !FX_COUNT_EVENTS
#error \
    "test_format checks the fixed-point formats: build it with -DREAL_FIXED=1 -DFX_COUNT_EVENTS=1"
#endif

/* One step of unit, and conversions to double. */
static const double lsb_u = 1.0 / (double)(1LL << FX_UNIT_FRAC);
static double u2d(unit a) { return a * lsb_u; }
static double r2d(real a) { return a / 65536.0; }
static real d2r(double x) { return (real)llround(x * 65536.0); }
static unit d2u(double x) { return (unit)llround(x / lsb_u); }

/* Largest errors allowed, in steps of unit (2^-FX_UNIT_FRAC) per component, over the cases
 * below; measured in comments. Q2.30: d3_ray truncates the pixel offsets to Q.28 (Q.28 - more on
 * frames wider than 4:1), d3_norm_near rounds 1/r. Refraction is counted in steps times
 * 1 + eta^2 / sqrt(k) (the square root near the critical angle). */
#if FX_UNIT_FRAC == 30
#define TOL_NORM_LSB 2.0    /* 0.73 */
#define TOL_NEAR_LSB 3.0    /* 2.34 */
#define TOL_RAY_LSB 8.0     /* 6.17 */
#define TOL_REFLECT_LSB 4.0 /* 2.80 */
#define TOL_REFRACT_LSB 3.0 /* 2.15 */
#else
#define TOL_NORM_LSB 2.0    /* 1.57 */
#define TOL_NEAR_LSB 2.0    /* 1.09 */
#define TOL_RAY_LSB 3.0     /* 1.84 */
#define TOL_REFLECT_LSB 4.0 /* 2.78 */
#define TOL_REFRACT_LSB 3.0 /* 1.39 */
#endif
/* Lengths from d3_norm: within 2 Q16.16 steps plus |v| 2^-(FX_UNIT_FRAC - 1), i.e. 2^-29 or
 * 2^-15 relative (measured: 0.41 of that for Q2.30, 0.65 for Q16.16). */
#define TOL_LEN(len) (2.0 / 65536.0 + (len)*2.0 * lsb_u)

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static uint32_t rng32(void)
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(rng_state >> 33);
}
/* Uniform in [-1, 1). */
static double rng_unit(void) { return rng32() / 1073741824.0 - 1.0; }

struct worst {
    const char *what;
    double lsb; /* the largest error seen, in steps of unit */
};

/* scale: the error is counted in units of scale steps of unit */
static void track_scaled(struct worst *w, double got, double want, double scale)
{
    double e = fabs(got - want) / lsb_u / scale;
    if (e > w->lsb)
        w->lsb = e;
}

static void track(struct worst *w, double got, double want)
{
    double e = fabs(got - want) / lsb_u;
    if (e > w->lsb)
        w->lsb = e;
}

static void report(const struct worst *w, double bound)
{
    printf("  %-16s worst %.2f steps of unit (bound %.1f)\n", w->what, w->lsb, bound);
    assert_true(w->lsb <= bound);
}

/* A random direction, as double and as the build's dir3. */
static void rand_dir(double e[3], dir3 *d)
{
    double n;
    do {
        e[0] = rng_unit(), e[1] = rng_unit(), e[2] = rng_unit();
        n = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    } while (n < 0.1 || n > 1.0);
    for (int i = 0; i < 3; i++)
        e[i] /= n;
    *d = (dir3){d2u(e[0]), d2u(e[1]), d2u(e[2])};
    /* the exact direction of what the build holds */
    double x = u2d(d->x), y = u2d(d->y), z = u2d(d->z);
    n = sqrt(x * x + y * y + z * z);
    e[0] = x / n, e[1] = y / n, e[2] = z / n;
}

static void test_constants(void **state)
{
    (void)state;
    printf("  unit_frac=%d U_ONE=%ld\n", FX_UNIT_FRAC, (long)U_ONE);
    assert_int_equal(U_ONE, (int64_t)1 << FX_UNIT_FRAC);
    assert_int_equal(U(0.5), (int64_t)1 << (FX_UNIT_FRAC - 1));
    assert_int_equal(U(-0.25), -((int64_t)1 << (FX_UNIT_FRAC - 2)));
    assert_int_equal(U_LSB, 1);
    assert_int_equal(u_to_real(U_ONE), R_ONE);
    assert_int_equal(u_to_real(U(0.75)), R(0.75));
    assert_int_equal(u_from_real(R(0.375)), U(0.375));
    assert_int_equal(u_mul(U(0.5), U(-0.5)), U(-0.25));
    assert_int_equal(u_mul(U_ONE, U_LSB), U_LSB);
    assert_int_equal(r_mul_u(R(3.0), U(0.5)), R(1.5));
    dir3 x = {U_ONE, 0, 0};
    assert_int_equal(d3_dot(x, x), U_ONE);
    real len = 0;
    dir3 d = d3_norm(v3(R(3.0), R(4.0), 0), &len);
    assert_int_equal(d.x, U(0.6));
    assert_int_equal(d.y, U(0.8));
    assert_int_equal(d.z, 0);
    assert_true(len >= R(5.0) - R_LSB && len <= R(5.0) + R_LSB);
    /* one step of unit, seen through a real: 2^-FX_UNIT_FRAC of 2^16 */
    assert_int_equal(r_mul_u(R(16384.0), U_LSB), (real)1 << (30 - FX_UNIT_FRAC));
}

static void test_norm(void **state)
{
    (void)state;
    struct worst wd = {"d3_norm", 0}, wn = {"d3_norm_near", 0};
    double wl = 0;
    fx_events_reset();
    for (int i = 0; i < 200000; i++) {
        /* components from one Q16.16 step to 30000, one of them often much smaller */
        double mag = ldexp(1.0, (int)(rng32() % 31) - 16);
        if (mag > 30000)
            mag = 30000;
        double e[3] = {rng_unit() * mag, rng_unit() * mag, rng_unit() * mag};
        if (i % 3 == 0)
            e[i % 2] *= 1e-4;
        vec3 v = v3(d2r(e[0]), d2r(e[1]), d2r(e[2]));
        if (v3_is_zero(v))
            continue;
        double x = r2d(v.x), y = r2d(v.y), z = r2d(v.z), n = sqrt(x * x + y * y + z * z);
        real len;
        dir3 d = d3_norm(v, &len);
        track(&wd, u2d(d.x), x / n);
        track(&wd, u2d(d.y), y / n);
        track(&wd, u2d(d.z), z / n);
        double le = fabs(r2d(len) - n);
        assert_true(le <= TOL_LEN(n));
        if (le / TOL_LEN(n) > wl)
            wl = le / TOL_LEN(n);
    }
    for (int i = 0; i < 100000; i++) {
        /* a point on a sphere (radius 1/128 .. 2048) minus its centre, rounded to Q16.16 */
        double r = ldexp(1.0, -7 + (int)(rng32() % 19)) * (1.0 + rng32() / 4294967296.0);
        double e[3];
        dir3 unused;
        rand_dir(e, &unused);
        vec3 v = v3(d2r(e[0] * r), d2r(e[1] * r), d2r(e[2] * r));
        double x = r2d(v.x), y = r2d(v.y), z = r2d(v.z), n = sqrt(x * x + y * y + z * z);
        dir3 d = d3_norm_near(v, r_inv_len(d2r(r)));
        track(&wn, u2d(d.x), x / n);
        track(&wn, u2d(d.y), y / n);
        track(&wn, u2d(d.z), z / n);
    }
    report(&wd, TOL_NORM_LSB);
    report(&wn, TOL_NEAR_LSB);
    printf("  d3_norm length   worst %.2f of its bound\n", wl);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
    assert_int_equal(fx_event_count[FX_EV_DOMAIN], 0);
}

/* Primary rays: a camera basis from d3_norm and d3_cross, the step from u_tan_step, pixels
 * across frames up to 4096 wide, against the same construction in double. */
static void test_rays(void **state)
{
    (void)state;
    struct worst w = {"d3_ray", 0};
    fx_events_reset();
    for (int c = 0; c < 2000; c++) {
        double ef[3], eu[3];
        dir3 f, up;
        rand_dir(ef, &f);
        rand_dir(eu, &up);
        real s;
        dir3 r = d3_cross(f, up, &s);
        if (r2d(s) < 0.05)
            continue;
        dir3 u = d3_cross(r, f, 0);
        int fov = 10 + (int)(rng32() % 111), h = 1 + (int)(rng32() % 4096),
            wd = 1 + (int)(rng32() % 4096);
        unit sn, cs;
        u_sincos_deg(r_shr(r_from_int(fov), 1), &sn, &cs);
        ustep step = u_tan_step(sn, cs, h);
        double stepd = step / 1073741824.0; /* ustep is Q2.30 in both fixed formats */
        for (int k = 0; k < 50; k++) {
            int ia = 2 * (int)(rng32() % (uint32_t)wd) + 1 - wd,
                ib = h - 2 * (int)(rng32() % (uint32_t)h) - 1;
            dir3 d = d3_ray(f, r, u, step, ia, ib);
            double a = stepd * ia, b = stepd * ib, v[3];
            v[0] = u2d(f.x) + u2d(r.x) * a + u2d(u.x) * b;
            v[1] = u2d(f.y) + u2d(r.y) * a + u2d(u.y) * b;
            v[2] = u2d(f.z) + u2d(r.z) * a + u2d(u.z) * b;
            double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            track(&w, u2d(d.x), v[0] / n);
            track(&w, u2d(d.y), v[1] / n);
            track(&w, u2d(d.z), v[2] / n);
        }
        /* the step itself: tan(fov / 2) / h to within the sine's and cosine's rounding */
        double t = tan(fov * 3.14159265358979323846 / 360.0) / h;
        assert_true(fabs(stepd - t) <= t * 4 * lsb_u / 0.08 + 1.0 / 1073741824.0);
    }
    report(&w, TOL_RAY_LSB);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
    assert_int_equal(fx_event_count[FX_EV_DOMAIN], 0);
}

static void test_reflect_refract(void **state)
{
    (void)state;
    struct worst wr = {"d3_reflect", 0}, wt = {"d3_refract/k", 0};
    fx_events_reset();
    for (int i = 0; i < 200000; i++) {
        double ed[3], en[3];
        dir3 d, n;
        rand_dir(ed, &d);
        rand_dir(en, &n);
        double dn = ed[0] * en[0] + ed[1] * en[1] + ed[2] * en[2];
        if (dn > 0) { /* the normal faces the incoming ray */
            for (int k = 0; k < 3; k++)
                en[k] = -en[k];
            n = d3_neg(n);
            dn = -dn;
        }
        dir3 m = d3_reflect(d, n);
        for (int k = 0; k < 3; k++)
            track(&wr, u2d(k == 0 ? m.x : k == 1 ? m.y : m.z), ed[k] - 2 * dn * en[k]);
        double eta = 1.0 / 3.0 + (rng32() % 8192) / 8192.0 * (3.0 - 1.0 / 3.0);
        real etar = d2r(eta);
        eta = r2d(etar);
        double cosi = -dn, k2 = 1 - eta * eta * (1 - cosi * cosi);
        dir3 t;
        int ok = d3_refract(d, n, etar, &t);
        if (fabs(k2) < 1e-3) /* total internal reflection or not: decided by rounding */
            continue;
        assert_int_equal(ok, k2 > 0);
        if (!ok)
            continue;
        double mm = eta * cosi - sqrt(k2), e[3];
        for (int k = 0; k < 3; k++)
            e[k] = eta * ed[k] + mm * en[k];
        double l = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
        /* near the critical angle the square root of k = 1 - eta^2 sin^2 magnifies k's
         * rounding (a few steps times eta^2) by 1 / (2 sqrt k): counted in those units */
        double scale = 1.0 + eta * eta / sqrt(k2);
        track_scaled(&wt, u2d(t.x), e[0] / l, scale);
        track_scaled(&wt, u2d(t.y), e[1] / l, scale);
        track_scaled(&wt, u2d(t.z), e[2] / l, scale);
    }
    report(&wr, TOL_REFLECT_LSB);
    report(&wt, TOL_REFRACT_LSB);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
    assert_int_equal(fx_event_count[FX_EV_DOMAIN], 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_constants),
        cmocka_unit_test(test_norm),
        cmocka_unit_test(test_rays),
        cmocka_unit_test(test_reflect_refract),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
