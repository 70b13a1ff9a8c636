/* test_numeric.c: the numeric layer (fixed/real.h) against a double oracle, saturation, events. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "real.h"
#include "rt_kernels.h"
#if REAL_FIXED
#include "fx_armv6m.h" /* the Cortex-M0's products, checked here against the host's */
#endif

#if !FX_COUNT_EVENTS
#error "test_numeric checks the event counters: build it with -DFX_COUNT_EVENTS=1"
#endif

#define PI_D 3.14159265358979323846

/* ---- conversions between the layer's types and double -------------------------------------- */

#if REAL_FIXED
#define LSB_R (1.0 / 65536.0)      /* Q16.16 */
#define LSB_U (1.0 / 1073741824.0) /* Q2.30 */
#define LSB_W (1.0 / 4294967296.0) /* Q32.32 */
static double clamp_d(double x, double lim) { return x > lim ? lim : (x < -lim ? -lim : x); }
static double r2d(real a) { return a / 65536.0; }
static double u2d(unit a) { return a / 1073741824.0; }
static double w2d(wide a) { return (double)a / 4294967296.0; }
static real d2r(double x) { return (real)clamp_d(round(x * 65536.0), INT32_MAX); }
static unit d2u(double x) { return (unit)clamp_d(round(x * 1073741824.0), INT32_MAX); }
static wide d2w(double x) { return (wide)clamp_d(round(x * 4294967296.0), 9.2e18); }
/* What an exact result becomes after saturation. */
static double sat_r(double x) { return clamp_d(x, INT32_MAX / 65536.0); }
static double sat_u(double x) { return clamp_d(x, INT32_MAX / 1073741824.0); }
#else
#define LSB_R 0.0 /* no fixed step: errors are shown in absolute terms only */
#define LSB_U 0.0
#define LSB_W 0.0
static double r2d(real a) { return a; }
static double u2d(unit a) { return a; }
static double w2d(wide a) { return a; }
static real d2r(double x) { return (real)x; }
static unit d2u(double x) { return (unit)x; }
static wide d2w(double x) { return (wide)x; }
static double sat_r(double x) { return x; }
static double sat_u(double x) { return x; }
#endif

/* ---- tolerances: |got - expected| <= abs + rel * scale (scale is usually |expected|) --------- */

struct tol {
    double abs, rel;
};

#if REAL_FIXED
/* Results the layer computes exactly (add, sub, neg, abs, saturation, shifts of raw values...). */
static const struct tol TOL_EXACT = {0.0, 0.0};
/* Additions and other results that are exact in fixed point but rounded once in float. */
static const struct tol TOL_ADD = {0.0, 0.0};
/* One rounding to nearest in Q16.16: mul, div, sqrt, hypot, mul_u, div_u, shr, dot products.
 * (The 1e-6 LSB of slack only absorbs the double oracle's own rounding at exact ties.) */
static const struct tol TOL_R_ROUND = {0.500001 * LSB_R, 0.0};
/* v3_dot_d: the sum is exact in 64 bits and rounded once (scale: sum of |v_i d_i|). */
static const struct tol TOL_DOT = {0.500001 * LSB_R, 0.0};
/* r_div: libfixmath's fix16_div (third-party code, not this layer): for |b| >= 16 its first
 * estimate truncates, and the result can be off by slightly more than half a step (0.53 LSB
 * measured). */
static const struct tol TOL_R_DIV = {1.0 * LSB_R, 0.0};
/* One rounding to nearest in Q2.30: u_mul, u_divi, u_div, d3_dot. */
static const struct tol TOL_U_ROUND = {0.500001 * LSB_U, 0.0};
/* Q32.32 squares: exact in 64 bits; the double oracle itself rounds at 2^-53. */
static const struct tol TOL_WIDE = {0.0, 0x1p-52};
/* libfixmath's sine on [-pi/2, pi/2] plus the folding by R_PI (205887, pi rounded down by
 * 0.42 LSB): 2.67 LSB = 4.1e-5 at worst over every step of [-2 pi, 2 pi]. */
static const struct tol TOL_SIN = {3.0 * LSB_R, 0.0};
/* The reduction modulo 2 pi happens in Q.32 and is exact to 2^-33 per turn: the error does
 * not grow with |a| beyond the final rounding of the reduced angle. */
static const double TOL_SIN_PER_RAD = 0.0;
/* u_sincos_deg: documented as about 2e-9; exact at multiples of 90 degrees. */
static const struct tol TOL_SINCOS_DEG = {1e-8, 0.0};
static const double TOL_SINCOS_AXIS = 0.0;
/* u_pow(b, n): at most one Q2.30 rounding per multiplication, none amplified: n LSB. */
static const struct tol TOL_POW_PER_STEP = {LSB_U, 0.0};
/* Unit vectors from normalisation (d3_norm, fx_norm64, fx_renorm, d3_reflect). */
static const struct tol TOL_NORM = {0x1p-28, 0.0};
/* d3_cross: the products are exact, so only the normalisation rounds (scale: 1 / |a x b|). */
static const struct tol TOL_CROSS = {0x1p-28, 0.0};
/* Lengths from normalisation: the isqrt rounding plus the bits dropped from large inputs. */
static const struct tol TOL_NORM_LEN = {0.5 * LSB_R, 0x1p-28};
/* d3_ray: the pixel offset is truncated to Q.28 before normalising. */
static const struct tol TOL_RAY = {0x1p-27, 0.0};
/* d3_refract: eta^2 and sin^2 are truncated to Q.30 / Q.28 before k = 1 - eta^2 sin^2 t; the
 * square root of k amplifies that error by 1 / (2 sqrt k) (scale: eta^2 / sqrt k). */
static const struct tol TOL_REFRACT = {0x1p-27, 0x1p-29};
/* r_to_byte: exact (integer rounding of c * 255 + 0.5). */
static const double TOL_BYTE = 0.0;
#else
static const struct tol TOL_EXACT = {0.0, 0.0};
static const struct tol TOL_ADD = {0.0, 0x1p-23};
/* One float rounding, relative to the result. */
static const struct tol TOL_R_ROUND = {0.0, 0x1p-23};
static const struct tol TOL_R_DIV = {0.0, 0x1p-23};
/* three products and two sums, each rounded: 1.5 ulp of the sum of magnitudes at most */
static const struct tol TOL_DOT = {0.0, 0x1p-22};
static const struct tol TOL_U_ROUND = {0.0, 0x1p-23};
/* Sums of float products: relative to the sum of magnitudes. */
static const struct tol TOL_WIDE = {0.0, 0x1p-22};
/* sinf is within an ulp or so. */
static const struct tol TOL_SIN = {0x1p-23, 0.0};
static const double TOL_SIN_PER_RAD = 0.0;
/* R_PI rounded to float is 8.7e-8 off pi: 1.7e-7 at 360 degrees, plus sinf's own rounding. */
static const struct tol TOL_SINCOS_DEG = {4e-7, 0.0};
static const double TOL_SINCOS_AXIS = 4e-7;
/* relative to the result, per multiplication; the absolute part covers underflowing powers */
static const struct tol TOL_POW_PER_STEP = {0x1p-60, 0x1p-23};
static const struct tol TOL_NORM = {0x1p-21, 0.0};
/* the products cancel in float: the error grows as 1 / |a x b| */
static const struct tol TOL_CROSS = {0x1p-21, 0x1p-22};
static const struct tol TOL_NORM_LEN = {0.0, 0x1p-22};
static const struct tol TOL_RAY = {0x1p-21, 0.0};
static const struct tol TOL_REFRACT = {0x1p-21, 0x1p-22};
/* c * 255.0f + 0.5f is rounded in float and may cross a .5 boundary. */
static const double TOL_BYTE = 1.0;
#endif

static double tol_at(struct tol t, double scale) { return t.abs + t.rel * fabs(scale); }

/* ---- checking helpers ------------------------------------------------------------------------ */

static int n_failed; /* failed checks in the current test */

#ifdef TEST_NUMERIC_REPORT
/* Debug runs only (-DTEST_NUMERIC_REPORT): the largest error seen per operation. */
static struct {
    const char *op;
    double err, lsb;
} worst[96];
static int n_worst;

static void note_error(const char *op, double err, double lsb)
{
    int i = 0;
    while (i < n_worst && strcmp(worst[i].op, op) != 0)
        i++;
    if (i == n_worst) {
        if (n_worst == (int)(sizeof worst / sizeof worst[0]))
            return;
        worst[n_worst].op = op;
        worst[n_worst].err = 0;
        worst[n_worst].lsb = lsb;
        n_worst++;
    }
    if (err > worst[i].err)
        worst[i].err = err;
}

static int print_worst(void **state)
{
    (void)state;
    for (int i = 0; i < n_worst; i++) {
        if (worst[i].lsb > 0)
            printf("worst %-22s %.3g (%.3f LSB)\n", worst[i].op, worst[i].err,
                   worst[i].err / worst[i].lsb);
        else
            printf("worst %-22s %.3g\n", worst[i].op, worst[i].err);
    }
    return 0;
}
#endif

/* Compares one result; on failure prints the operation, its inputs (fmt), expected, got and the
 * error (also in LSB of the result type when lsb > 0), and counts the failure. */
static void vcheck(const char *op, double lsb, double expected, double got, double tol,
                   const char *fmt, va_list ap)
{
    double err = fabs(got - expected);
#ifdef TEST_NUMERIC_REPORT
    note_error(op, err, lsb);
#endif
    if (err <= tol)
        return;
    char args[256];
    vsnprintf(args, sizeof args, fmt, ap);
    n_failed++;
    if (lsb > 0)
        print_error("%s(%s): expected %.12g, got %.12g, error %.4g (%.2f LSB) > tolerance %.4g\n",
                    op, args, expected, got, err, err / lsb, tol);
    else
        print_error("%s(%s): expected %.12g, got %.12g, error %.4g > tolerance %.4g\n", op, args,
                    expected, got, err, tol);
}

/* A real result. */
__attribute__((format(printf, 5, 6))) static void check_r(const char *op, double expected, real got,
                                                          double tol, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vcheck(op, LSB_R, expected, r2d(got), tol, fmt, ap);
    va_end(ap);
}

/* A unit result. */
__attribute__((format(printf, 5, 6))) static void check_u(const char *op, double expected, unit got,
                                                          double tol, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vcheck(op, LSB_U, expected, u2d(got), tol, fmt, ap);
    va_end(ap);
}

/* A wide result. */
__attribute__((format(printf, 5, 6))) static void check_w(const char *op, double expected, wide got,
                                                          double tol, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vcheck(op, LSB_W, expected, w2d(got), tol, fmt, ap);
    va_end(ap);
}

/* An integer result (or any plain number). */
__attribute__((format(printf, 5, 6))) static void check_i(const char *op, double expected,
                                                          double got, double tol, const char *fmt,
                                                          ...)
{
    va_list ap;
    va_start(ap, fmt);
    vcheck(op, 1.0, expected, got, tol, fmt, ap);
    va_end(ap);
}

/* Per-test set-up: a test that stopped at an assertion must not leave its count behind. */
static int reset_checks(void **state)
{
    (void)state;
    n_failed = 0;
    return 0;
}

/* Ends a test: fails it when any check failed (each was printed above). */
static void checks_done(void)
{
    int n = n_failed;
    n_failed = 0;
    if (n)
        fail_msg("%d check(s) out of tolerance", n);
}

/* Event counts since the last fx_events_reset(), compared with the expected ones. */
static void check_events(const char *what, unsigned long overflow, unsigned long domain)
{
    if (fx_event_count[FX_EV_OVERFLOW] != overflow || fx_event_count[FX_EV_DOMAIN] != domain) {
        n_failed++;
        print_error("%s: events overflow=%lu domain=%lu, expected overflow=%lu domain=%lu\n", what,
                    fx_event_count[FX_EV_OVERFLOW], fx_event_count[FX_EV_DOMAIN], overflow, domain);
    }
}

/* A deterministic pseudo-random stream (xorshift64*). */
static uint64_t rng_state = 0x9E3779B97F4A7C15u;
static uint64_t rng(void)
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return rng_state * 0x2545F4914F6CDD1Du;
}

/* A uniform double in [0, 1). */
static double rng_unit(void) { return (double)(rng() >> 11) * 0x1p-53; }

/* A real of random sign with magnitude log-uniform in [2^lo, 2^hi). */
static real rng_real(int lo, int hi)
{
    double m = ldexp(1.0 + rng_unit(), lo + (int)(rng() % (uint64_t)(hi - lo)));
    return d2r(rng() & 1 ? -m : m);
}

/* ---- tables of edge cases -------------------------------------------------------------------- */

static const real edge_r[] = {
    0,          R_LSB,      -R_LSB,      2 * R_LSB,    R(0.0001), R(-0.001),     R(0.5),
    R(-0.5),    R_ONE,      -R_ONE,      R(1.5),       R(-2.75),  R(3.0),        R(100.25),
    R(181.0),   R(-181.0),  R(181.02),   R(182.0),     R(-182.0), R(-1234.5678), R(4096.0),
    R(-4096.0), R(16384.0), R(32767.99), R(-32767.99), R_MAX,     -R_MAX,
};
#define N_EDGE_R ((int)(sizeof edge_r / sizeof edge_r[0]))

static const unit edge_u[] = {
    0,
    U_LSB,
    -U_LSB,
    U(1e-6),
    U(0.5),
    U(-0.5),
    U_ONE,
    -U_ONE,
    U(0.70710678118654752),
    U(-0.70710678118654752),
    U(0.333333333333),
    U(-0.1),
    U(1.5),
    U(-1.5),
    U(1.999999999),
    U(-1.999999999),
};
#define N_EDGE_U ((int)(sizeof edge_u / sizeof edge_u[0]))

/* Position-like vectors, from single steps to the edge of the range. */
static const vec3 edge_v[] = {
    {R(1.0), 0, 0},
    {0, R(-1.0), 0},
    {0, 0, R(7.0)},
    {R(3.0), R(4.0), 0},
    {R(0.01), R(0.005), 0},
    {R(0.001), R(0.002), R(-0.003)},
    {R_LSB, 0, 0},
    {R_LSB, R_LSB, R_LSB},
    {R_LSB, -R_LSB, 0},
    {-R_LSB, 0, 2 * R_LSB},
    {R(0.25), R(-0.5), R(0.125)},
    {R(181.0), R(182.0), R(-181.0)},
    {R(200.0), R(100.0), 0},
    {R(1234.5), R(-0.001), R(77.7)},
    {R(4096.0), R(-4096.0), R(4096.0)},
    {R(8191.0), R(-3.0), R(8191.0)},
};
#define N_EDGE_V ((int)(sizeof edge_v / sizeof edge_v[0]))

/* Direction vectors, given unnormalised. */
static const double edge_dirs[][3] = {
    {1, 0, 0},           {0, 1, 0},     {0, 0, -1},       {1, 1, 1},
    {1, -2, 3},          {0.6, 0.8, 0}, {-0.28, 0.96, 0}, {1e-4, 1, 0},
    {0.3, -0.4, -0.866}, {-5, -1, 2},   {1, 1e-6, 1e-6},  {-0.5, 0.5, -0.70710678},
};
#define N_EDGE_D ((int)(sizeof edge_dirs / sizeof edge_dirs[0]))

/* The unit vector along (x, y, z), rounded to the unit type. */
static dir3 dir_from(const double *v)
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    dir3 d = {d2u(v[0] / l), d2u(v[1] / l), d2u(v[2] / l)};
    return d;
}

static double dd_dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void dd_from_dir(dir3 d, double *out)
{
    out[0] = u2d(d.x);
    out[1] = u2d(d.y);
    out[2] = u2d(d.z);
}

static void dd_from_vec(vec3 v, double *out)
{
    out[0] = r2d(v.x);
    out[1] = r2d(v.y);
    out[2] = r2d(v.z);
}

/* Checks a unit vector against the normalised double vector e (tolerance per component). */
static void check_dir(const char *op, const double *e, dir3 got, double tol, const char *what)
{
    double l = sqrt(dd_dot(e, e));
    check_u(op, e[0] / l, got.x, tol, "%s: x", what);
    check_u(op, e[1] / l, got.y, tol, "%s: y", what);
    check_u(op, e[2] / l, got.z, tol, "%s: z", what);
}

/* ---- scalars --------------------------------------------------------------------------------- */

static void test_real_arithmetic(void **state)
{
    (void)state;
    for (int i = 0; i < N_EDGE_R; i++) {
        real a = edge_r[i];
        double x = r2d(a);
        check_r("r_neg", sat_r(-x), r_neg(a), tol_at(TOL_EXACT, x), "%.9g", x);
        check_r("r_abs", sat_r(fabs(x)), r_abs(a), tol_at(TOL_EXACT, x), "%.9g", x);
        check_r("r_sqrt", x < 0 ? 0.0 : sqrt(x), r_sqrt(a), tol_at(TOL_R_ROUND, sqrt(fabs(x))),
                "%.9g", x);
        for (int j = 0; j < N_EDGE_R; j++) {
            real b = edge_r[j];
            double y = r2d(b);
            check_r("r_add", sat_r(x + y), r_add(a, b), tol_at(TOL_ADD, x + y), "%.9g, %.9g", x, y);
            check_r("r_sub", sat_r(x - y), r_sub(a, b), tol_at(TOL_ADD, x - y), "%.9g, %.9g", x, y);
            check_r("r_mul", sat_r(x * y), r_mul(a, b), tol_at(TOL_R_ROUND, x * y), "%.9g, %.9g", x,
                    y);
            if (b != 0)
                check_r("r_div", sat_r(x / y), r_div(a, b), tol_at(TOL_R_DIV, x / y), "%.9g, %.9g",
                        x, y);
            check_r("r_hypot", sat_r(hypot(x, y)), r_hypot(a, b), tol_at(TOL_R_ROUND, hypot(x, y)),
                    "%.9g, %.9g", x, y);
            check_r("r_clamp", fmin(fmax(x, -fabs(y)), fabs(y)), r_clamp(a, -r_abs(b), r_abs(b)),
                    0.0, "%.9g, %.9g, %.9g", x, -fabs(y), fabs(y));
        }
    }
    /* A random sweep over all magnitudes. */
    for (int k = 0; k < 20000; k++) {
        real a = rng_real(-16, 15), b = rng_real(-16, 15);
        double x = r2d(a), y = r2d(b);
        check_r("r_mul", sat_r(x * y), r_mul(a, b), tol_at(TOL_R_ROUND, x * y), "%.9g, %.9g", x, y);
        check_r("r_div", sat_r(x / y), r_div(a, b), tol_at(TOL_R_DIV, x / y), "%.9g, %.9g", x, y);
        check_r("r_sqrt", sqrt(fabs(x)), r_sqrt(r_abs(a)), tol_at(TOL_R_ROUND, sqrt(fabs(x))),
                "%.9g", fabs(x));
        check_r("r_hypot", sat_r(hypot(x, y)), r_hypot(a, b), tol_at(TOL_R_ROUND, hypot(x, y)),
                "%.9g, %.9g", x, y);
    }
    /* Exact cases. */
    assert_true(r_mul(R(0.5), R(0.5)) == R(0.25));
    assert_true(r_div(R(1.0), R(4.0)) == R(0.25));
    assert_true(r_sqrt(R(4.0)) == R(2.0));
    assert_true(r_sqrt(R(0.0)) == 0);
    assert_true(r_hypot(R(3.0), R(-4.0)) == R(5.0));
    assert_true(r_lerp(R(2.0), R(6.0), R(0.25)) == R(3.0));
    checks_done();
}

/* r_mod_pow2 must be bit for bit r_mod (in the float build also the sign of a zero result):
 * x itself and x's nearest multiples of each power-of-two modulus. */
static void check_mod_pow2(real x)
{
    static const double mods[] = {0.5, 1.0, 2.0, 256.0};
    for (int k = 0; k < (int)(sizeof mods / sizeof mods[0]); k++) {
        real m = d2r(mods[k]);
        for (int j = 0; j < 3; j++) {
            real a = x;
            if (j > 0) { /* a multiple of m next to x, and just below it */
                double q = floor(r2d(x) / mods[k]) * mods[k];
                if (q < -30000.0 || q > 30000.0)
                    continue;
                a = d2r(q);
                if (j == 2)
                    a = r_sub(a, R_LSB);
            }
            real want = r_mod(a, m), got = r_mod_pow2(a, m);
            if (memcmp(&want, &got, sizeof want) != 0) {
                n_failed++;
                print_error("r_mod_pow2(%.9g, %g) = %.9g, r_mod gives %.9g\n", r2d(a), mods[k],
                            r2d(got), r2d(want));
            }
            /* r_mod_pow2_twice on that wrapped value: r_mod_pow2 of its double */
            real w2 = r_mod_pow2(r_muli(got, 2), m), g2 = r_mod_pow2_twice(got, m);
            if (memcmp(&w2, &g2, sizeof w2) != 0) {
                n_failed++;
                print_error("r_mod_pow2_twice(%.9g, %g) = %.9g, want %.9g\n", r2d(got), mods[k],
                            r2d(g2), r2d(w2));
            }
        }
    }
}

static void test_real_conversions(void **state)
{
    (void)state;
    static const int32_t ints[] = {0,     1,      -1,    2,      181,   -182,   4096,
                                   32767, -32767, 32768, -32768, 40000, -100000};
    for (int i = 0; i < (int)(sizeof ints / sizeof ints[0]); i++)
        check_r("r_from_int", sat_r(ints[i]), r_from_int(ints[i]), 0.0, "%d", (int)ints[i]);

    for (int i = 0; i < N_EDGE_R; i++) {
        double x = r2d(edge_r[i]);
        check_i("r_to_int", floor(x + 0.5), r_to_int(edge_r[i]), 0.0, "%.9g", x);
    }
    /* halves round up */
    static const double halves[] = {0.5, -0.5, 1.5, -1.5, 2.5, -2.5, 0.49999, -0.50001, 181.5};
    for (int i = 0; i < (int)(sizeof halves / sizeof halves[0]); i++) {
        real a = d2r(halves[i]);
        check_i("r_to_int", floor(r2d(a) + 0.5), r_to_int(a), 0.0, "%.9g", r2d(a));
    }

    static const int32_t ratios[][2] = {
        {1, 3},      {-1, 3},      {2, 3},      {-2, 3},    {1, 2},      {-1, 2},
        {1, 131072}, {-1, 131072}, {3, 131072}, {7, 640},   {-319, 640}, {32767, 1},
        {100000, 2}, {-100000, 2}, {0, 5},      {479, 480}, {1, 65537}};
    for (int i = 0; i < (int)(sizeof ratios / sizeof ratios[0]); i++) {
        int32_t n = ratios[i][0], d = ratios[i][1];
        double q = (double)n / d;
        check_r("r_from_ratio", sat_r(q), r_from_ratio(n, d), tol_at(TOL_R_ROUND, q), "%d, %d",
                (int)n, (int)d);
    }

    for (int i = 0; i < N_EDGE_R; i++) {
        real a = edge_r[i];
        double x = r2d(a);
        for (int n = 1; n <= 20; n++) {
            double q = ldexp(x, -n);
            check_r("r_shr", q, r_shr(a, n), tol_at(TOL_R_ROUND, q), "%.9g, %d", x, n);
        }
        static const int32_t mults[] = {0, 1, 2, 3, 255, 1000};
        for (int k = 0; k < (int)(sizeof mults / sizeof mults[0]); k++) {
            double p = x * mults[k];
            check_r("r_muli", sat_r(p), r_muli(a, mults[k]), tol_at(TOL_ADD, p), "%.9g, %d", x,
                    (int)mults[k]);
        }
        /* floor and fraction */
        int32_t ip = 12345;
        real f = r_floor_split(a, &ip);
        check_i("r_floor_split:int", floor(x), ip, 0.0, "%.9g", x);
        check_r("r_floor_split:frac", x - floor(x), f, tol_at(TOL_ADD, 1.0), "%.9g", x);
        /* modulo */
        static const double mods[] = {1.0, 0.5, 2.5, 360.0, 1000.0};
        for (int k = 0; k <= (int)(sizeof mods / sizeof mods[0]); k++) {
            real m = k < (int)(sizeof mods / sizeof mods[0]) ? d2r(mods[k]) : 3 * R_LSB;
            double md = r2d(m), e = fmod(x, md);
            if (e < 0)
                e += md;
            check_r("r_mod", e, r_mod(a, m), tol_at(TOL_ADD, md), "%.9g, %.9g", x, md);
        }
        check_mod_pow2(a);
        /* r_mul_sign: exactly the selection g > 0 ? a : g < 0 ? r_neg(a) : 0, bit for bit */
        for (int g = -1; g <= 1; g++) {
            real want = g > 0 ? a : (g < 0 ? r_neg(a) : 0), got = r_mul_sign(a, g);
            if (memcmp(&want, &got, sizeof want) != 0) {
                n_failed++;
                print_error("r_mul_sign(%.9g, %d) = %.9g, want %.9g\n", r2d(a), g, r2d(got),
                            r2d(want));
            }
        }
    }
    for (int k = 0; k < 200000; k++)
        check_mod_pow2(k < 100000 ? rng_real(-16, 14) : rng_real(-40, 14));
#if !REAL_FIXED
    /* the float build's extremes: subnormals (x / m underflows) and the largest values */
    for (int k = 0; k < 2000; k++) {
        float x = ldexpf(1.0f + (float)rng_unit(), -150 + (int)(rng() % 40)) * (k & 1 ? -1 : 1);
        check_mod_pow2(k % 100 == 99 ? ldexpf(x, 200) : x);
        /* r_shr: the same bits as ldexpf, subnormal results included */
        for (int n = 0; n < 40; n += 1 + n / 8) {
            float want = ldexpf(x, -n), got = r_shr(x, n);
            if (memcmp(&want, &got, sizeof want) != 0) {
                n_failed++;
                print_error("r_shr(%g, %d) = %g, ldexpf gives %g\n", (double)x, n, (double)got,
                            (double)want);
            }
        }
    }
    /* r_floor_split: the same bits as floorf and x - floorf(x) (on x86-64 it forms the floor
     * from the truncated integer): signed zeros, (-1, 0), integers, 2^23 and the int32 ends */
    static const float fl[] = {
        0.0f,       -0.0f,       0.5f,          -0.5f,          1e-30f,        -1e-30f,
        1.0f,       -1.0f,       -3.0f,         -2.75f,         8388607.5f,    -8388607.5f,
        8388608.0f, -8388609.0f, 2147483520.0f, -2147483520.0f, -2147483648.0f};
    for (int k = 0; k < (int)(sizeof fl / sizeof fl[0]) + 200000; k++) {
        const float x = k < (int)(sizeof fl / sizeof fl[0])
            ? fl[k]
            : ldexpf((float)rng_unit(), (int)(rng() % 31)) * (k & 1 ? -1 : 1);
        const float want_i = floorf(x), want_f = x - want_i;
        int32_t got_i = 0;
        const float got_f = r_floor_split(x, &got_i);
        if (got_i != (int32_t)want_i || memcmp(&got_f, &want_f, sizeof got_f) != 0) {
            n_failed++;
            print_error("r_floor_split(%.9g) = %d, %.9g; floorf gives %.9g, %.9g\n", (double)x,
                        (int)got_i, (double)got_f, (double)want_i, (double)want_f);
        }
    }
#endif
    for (int k = 0; k < 5000; k++) {
        real a = rng_real(-16, 15);
        double x = r2d(a);
        int32_t ip = 0;
        real f = r_floor_split(a, &ip);
        check_i("r_floor_split:int", floor(x), ip, 0.0, "%.9g", x);
        check_r("r_floor_split:frac", x - floor(x), f, tol_at(TOL_ADD, 1.0), "%.9g", x);
    }

    /* lerp and clamp on moderate values (b - a must not saturate) */
    static const double lv[] = {0, 1, -1, 0.5, 181, -182, 1000, -2.75};
    static const double lt[] = {0, 1, 0.5, 0.25, 0.999, 2, -1, 1.0 / 3.0};
    for (int i = 0; i < 8; i++)
        for (int j = 0; j < 8; j++)
            for (int k = 0; k < 8; k++) {
                real a = d2r(lv[i]), b = d2r(lv[j]), t = d2r(lt[k]);
                double x = r2d(a), y = r2d(b), tt = r2d(t), e = x + (y - x) * tt;
                check_r("r_lerp", e, r_lerp(a, b, t),
                        tol_at(TOL_R_ROUND, fabs(x) + fabs(y - x) * fabs(tt)), "%.9g, %.9g, %.9g",
                        x, y, tt);
            }
    assert_true(r_clamp(R(5.0), R(0.0), R(1.0)) == R(1.0));
    assert_true(r_clamp(R(-5.0), R(0.0), R(1.0)) == R(0.0));
    assert_true(r_clamp(R(0.25), R(0.0), R(1.0)) == R(0.25));
    assert_true(r_min(R(-1.0), R(2.0)) == R(-1.0));
    assert_true(r_max(R(-1.0), R(2.0)) == R(2.0));
    checks_done();
}

static void test_to_byte(void **state)
{
    (void)state;
    assert_int_equal(r_to_byte(0), 0);
    assert_int_equal(r_to_byte(R_ONE), 255);
    assert_int_equal(r_to_byte(R(0.5)), 128);
    assert_int_equal(r_to_byte(R(-0.5)), 0);
    assert_int_equal(r_to_byte(-R_MAX), 0);
    assert_int_equal(r_to_byte(R(1.5)), 255);
    assert_int_equal(r_to_byte(R_MAX), 255);
    assert_int_equal(r_to_byte(R(0.25)), 64); /* 63.75 */
    assert_int_equal(r_to_byte(R(0.51 / 255)), 1);
    assert_int_equal(r_to_byte(R(0.49 / 255)), 0);
    assert_int_equal(r_to_byte(R(254.51 / 255)), 255);
    assert_int_equal(r_to_byte(R(254.49 / 255)), 254);
    /* every step of [0, 1] (Q16.16 has 65537 of them) */
    for (int32_t k = -2; k <= 65538; k++) {
        real c = r_from_ratio(k, 65536);
        double x = r2d(c), e = x <= 0 ? 0 : (x >= 1 ? 255 : floor(x * 255 + 0.5));
        check_i("r_to_byte", e, r_to_byte(c), TOL_BYTE, "%.9g", x);
    }
    checks_done();
}

/* ---- saturation and events ------------------------------------------------------------------- */

/* Domain errors: defined results and a DOMAIN event in both builds. */
static void test_domain_events(void **state)
{
    (void)state;
    real len = R(9.0);
    fx_events_reset();
    assert_true(r_div(R(3.0), 0) == R_MAX);
    check_events("r_div(3, 0)", 0, 1);
    fx_events_reset();
    assert_true(r_div(R(-3.0), 0) == -R_MAX);
    check_events("r_div(-3, 0)", 0, 1);
    fx_events_reset();
    assert_true(r_div(0, 0) == 0);
    check_events("r_div(0, 0)", 0, 1);
    fx_events_reset();
    assert_true(r_div_u(R(2.0), 0) == R_MAX);
    assert_true(r_div_u(R(-2.0), 0) == -R_MAX);
    check_events("r_div_u(+-2, 0)", 0, 2);
    fx_events_reset();
    assert_true(u_div(U(0.5), 0) > U(1.99));
    assert_true(u_div(U(-0.5), 0) < U(-1.99));
    assert_true(u_div(0, 0) == 0);
    check_events("u_div(x, 0)", 0, 3);
    fx_events_reset();
    assert_true(r_sqrt(R(-1.0)) == 0);
    assert_true(r_sqrt(-R_LSB) == 0);
    assert_true(r_sqrt(-R_MAX) == 0);
    check_events("r_sqrt(negative)", 0, 3);
    fx_events_reset();
    assert_true(r_sqrt_w(-w_sq(R(2.0))) == 0);
    check_events("r_sqrt_w(-4)", 0, 1);
    fx_events_reset();
    dir3 d = d3_norm(v3(0, 0, 0), &len);
    assert_true(d.x == 0 && d.y == 0 && d.z == 0 && len == 0);
    check_events("d3_norm(0)", 0, 1);
    fx_events_reset();
    dir3 a = dir_from(edge_dirs[4]);
    len = R(9.0);
    d = d3_cross(a, a, &len);
    assert_true(d.x == 0 && d.y == 0 && d.z == 0 && len == 0);
    check_events("d3_cross(a, a)", 0, 1);
    checks_done();
}

#if REAL_FIXED /* float has the range to spare: nothing saturates */
/* Overflow saturates to +-R_MAX (never INT32_MIN) and counts one OVERFLOW event per result. */
static void test_saturation(void **state)
{
    (void)state;
    struct {
        const char *what;
        real got, want;
        unsigned long overflows, domains;
    } cases[16];
    int n = 0;
#define SAT_CASE(expr, want_) \
    do { \
        assert_true(n < (int)(sizeof cases / sizeof cases[0])); \
        fx_events_reset(); \
        cases[n].got = (expr); \
        cases[n].what = #expr; \
        cases[n].want = (want_); \
        cases[n].overflows = fx_event_count[FX_EV_OVERFLOW]; \
        cases[n].domains = fx_event_count[FX_EV_DOMAIN]; \
        n++; \
    } while (0)
    SAT_CASE(r_add(R_MAX, R_ONE), R_MAX);
    SAT_CASE(r_add(-R_MAX, -R_MAX), -R_MAX);
    SAT_CASE(r_sub(-R_MAX, R_ONE), -R_MAX);
    SAT_CASE(r_mul(R(1000.0), R(1000.0)), R_MAX);
    SAT_CASE(r_mul(R(-1000.0), R(1000.0)), -R_MAX);
    SAT_CASE(r_mul(R(-1000.0), R(-1000.0)), R_MAX);
    SAT_CASE(r_mul(R(-16384.0), R(2.0)), -R_MAX); /* exactly -32768 is out of range too */
    SAT_CASE(r_div(R(30000.0), R(0.5)), R_MAX);
    SAT_CASE(r_div(R(-30000.0), R(0.5)), -R_MAX);
    SAT_CASE(r_from_int(-40000), -R_MAX);
    SAT_CASE(r_muli(R(20000.0), 2), R_MAX);
    SAT_CASE(r_mul_u(-R_MAX, U(1.5)), -R_MAX);
    SAT_CASE(r_div_u(R(30000.0), U(-0.5)), -R_MAX);
    SAT_CASE(r_hypot(R(30000.0), R(-30000.0)), R_MAX);
    SAT_CASE(r_sqrt_w(d2w(2e9)), R_MAX);
    SAT_CASE(u_to_real(u_mul(U(1.5), U(1.5))), R(2.0)); /* u_mul saturates at 2 - 2^-30 */
#undef SAT_CASE
    for (int i = 0; i < n; i++) {
        if (cases[i].got != cases[i].want || cases[i].overflows != 1 || cases[i].domains != 0) {
            n_failed++;
            print_error("%s = %.10g with events overflow=%lu domain=%lu; expected %.10g with "
                        "overflow=1 domain=0\n",
                        cases[i].what, r2d(cases[i].got), cases[i].overflows, cases[i].domains,
                        r2d(cases[i].want));
        }
    }
    /* the most negative value is -R_MAX; negating it is exact */
    fx_events_reset();
    assert_true(r_neg(-R_MAX) == R_MAX);
    assert_true(r_abs(-R_MAX) == R_MAX);
    check_events("r_neg(-R_MAX), r_abs(-R_MAX)", 0, 0);
    /* units saturate at +-(2 - 2^-30) */
    const unit u_max = (unit)INT32_MAX;
    fx_events_reset();
    assert_true(u_add(U(1.5), U(1.5)) == u_max);
    assert_true(u_add(U(-1.5), U(-1.5)) == -u_max);
    assert_true(u_from_real(R(3.0)) == u_max);
    assert_true(u_muli(U(0.75), -3) == -u_max);
    assert_true(u_div(U(1.5), U(0.5)) == u_max);
    check_events("unit saturation", 5, 0);
    /* a length beyond the range saturates; its direction is still right */
    fx_events_reset();
    real len = 0;
    dir3 d = d3_norm(v3(R(30000.0), R(-30000.0), R(30000.0)), &len);
    assert_true(len == R_MAX);
    check_events("d3_norm((30000, -30000, 30000), &len)", 1, 0);
    double e[3] = {1, -1, 1};
    check_dir("d3_norm", e, d, TOL_NORM.abs, "(30000, -30000, 30000)");
    checks_done();
}
#endif

/* Ordinary use, within the scene's limits, counts no event at all. */
static void test_no_events_in_range(void **state)
{
    (void)state;
    fx_events_reset();
    volatile real sink = 0;
    volatile unit usink = 0;
    real len = 0;
    for (int i = 0; i < 2000; i++) {
        real a = rng_real(-8, 7), b = rng_real(-4, 7); /* |a / b| < 2^11 */
        unit u = d2u(rng_unit() * 1.9 - 0.95), w = d2u(rng_unit() * 1.9 - 0.95);
        sink = r_add(a, b);
        sink = r_sub(a, b);
        sink = r_neg(a);
        sink = r_abs(a);
        sink = r_mul(a, b);
        sink = r_div(a, b);
        sink = r_sqrt(r_abs(a));
        sink = r_sin(a);
        sink = r_cos(a);
        sink = r_mod(a, R(2.5));
        sink = r_mul_u(a, u);
        sink = r_div_u(a, U(0.75));
        sink = r_hypot(a, b);
        sink = r_lerp(a, b, R(0.5));
        sink = r_shr(a, 3);
        sink = r_muli(a, 3);
        sink = r_sqrt_w(w_add(w_sq(a), w_sq(b)));
        sink = u_to_real(u);
        usink = u_mul(u, w);
        usink = u_add(u_divi(u, 2), u_divi(w, 2));
        usink = u_neg(u);
        usink = u_div(u_divi(u, 2), U(0.75));
        usink = u_from_real(r_shr(a, 8));
        unit s, c;
        u_sincos_deg(r_muli(a, 3), &s, &c);
        vec3 v = v3(a, b, r_sub(a, b));
        dir3 d = d3_norm(v, &len);
        sink = v3_dot_d(v, d);
        usink = d3_dot(d, d);
        vec3 p = v3_along(v, d, R(2.0));
        sink = p.x;
        p = d3_scale(d, a);
        sink = p.y;
        p = d3_scale_in(d, b);
        sink = p.z;
        sink = v3_dot_d_in(v3_sub_in(v, p), d);
        dir3 n = dir_from(edge_dirs[i % N_EDGE_D]);
        dir3 r = d3_reflect(d, n);
        usink = r.x;
        if (d3_dot(d, n) <= 0 && d3_refract(d, n, R(0.75), &r))
            usink = r.y;
        if (d3_dot(d, n) != U_ONE && d3_dot(d, n) != -U_ONE) {
            r = d3_cross(d, n, &len);
            usink = r.z;
            r = d3_ray(n, r, d3_cross(n, r, 0), U(0.002), i % 640 - 320, i % 480 - 240);
            usink = r.x;
        }
    }
    (void)sink;
    (void)usink;
    check_events("normal operations", 0, 0);
    checks_done();
}

/* ---- units and trigonometry ------------------------------------------------------------------ */

static void test_units(void **state)
{
    (void)state;
    for (int i = 0; i < N_EDGE_U; i++) {
        unit a = edge_u[i];
        double x = u2d(a);
        check_u("u_neg", sat_u(-x), u_neg(a), 0.0, "%.12g", x);
        check_r("u_to_real", x, u_to_real(a), tol_at(TOL_R_ROUND, x), "%.12g", x);
        static const int32_t divs[] = {1, 2, 3, 6, 7, 110, 132, 480, 1000};
        for (int k = 0; k < (int)(sizeof divs / sizeof divs[0]); k++) {
            double q = x / divs[k];
            check_u("u_divi", q, u_divi(a, divs[k]), tol_at(TOL_U_ROUND, q), "%.12g, %d", x,
                    (int)divs[k]);
        }
        static const int32_t mults[] = {0, 1, -1, 2, 3, -640, 1000};
        for (int k = 0; k < (int)(sizeof mults / sizeof mults[0]); k++) {
            double p = x * mults[k];
            check_u("u_muli", sat_u(p), u_muli(a, mults[k]), tol_at(TOL_ADD, p), "%.12g, %d", x,
                    (int)mults[k]);
        }
        for (int j = 0; j < N_EDGE_U; j++) {
            unit b = edge_u[j];
            double y = u2d(b);
            check_u("u_mul", sat_u(x * y), u_mul(a, b), tol_at(TOL_U_ROUND, x * y), "%.12g, %.12g",
                    x, y);
            check_u("u_add", sat_u(x + y), u_add(a, b), tol_at(TOL_ADD, x + y), "%.12g, %.12g", x,
                    y);
            if (b != 0 && fabs(x / y) < 1.99) {
                double q = x / y;
                check_u("u_div", q, u_div(a, b), tol_at(b > 0 ? TOL_U_ROUND : TOL_U_ROUND, q),
                        "%.12g, %.12g", x, y);
            }
        }
    }
    for (int k = 0; k < 20000; k++) {
        unit a = d2u(rng_unit() * 3.8 - 1.9), b = d2u(rng_unit() * 3.8 - 1.9);
        double x = u2d(a), y = u2d(b);
        check_u("u_mul", sat_u(x * y), u_mul(a, b), tol_at(TOL_U_ROUND, x * y), "%.12g, %.12g", x,
                y);
        if (b != 0 && fabs(x / y) < 1.99)
            check_u("u_div", x / y, u_div(a, b), tol_at(b > 0 ? TOL_U_ROUND : TOL_U_ROUND, x / y),
                    "%.12g, %.12g", x, y);
        int32_t i = 1 + (int32_t)(rng() % 1000);
        check_u("u_divi", x / i, u_divi(a, i), tol_at(TOL_U_ROUND, x / i), "%.12g, %d", x, (int)i);
    }
    /* exact cases */
    assert_true(u_mul(U(0.5), U(0.5)) == U(0.25));
    assert_true(u_div(U(0.25), U(0.5)) == U(0.5));
    assert_true(u_div(U(-0.25), U(0.5)) == U(-0.5));
    assert_true(u_divi(U(0.75), 3) == U(0.25));
    for (int i = 0; i < N_EDGE_R; i++) {
        double x = r2d(edge_r[i]);
        check_u("u_from_real", sat_u(x), u_from_real(edge_r[i]), 0.0, "%.9g", x);
    }
    /* powers of bases in [0, 1] */
    static const double bases[] = {0, 1e-9, 0.123, 0.5, 0.9, 0.99, 0.999999, 1};
    static const unsigned exps[] = {1, 2, 3, 5, 8, 16, 20, 64, 100, 255};
    for (int i = 0; i < (int)(sizeof bases / sizeof bases[0]); i++)
        for (int k = 0; k < (int)(sizeof exps / sizeof exps[0]); k++) {
            unit b = d2u(bases[i]);
            double x = u2d(b), e = pow(x, exps[k]);
            check_u("u_pow", e, u_pow(b, exps[k]), exps[k] * tol_at(TOL_POW_PER_STEP, e),
                    "%.12g, %u", x, exps[k]);
        }
    checks_done();
}

static void check_sin_cos(real a)
{
    double x = r2d(a), t = TOL_SIN.abs + TOL_SIN_PER_RAD * fabs(x);
    check_r("r_sin", sin(x), r_sin(a), t, "%.9g", x);
    check_r("r_cos", cos(x), r_cos(a), t, "%.9g", x);
}

static void test_trig(void **state)
{
    (void)state;
    static const double angles[] = {
        0,       0.5,     -0.5,   1,        -1,      1.5707963, -1.5707963, 1.5708,    2,
        3,       3.14159, 3.1416, -3.14159, -3.1416, 4.712389,  -4.712389,  6.2831853, 6.2832,
        -6.2832, 10,      -10,    100,      -100,    1000,      12345.678,  32767.99,  -32767.99,
    };
    for (int i = 0; i < (int)(sizeof angles / sizeof angles[0]); i++)
        check_sin_cos(d2r(angles[i]));
    static const real raw[] = {R_LSB,        -R_LSB,       R_PI,          -R_PI,
                               R_PI + R_LSB, R_PI - R_LSB, -R_PI - R_LSB, -R_PI + R_LSB,
                               2 * R_PI,     -2 * R_PI,    R_MAX,         -R_MAX};
    for (int i = 0; i < (int)(sizeof raw / sizeof raw[0]); i++)
        check_sin_cos(raw[i]);
    /* every Q16.16 step of [-2 pi, 2 pi] (in float, steps of 2^-16) */
    const real step = d2r(1.0 / 65536), end = r_muli(R_PI, 2);
    for (real a = r_neg(end); a <= end; a = r_add(a, step))
        check_sin_cos(a);
    for (double x = -40; x <= 40; x += 0.00731)
        check_sin_cos(d2r(x));
    for (int k = 0; k < 5000; k++)
        check_sin_cos(rng_real(-16, 15));

    /* u_sincos_deg: the camera's accurate sine and cosine in degrees */
    static const double degs[] = {
        0,   30,   45,     60,       90,         135,   180,       225,   270,   315,   359.9, -45,
        -90, -180, -359.9, 720 + 30, 1e4 + 0.25, 32767, -32767.99, 0.001, 44.99, 45.01, 89.999};
    for (int i = 0; i < (int)(sizeof degs / sizeof degs[0]); i++) {
        real a = d2r(degs[i]);
        double x = r2d(a), rad = x * (PI_D / 180);
        unit s = 7, c = 7;
        u_sincos_deg(a, &s, &c);
        check_u("u_sincos_deg:sin", sin(rad), s, TOL_SINCOS_DEG.abs, "%.9g deg", x);
        check_u("u_sincos_deg:cos", cos(rad), c, TOL_SINCOS_DEG.abs, "%.9g deg", x);
    }
    for (double x = -730; x <= 730; x += 0.1373) {
        real a = d2r(x);
        double rad = r2d(a) * (PI_D / 180);
        unit s, c;
        u_sincos_deg(a, &s, &c);
        check_u("u_sincos_deg:sin", sin(rad), s, TOL_SINCOS_DEG.abs, "%.9g deg", r2d(a));
        check_u("u_sincos_deg:cos", cos(rad), c, TOL_SINCOS_DEG.abs, "%.9g deg", r2d(a));
    }
    /* the axes */
    for (int q = -4; q <= 8; q++) {
        unit s, c;
        u_sincos_deg(r_from_int(90 * q), &s, &c);
        check_u("u_sincos_deg:sin", (q % 2 == 0) ? 0 : ((q % 4 + 4) % 4 == 1 ? 1 : -1), s,
                TOL_SINCOS_AXIS, "%d deg", 90 * q);
        check_u("u_sincos_deg:cos", (q % 2 != 0) ? 0 : ((q % 4 + 4) % 4 == 0 ? 1 : -1), c,
                TOL_SINCOS_AXIS, "%d deg", 90 * q);
    }
    checks_done();
}

/* ---- wide values and square roots ------------------------------------------------------------ */

static void test_wide(void **state)
{
    (void)state;
    for (int i = 0; i < N_EDGE_R; i++) {
        real a = edge_r[i];
        double x = r2d(a);
        check_w("w_sq", x * x, w_sq(a), tol_at(TOL_WIDE, x * x), "%.9g", x);
        check_r("r_sqrt_w", sat_r(fabs(x)), r_sqrt_w(w_sq(a)), tol_at(TOL_R_ROUND, x), "%.9g^2", x);
        for (int j = 0; j < N_EDGE_R; j++) {
            double y = r2d(edge_r[j]);
            wide s = w_add(w_sq(a), w_sq(edge_r[j]));
            check_w("w_add", x * x + y * y, s, tol_at(TOL_WIDE, x * x + y * y), "%.9g^2, %.9g^2", x,
                    y);
            check_w("w_sub", x * x - y * y, w_sub(w_sq(a), w_sq(edge_r[j])),
                    tol_at(TOL_WIDE, x * x + y * y), "%.9g^2, %.9g^2", x, y);
            double h = sqrt(x * x + y * y);
            check_r("r_sqrt_w", sat_r(h), r_sqrt_w(s), tol_at(TOL_R_ROUND, h), "%.9g^2 + %.9g^2", x,
                    y);
        }
    }
    for (int i = 0; i < N_EDGE_V; i++) {
        vec3 v = edge_v[i];
        double e[3];
        dd_from_vec(v, e);
        double l2 = dd_dot(e, e);
        check_w("w_len2", l2, w_len2(v), tol_at(TOL_WIDE, l2), "(%.9g, %.9g, %.9g)", e[0], e[1],
                e[2]);
        check_r("r_sqrt_w", sqrt(l2), r_sqrt_w(w_len2(v)), tol_at(TOL_R_ROUND, sqrt(l2)),
                "|(%.9g, %.9g, %.9g)|^2", e[0], e[1], e[2]);
    }
    /* w_len2 at its documented bound: components just below 24576 */
    static const vec3 bound_v[] = {{R(24575.99), R(-24575.99), R(24575.99)},
                                   {R(-24575.99), R(-24575.99), R(-24575.99)}};
    for (int i = 0; i < 2; i++) {
        double e[3];
        dd_from_vec(bound_v[i], e);
        double l2 = dd_dot(e, e);
        check_w("w_len2", l2, w_len2(bound_v[i]), tol_at(TOL_WIDE, l2), "(%.9g, %.9g, %.9g)", e[0],
                e[1], e[2]);
        check_r("r_sqrt_w", sat_r(sqrt(l2)), r_sqrt_w(w_len2(bound_v[i])),
                tol_at(TOL_R_ROUND, sqrt(l2)), "|(%.9g, %.9g, %.9g)|^2", e[0], e[1], e[2]);
    }
    /* small and odd wide values straight from double */
    static const double ws[] = {0, 0x1p-32, 0x1p-31, 3 * 0x1p-32, 0x1p-30,      2,
                                3, 1e-6,    0.5,     1e9,         1073741823.99};
    for (int i = 0; i < (int)(sizeof ws / sizeof ws[0]); i++) {
        wide w = d2w(ws[i]);
        double x = w2d(w);
        check_r("r_sqrt_w", sat_r(sqrt(x)), r_sqrt_w(w), tol_at(TOL_R_ROUND, sqrt(x)), "%.12g", x);
    }
    for (int k = 0; k < 20000; k++) {
        double x = ldexp(1.0 + rng_unit(), (int)(rng() % 62) - 32);
        wide w = d2w(x);
        double xw = w2d(w);
        check_r("r_sqrt_w", sat_r(sqrt(xw)), r_sqrt_w(w), tol_at(TOL_R_ROUND, sqrt(xw)), "%.12g",
                xw);
    }
    checks_done();
}

#if REAL_FIXED
/* The exact rounded square root of n, for fx_isqrt64 (clamped to 32 bits). */
static uint64_t ref_isqrt(uint64_t n)
{
    uint64_t r = (uint64_t)sqrt((double)n);
    if (r > 0xFFFFFFFFu)
        r = 0xFFFFFFFFu;
    while (r * r > n)
        r--;
    while (r < 0xFFFFFFFFu && (r + 1) * (r + 1) <= n)
        r++;
    /* round up when n >= r^2 + r + 1, i.e. sqrt(n) > r + 1/2 */
    if (n - r * r > r)
        r++;
    return r > 0xFFFFFFFFu ? 0xFFFFFFFFu : r;
}
#endif

#if REAL_FIXED /* fx_isqrt64, fx_norm64 and fx_renorm exist in the fixed build only */
/* The fixed build's own parts: fx_isqrt64, fx_norm64, fx_renorm, and r_mul against
 * libfixmath's fix16_mul bit for bit. */
/* fx_armv6m.h's products in 32-bit pieces (the Cortex-M0's FX_SMUL and FX_UMUL) are the 64-bit
 * products: every pair of edge values (the halves' carries and signs) and 2,000,000 random pairs. */
static void test_armv6m_products(void **state)
{
    (void)state;
    static const int32_t edge[] = {0,          1,           -1,          2,          0x7fff,
                                   0x8000,     0xffff,      0x10000,     0x10001,    -0x8000,
                                   -0x8001,    -0xffff,     -0x10000,    -0x10001,   0x7fff0000,
                                   0x7fffffff, -0x7fffffff, INT32_MIN,   0x12345678, -0x789abcde,
                                   0x0000ffff, 0x40000000,  -0x40000000, 0x3fffffff, 0x55555555};
    const int n = (int)(sizeof edge / sizeof *edge);
    long bad = 0;
    for (int k = 0; k < n * n + 2000000; k++) {
        int32_t a, b;
        if (k < n * n) {
            a = edge[k / n];
            b = edge[k % n];
        } else {
            uint64_t r = rng();
            a = (int32_t)(uint32_t)r;
            b = (int32_t)(uint32_t)(r >> 32);
        }
        bad += fx_v6m_smul(a, b) != (int64_t)a * b;
        bad += fx_v6m_umul((uint32_t)a, (uint32_t)b) != (uint64_t)(uint32_t)a * (uint32_t)b;
    }
    assert_int_equal(bad, 0);
}

static void test_fixed_internals(void **state)
{
    (void)state;
    /* r_mul is fix16_mul written inline: the same bits wherever fix16_mul does not overflow */
    for (int k = 0; k < 200000 + N_EDGE_R * N_EDGE_R + 60000; k++) {
        real a, b;
        if (k < N_EDGE_R * N_EDGE_R) {
            a = edge_r[k / N_EDGE_R];
            b = edge_r[k % N_EDGE_R];
        } else if (k >= 200000 + N_EDGE_R * N_EDGE_R) {
            /* products next to +-2^47, where the result stops fitting (r_mul's range check) */
            int j = k - (200000 + N_EDGE_R * N_EDGE_R);
            int64_t bb = 65536 + (j < 30000 ? j / 10 : (int64_t)(rng() % 0x7FFF0000));
            int64_t aa = ((j & 1 ? 1 : -1) * ((int64_t)1 << 47)) / bb + (j % 5) - 2;
            if (aa < -INT32_MAX || aa > INT32_MAX)
                continue;
            a = (real)aa;
            b = (real)(j & 2 ? -bb : bb);
            if (j & 2)
                a = -a;
        } else if (k % 4 == 0) {
            /* products whose low 16 bits are exactly one half: the rounding ties */
            a = (real)(rng() >> 48) | 1;
            b = (real)(0x8000 * (1 + (rng() % 64) * 2)) * (k % 8 ? 1 : -1);
        } else {
            a = (real)(uint32_t)(rng() >> (32 + rng() % 32));
            b = (real)(uint32_t)(rng() >> (32 + rng() % 32));
        }
        fix16_t p = fix16_mul(a, b);
        real r = r_mul(a, b);
        if (p != fix16_overflow) {
            if (r != p) {
                n_failed++;
                print_error("r_mul(%d, %d) = %d, fix16_mul gives %d\n", (int)a, (int)b, (int)r,
                            (int)p);
            }
        } else if (r != ((a < 0) != (b < 0) ? -R_MAX : R_MAX)) {
            n_failed++;
            print_error("r_mul(%d, %d) = %d: fix16_mul overflows, want %s\n", (int)a, (int)b,
                        (int)r, (a < 0) != (b < 0) ? "-R_MAX" : "R_MAX");
        }
    }

    /* fx_sat's two forms, for 64-bit machines and for 32-bit cores (the ARM board), give the
     * same values and count the same overflows around every edge of real's range */
    static const int64_t sat_edges[] = {0,         INT32_MAX, INT32_MIN,       (int64_t)1 << 32,
                                        INT64_MAX, INT64_MIN, (int64_t)3 << 31};
    for (int k = 0; k < 7 * 2 * 9 + 100000; k++) {
        int64_t v;
        if (k < 7 * 2 * 9) {
            int64_t e = sat_edges[k / 18];
            int d = k % 9 - 4;
            v = (k / 9) % 2 && e != INT64_MIN ? -e : e;
            v = d < 0 ? (v >= INT64_MIN - d ? v + d : v) : (v <= INT64_MAX - d ? v + d : v);
        } else {
            v = (int64_t)rng() >> (rng() % 64);
        }
        fx_events_reset();
        real w32 = fx_sat_w32(v);
        unsigned long e32 = fx_event_count[FX_EV_OVERFLOW];
        fx_events_reset();
        real w64 = fx_sat_w64(v);
        unsigned long e64 = fx_event_count[FX_EV_OVERFLOW];
        if (w32 != w64 || e32 != e64 || (e64 != 0) != (v < -R_MAX || v > R_MAX)) {
            n_failed++;
            print_error("fx_sat(%lld): 32-bit form %d (%lu events), 64-bit form %d (%lu)\n",
                        (long long)v, (int)w32, e32, (int)w64, e64);
        }
    }
    fx_events_reset();

    /* r_reduce_angle's remainder, formed without a 64-bit division, is the % operator's: every
     * 4099th 32-bit angle, the ends of the range, and the angles next to each multiple of 2 pi
     * up to 5214 turns (where the quotient's estimate falls one short) */
    for (int64_t k = 0; k < 1048576 + 2 * 5215 * 8; k++) {
        int64_t a64 = k < 1048576 ? INT32_MIN + k * 4099 : 0;
        if (k >= 1048576) {
            int64_t j = k - 1048576, turn = j / 16;
            a64 = (turn * 26986075409LL >> 16) + j % 8 - 4;
            a64 = j % 16 >= 8 ? -a64 : a64;
        }
        if (a64 > INT32_MAX || a64 < INT32_MIN)
            a64 = a64 < 0 ? INT32_MIN : INT32_MAX;
        const real a = (real)a64;
        int64_t v = ((int64_t)a * 65536) % 26986075409LL;
        if (v > 13493037705LL)
            v -= 26986075409LL;
        else if (v <= -13493037705LL)
            v += 26986075409LL;
        if (r_reduce_angle(a) != (real)fx_round_shift(v, 16)) {
            n_failed++;
            print_error("r_reduce_angle(%d) = %d, the %% operator's remainder gives %d\n", (int)a,
                        (int)r_reduce_angle(a), (int)fx_round_shift(v, 16));
        }
    }

    static const uint64_t ns[] = {0,
                                  1,
                                  2,
                                  3,
                                  4,
                                  5,
                                  6,
                                  7,
                                  8,
                                  9,
                                  12,
                                  13,
                                  15,
                                  16,
                                  17,
                                  20,
                                  21,
                                  1u << 20,
                                  (1u << 20) + 1024,
                                  (1ull << 20) + 1025,
                                  1ull << 62,
                                  (1ull << 62) - 1,
                                  (1ull << 62) + (1ull << 31),
                                  (1ull << 62) + (1ull << 31) + 1,
                                  UINT64_MAX,
                                  UINT64_MAX - 1,
                                  0xFFFFFFFE00000001ull,
                                  0xFFFFFFFF7FFFFFFFull,
                                  0xFFFFFFFF80000000ull,
                                  0xFFFFFFFF80000001ull};
    for (int i = 0; i < (int)(sizeof ns / sizeof ns[0]); i++)
        check_i("fx_isqrt64", (double)ref_isqrt(ns[i]), fx_isqrt64(ns[i]), 0.0, "%llu",
                (unsigned long long)ns[i]);
    assert_int_equal(fx_isqrt64(0), 0);
    assert_int_equal(fx_isqrt64(1), 1);
    assert_int_equal(fx_isqrt64(2), 1);
    assert_int_equal(fx_isqrt64(3), 2); /* 1.73 */
    assert_int_equal(fx_isqrt64(4), 2);
    assert_int_equal(fx_isqrt64(6), 2); /* 2.449 */
    assert_int_equal(fx_isqrt64(7), 3); /* 2.646 */
    assert_int_equal(fx_isqrt64(1ull << 62), 1u << 31);
    assert_int_equal(fx_isqrt64(UINT64_MAX), UINT32_MAX);
    /* perfect squares and their neighbours, including the rounding boundaries k^2 + k (down)
     * and k^2 + k + 1 (up) */
    for (int k = 0; k < 3000; k++) {
        uint64_t r = k < 1000 ? (uint64_t)k : (rng() >> 32) | 1;
        uint64_t sq = r * r;
        uint64_t cands[] = {sq, sq - 1, sq + 1, sq + r, sq + r + 1};
        for (int c = 0; c < 5; c++) {
            if (r == 0 && c != 0 && c != 2)
                continue;
            check_i("fx_isqrt64", (double)ref_isqrt(cands[c]), fx_isqrt64(cands[c]), 0.0, "%llu",
                    (unsigned long long)cands[c]);
        }
    }
    /* roots at the edges: 2^32 - 1, powers of two and their neighbours, sqrt(2) 2^31 */
    static const uint64_t roots[] = {0xFFFFFFFFu, 0xFFFFFFFEu, 0x80000000u, 0x7FFFFFFFu,
                                     0x80000001u, 0xB504F333u, 0xB504F334u, 65535,
                                     65536,       65537};
    for (int k = 0; k < (int)(sizeof roots / sizeof roots[0]) + 64; k++) {
        uint64_t r = k < (int)(sizeof roots / sizeof roots[0])
            ? roots[k]
            : ((uint64_t)1 << ((k - 10) / 2)) + ((k & 1) ? 1 : (uint64_t)-1);
        if (r > 0xFFFFFFFFu || r == 0)
            continue;
        uint64_t sq = r * r;
        uint64_t cands[] = {sq, sq - 1, sq + 1, sq + r, sq + r + 1};
        for (int c = 0; c < 5; c++)
            check_i("fx_isqrt64", (double)ref_isqrt(cands[c]), fx_isqrt64(cands[c]), 0.0, "%llu",
                    (unsigned long long)cands[c]);
    }
    /* every n below 2^20, and random n of every size */
    for (uint64_t n = 0; n < (1u << 20); n++) {
        uint32_t r = fx_isqrt64(n);
        if (r != ref_isqrt(n))
            check_i("fx_isqrt64", (double)ref_isqrt(n), r, 0.0, "%llu", (unsigned long long)n);
    }
    for (int k = 0; k < 200000; k++) {
        uint64_t n = rng() >> (rng() % 64);
        uint32_t r = fx_isqrt64(n);
        if (r != ref_isqrt(n))
            check_i("fx_isqrt64", (double)ref_isqrt(n), r, 0.0, "%llu", (unsigned long long)n);
    }

    /* fx_udiv64 (the ARM926's division in r_div_u) against the division: quotients of every
     * size (the large ones take its fallback), divisors of every size, and exact multiples
     * and their neighbours, where an estimate off by one shows */
    for (int k = 0; k < 400000; k++) {
        uint32_t m = (uint32_t)(rng() >> (32 + rng() % 32));
        if (m == 0)
            m = 1;
        uint64_t n;
        if (k % 3 == 0)
            n = rng() >> 2; /* any n below 2^62 */
        else {
            uint64_t q = rng() >> (33 + rng() % 31); /* a quotient below 2^31 */
            n = q * m + (k % 3 == 1 ? 0 : (uint64_t)(rng() % m));
            if (k % 5 == 0 && n > 0)
                n--;
            n &= ((uint64_t)1 << 62) - 1;
        }
        uint64_t want = n / m, got = fx_udiv64(n, m);
        if (got != want) {
            n_failed++;
            print_error("fx_udiv64(%llu, %u) = %llu, want %llu\n", (unsigned long long)n, m,
                        (unsigned long long)got, (unsigned long long)want);
        }
    }

    /* fx_norm64: any 64-bit components, any scale */
    static const struct {
        int64_t x, y, z;
        int frac;
    } nv[] = {
        {INT64_MIN, 0, 0, 60},
        {INT64_MAX, INT64_MAX, INT64_MAX, 60},
        {INT64_MIN, INT64_MAX, 1, 58},
        {1, 2, 2, 0},
        {5, 0, -12, 16},
        {3, 4, 0, 30},
        {1, 1, 1, 0},
        {1, 0, 0, 62},
        {-1, 0, 0, 16},
        {1ll << 40, 0, 0, 0},
        {(1ll << 40) + 1, -3, 7, 24},
        {123456789012345ll, -98765432109ll, 5, 44},
    };
    for (int i = 0; i < (int)(sizeof nv / sizeof nv[0]); i++) {
        double e[3] = {(double)nv[i].x, (double)nv[i].y, (double)nv[i].z};
        double l = sqrt(dd_dot(e, e)), el = sat_r(ldexp(l, -nv[i].frac));
        real len = 77;
        dir3 d = fx_norm64(nv[i].x, nv[i].y, nv[i].z, nv[i].frac, &len);
        char what[128];
        snprintf(what, sizeof what, "%lld, %lld, %lld, frac %d", (long long)nv[i].x,
                 (long long)nv[i].y, (long long)nv[i].z, nv[i].frac);
        check_dir("fx_norm64", e, d, TOL_NORM.abs, what);
        check_r("fx_norm64:len", el, len, tol_at(TOL_NORM_LEN, el), "%s", what);
    }
    for (int k = 0; k < 20000; k++) {
        int sh = (int)(rng() % 62);
        int64_t x = (int64_t)rng() >> sh, y = (int64_t)rng() >> (rng() % 63),
                z = (int64_t)rng() >> (rng() % 63);
        if (x == 0 && y == 0 && z == 0)
            continue;
        int frac = (int)(rng() % 63);
        double e[3] = {(double)x, (double)y, (double)z};
        double l = sqrt(dd_dot(e, e)), el = sat_r(ldexp(l, -frac));
        real len;
        dir3 d = fx_norm64(x, y, z, frac, &len);
        char what[128];
        snprintf(what, sizeof what, "%lld, %lld, %lld, frac %d", (long long)x, (long long)y,
                 (long long)z, frac);
        check_dir("fx_norm64", e, d, TOL_NORM.abs, what);
        check_r("fx_norm64:len", el, len, tol_at(TOL_NORM_LEN, el), "%s", what);
    }

    /* fx_norm32 and fx_norm32_to: fx_norm64(x, y, z, 16, len)'s results bit for bit, for 32-bit
     * components of every size (the largest magnitude from 1 to 2^31: the light direction's
     * usual path below 2^30, fx_norm64 itself above) */
    for (int k = 0; k < 40000; k++) {
        int32_t c[3];
        for (int j = 0; j < 3; j++)
            c[j] = (int32_t)(uint32_t)rng() >> (rng() % 32);
        if (k % 7 == 0)
            c[k % 3] = k & 8 ? INT32_MIN : INT32_MAX;
        if (c[0] == 0 && c[1] == 0 && c[2] == 0)
            continue;
        real want_len = 0, len = 1, len_to;
        dir3 want = fx_norm64(c[0], c[1], c[2], 16, &want_len),
             d = fx_norm32(c[0], c[1], c[2], &len), d_to;
        len_to = fx_norm32_to(&d_to, c[0], c[1], c[2]);
        if (d.x != want.x || d.y != want.y || d.z != want.z || len != want_len ||
            d_to.x != want.x || d_to.y != want.y || d_to.z != want.z || len_to != want_len) {
            n_failed++;
            print_error("fx_norm32(%d, %d, %d) differs from fx_norm64's (%d, %d, %d), %d\n", c[0],
                        c[1], c[2], want.x, want.y, want.z, want_len);
        }
    }

    /* fx_renorm: Q.60 vectors near unit length (first-order correction), and those too far
     * from it or beyond 2.0 (fallback to fx_norm64) */
    static const double scales[] = {1.0,         1 + 0x1p-22, 1 - 0x1p-22, 1 + 0x1p-21, 1 - 0x1p-21,
                                    1 + 0x1p-20, 1 + 0x1p-19, 1 - 0x1p-19, 0.5,         1.5,
                                    1.99,        2.5,         3.9};
    for (int k = 0; k < 20000 + N_EDGE_D * 13; k++) {
        double v[3], sc;
        if (k < N_EDGE_D * 13) {
            const double *dv = edge_dirs[k / 13];
            double l = sqrt(dd_dot(dv, dv));
            sc = scales[k % 13];
            for (int c = 0; c < 3; c++)
                v[c] = dv[c] / l * sc;
        } else {
            double r3[3] = {rng_unit() - 0.5, rng_unit() - 0.5, rng_unit() - 0.5};
            double l = sqrt(dd_dot(r3, r3));
            sc = 1 + (rng_unit() - 0.5) * 0x1p-18;
            for (int c = 0; c < 3; c++)
                v[c] = r3[c] / l * sc;
        }
        int64_t q[3];
        for (int c = 0; c < 3; c++)
            q[c] = (int64_t)llround(v[c] * 0x1p60);
        double e[3] = {(double)q[0], (double)q[1], (double)q[2]};
        char what[128];
        snprintf(what, sizeof what, "(%.12g, %.12g, %.12g) * 2^60", v[0], v[1], v[2]);
        check_dir("fx_renorm", e, fx_renorm(q[0], q[1], q[2]), TOL_NORM.abs, what);
    }
    checks_done();
}
#endif

/* ---- vectors and normalisation --------------------------------------------------------------- */

static void test_vectors(void **state)
{
    (void)state;
    for (int i = 0; i < N_EDGE_V; i++) {
        vec3 v = edge_v[i];
        double e[3];
        dd_from_vec(v, e);
        char what[96];
        snprintf(what, sizeof what, "(%.9g, %.9g, %.9g)", e[0], e[1], e[2]);
        real len = 0;
        dir3 d = d3_norm(v, &len);
        double l = sqrt(dd_dot(e, e));
        check_dir("d3_norm", e, d, TOL_NORM.abs, what);
        check_r("d3_norm:len", sat_r(l), len, tol_at(TOL_NORM_LEN, l), "%s", what);
        double dd[3];
        dd_from_dir(d, dd);
        check_i("d3_norm:|d|", 1.0, sqrt(dd_dot(dd, dd)), 2 * TOL_NORM.abs, "%s", what);

        for (int j = 0; j < N_EDGE_D; j++) {
            dir3 u = dir_from(edge_dirs[j]);
            double ud[3];
            dd_from_dir(u, ud);
            double dot = dd_dot(e, ud);
            double mag = fabs(e[0] * ud[0]) + fabs(e[1] * ud[1]) + fabs(e[2] * ud[2]);
            check_r("v3_dot_d", dot, v3_dot_d(v, u), tol_at(TOL_DOT, mag), "%s . dir %d", what, j);
            real t = edge_r[(i + j) % N_EDGE_R];
            double td = r2d(t);
            if (fabs(td) < 10000 && fabs(e[0]) + fabs(e[1]) + fabs(e[2]) < 10000) {
                vec3 p = v3_along(v, u, t);
                check_r("v3_along", e[0] + ud[0] * td, p.x,
                        tol_at(TOL_R_ROUND, fabs(e[0]) + fabs(ud[0] * td)), "%s + dir %d * %.9g",
                        what, j, td);
                check_r("v3_along", e[1] + ud[1] * td, p.y,
                        tol_at(TOL_R_ROUND, fabs(e[1]) + fabs(ud[1] * td)), "%s + dir %d * %.9g",
                        what, j, td);
                check_r("v3_along", e[2] + ud[2] * td, p.z,
                        tol_at(TOL_R_ROUND, fabs(e[2]) + fabs(ud[2] * td)), "%s + dir %d * %.9g",
                        what, j, td);
            }
        }
    }
    /* the in-scene variants (no saturation test) within their documented bounds: differences
     * below 24576 */
    for (int k = 0; k < 20000; k++) {
        vec3 a = v3(rng_real(-16, 14), rng_real(-16, 14), rng_real(-16, 14));
        vec3 b = v3(rng_real(-16, 13), rng_real(-16, 13), rng_real(-16, 13));
        if (k % 3 == 0)
            b = v3(r_neg(a.x), r_shr(a.y, 1), a.z); /* large differences, up to 24576 */
        vec3 v = v3_sub_in(a, b);
        double ad[3], bd[3], vd[3];
        dd_from_vec(a, ad);
        dd_from_vec(b, bd);
        dd_from_vec(v, vd);
        char what[128];
        snprintf(what, sizeof what, "(%.9g, %.9g, %.9g) - (%.9g, %.9g, %.9g)", ad[0], ad[1], ad[2],
                 bd[0], bd[1], bd[2]);
        for (int c = 0; c < 3; c++)
            check_r("v3_sub_in", ad[c] - bd[c], (&v.x)[c], tol_at(TOL_ADD, ad[c] - bd[c]), "%s",
                    what);
        dir3 u = dir_from(edge_dirs[k % N_EDGE_D]);
        double ud[3];
        dd_from_dir(u, ud);
        double mag = fabs(vd[0] * ud[0]) + fabs(vd[1] * ud[1]) + fabs(vd[2] * ud[2]);
        check_r("v3_dot_d_in", dd_dot(vd, ud), v3_dot_d_in(v, u), tol_at(TOL_DOT, mag),
                "%s . dir %d", what, k % N_EDGE_D);
        assert_true(v3_dot_d_in(v, u) == v3_dot_d(v, u));
        real t = rng_real(-16, 14);
        vec3 p = d3_scale_in(u, t), p2 = d3_scale(u, t);
        for (int c = 0; c < 3; c++)
            check_r("d3_scale_in", ud[c] * r2d(t), (&p.x)[c], tol_at(TOL_R_ROUND, ud[c] * r2d(t)),
                    "dir %d * %.9g", k % N_EDGE_D, r2d(t));
        assert_true(p.x == p2.x && p.y == p2.y && p.z == p2.z);
    }

    /* beyond the scene's limits (w_len2 would overflow): normalisation and dot products still
     * hold, and lengths saturate */
    static const vec3 big_v[] = {{R_MAX, -R_MAX, R_MAX},
                                 {R(30000.0), R(-30000.0), R(30000.0)},
                                 {-R_MAX, 0, R_LSB},
                                 {R(-20000.0), R(-25000.0), R(100.0)}};
    for (int i = 0; i < (int)(sizeof big_v / sizeof big_v[0]); i++) {
        double e[3];
        dd_from_vec(big_v[i], e);
        char what[96];
        snprintf(what, sizeof what, "(%.9g, %.9g, %.9g)", e[0], e[1], e[2]);
        real len = 0;
        dir3 d = d3_norm(big_v[i], &len);
        double l = sqrt(dd_dot(e, e));
        check_dir("d3_norm", e, d, TOL_NORM.abs, what);
        check_r("d3_norm:len", sat_r(l), len, tol_at(TOL_NORM_LEN, l), "%s", what);
        for (int j = 0; j < N_EDGE_D; j++) {
            dir3 u = dir_from(edge_dirs[j]);
            double ud[3];
            dd_from_dir(u, ud);
            double mag = fabs(e[0] * ud[0]) + fabs(e[1] * ud[1]) + fabs(e[2] * ud[2]);
            check_r("v3_dot_d", sat_r(dd_dot(e, ud)), v3_dot_d(big_v[i], u), tol_at(TOL_DOT, mag),
                    "%s . dir %d", what, j);
        }
    }
    /* the tiny vector (0.01, 0.005, 0) keeps its direction: 0.894, 0.447 */
    dir3 d = d3_norm(v3(R(0.01), R(0.005), 0), 0);
    assert_true(fabs(u2d(d.x) - 0.894427) < 1e-3 && fabs(u2d(d.y) - 0.447214) < 1e-3);
    assert_true(d.z == 0);
    /* single steps */
    real len = 0;
    d = d3_norm(v3(R_LSB, 0, 0), &len);
    assert_true(d.x == U_ONE && d.y == 0 && d.z == 0 && len == R_LSB);
    d = d3_norm(v3(0, -R_LSB, 0), &len);
    assert_true(d.x == 0 && d.y == -U_ONE && d.z == 0 && len == R_LSB);
    /* large vectors */
    d = d3_norm(v3(R(200.0), R(100.0), 0), &len);
    check_u("d3_norm", 2 / sqrt(5), d.x, TOL_NORM.abs, "(200, 100, 0): x");
    check_u("d3_norm", 1 / sqrt(5), d.y, TOL_NORM.abs, "(200, 100, 0): y");
    check_r("d3_norm:len", sqrt(50000), len, tol_at(TOL_NORM_LEN, sqrt(50000)), "(200, 100, 0)");
    d = d3_norm(v3(R(30000.0), R(-30000.0), R(30000.0)), 0);
    check_u("d3_norm", 1 / sqrt(3), d.x, TOL_NORM.abs, "(30000, -30000, 30000): x");
    check_u("d3_norm", -1 / sqrt(3), d.y, TOL_NORM.abs, "(30000, -30000, 30000): y");
    /* random vectors */
    for (int k = 0; k < 20000; k++) {
        int hi = 1 + (int)(rng() % 15);
        vec3 v = v3(rng_real(-16, hi), rng_real(-16, hi), rng_real(-16, hi));
        double e[3];
        dd_from_vec(v, e);
        double l = sqrt(dd_dot(e, e));
        dir3 r = d3_norm(v, &len);
        char what[96];
        snprintf(what, sizeof what, "(%.9g, %.9g, %.9g)", e[0], e[1], e[2]);
        check_dir("d3_norm", e, r, TOL_NORM.abs, what);
        check_r("d3_norm:len", sat_r(l), len, tol_at(TOL_NORM_LEN, l), "%s", what);
    }

    /* unit-vector products */
    for (int i = 0; i < N_EDGE_D; i++) {
        dir3 a = dir_from(edge_dirs[i]);
        double ad[3];
        dd_from_dir(a, ad);
        for (int j = 0; j < N_EDGE_D; j++) {
            dir3 b = dir_from(edge_dirs[j]);
            double bd[3];
            dd_from_dir(b, bd);
            check_u("d3_dot", dd_dot(ad, bd), d3_dot(a, b), tol_at(TOL_U_ROUND, 3.0),
                    "dir %d, dir %d", i, j);
            double c[3] = {ad[1] * bd[2] - ad[2] * bd[1], ad[2] * bd[0] - ad[0] * bd[2],
                           ad[0] * bd[1] - ad[1] * bd[0]};
            double cl = sqrt(dd_dot(c, c));
            if (cl == 0)
                continue;
            real clen = 0;
            dir3 x = d3_cross(a, b, &clen);
            char what[64];
            snprintf(what, sizeof what, "dir %d x dir %d", i, j);
            check_dir("d3_cross", c, x, tol_at(TOL_CROSS, 1 / cl), what);
            check_r("d3_cross:len", cl, clen, tol_at(TOL_NORM_LEN, 1.0), "%s", what);
        }
        static const double scales[] = {0, 1, -1, 0.5, 181, -4096, 32767};
        for (int k = 0; k < (int)(sizeof scales / sizeof scales[0]); k++) {
            real s = d2r(scales[k]);
            double sd = r2d(s);
            vec3 v = d3_scale(a, s);
            check_r("d3_scale", ad[0] * sd, v.x, tol_at(TOL_R_ROUND, ad[0] * sd), "dir %d, %.9g", i,
                    sd);
            check_r("d3_scale", ad[1] * sd, v.y, tol_at(TOL_R_ROUND, ad[1] * sd), "dir %d, %.9g", i,
                    sd);
            check_r("d3_scale", ad[2] * sd, v.z, tol_at(TOL_R_ROUND, ad[2] * sd), "dir %d, %.9g", i,
                    sd);
        }
        /* r_mul_u and r_div_u with the components */
        for (int j = 0; j < N_EDGE_R; j++) {
            real x = edge_r[j];
            double xd = r2d(x);
            check_r("r_mul_u", sat_r(xd * ad[0]), r_mul_u(x, a.x), tol_at(TOL_R_ROUND, xd * ad[0]),
                    "%.9g, %.12g", xd, ad[0]);
        }
    }
    for (int i = 0; i < N_EDGE_R; i++) {
        real x = edge_r[i];
        double xd = r2d(x);
        for (int j = 0; j < N_EDGE_U; j++) {
            unit u = edge_u[j];
            double ud = u2d(u);
            check_r("r_mul_u", sat_r(xd * ud), r_mul_u(x, u), tol_at(TOL_R_ROUND, xd * ud),
                    "%.9g, %.12g", xd, ud);
            if (u != 0)
                check_r("r_div_u", sat_r(xd / ud), r_div_u(x, u), tol_at(TOL_R_ROUND, xd / ud),
                        "%.9g, %.12g", xd, ud);
        }
    }
    for (int k = 0; k < 20000; k++) {
        real x = rng_real(-16, 15);
        unit u = d2u(rng_unit() * 3.8 - 1.9);
        double xd = r2d(x), ud = u2d(u);
        check_r("r_mul_u", sat_r(xd * ud), r_mul_u(x, u), tol_at(TOL_R_ROUND, xd * ud),
                "%.9g, %.12g", xd, ud);
        if (u != 0)
            check_r("r_div_u", sat_r(xd / ud), r_div_u(x, u), tol_at(TOL_R_ROUND, xd / ud),
                    "%.9g, %.12g", xd, ud);
    }
    checks_done();
}

static void test_primary_rays(void **state)
{
    (void)state;
    /* an axis-aligned camera and a tilted one (right = up x forward, all rounded to units) */
    static const double fwd[][3] = {{0, 0, 1}, {0.3, -0.2, -0.9}};
    for (int cam = 0; cam < 2; cam++) {
        double f[3], up[3] = {0, 1, 0}, r[3], u[3];
        double fl = sqrt(dd_dot(fwd[cam], fwd[cam]));
        for (int k = 0; k < 3; k++)
            f[k] = fwd[cam][k] / fl;
        r[0] = up[1] * f[2] - up[2] * f[1];
        r[1] = up[2] * f[0] - up[0] * f[2];
        r[2] = up[0] * f[1] - up[1] * f[0];
        u[0] = f[1] * r[2] - f[2] * r[1];
        u[1] = f[2] * r[0] - f[0] * r[2];
        u[2] = f[0] * r[1] - f[1] * r[0];
        dir3 fd = dir_from(f), rd = dir_from(r), ud = dir_from(u);
        double fe[3], re[3], ue[3];
        dd_from_dir(fd, fe);
        dd_from_dir(rd, re);
        dd_from_dir(ud, ue);
        /* the last one takes step * |ia| to 7.5, near the documented limit of 8 */
        static const double fovs[] = {10, 60, 120, 165.5};
        static const int32_t heights[] = {48, 480, 2048, 750};
        for (int v = 0; v < 4; v++) {
            unit step = d2u(tan(fovs[v] * PI_D / 360) / heights[v]);
            double sd = u2d(step);
            int32_t hmax = heights[v], wmax = heights[v] * 4 / 3;
            int32_t ias[] = {0, 1, -1, 7, -wmax, wmax, wmax / 3};
            int32_t ibs[] = {0, 1, -1, -5, -hmax, hmax, hmax / 2};
            for (int a = 0; a < 7; a++)
                for (int b = 0; b < 7; b++) {
                    double oa = sd * ias[a], ob = sd * ibs[b];
                    double e[3];
                    for (int k = 0; k < 3; k++)
                        e[k] = fe[k] + re[k] * oa + ue[k] * ob;
                    char what[96];
                    snprintf(what, sizeof what, "camera %d, fov %g, ia %d, ib %d", cam, fovs[v],
                             (int)ias[a], (int)ibs[b]);
                    check_dir("d3_ray", e, d3_ray(fd, rd, ud, step, ias[a], ibs[b]), TOL_RAY.abs,
                              what);
                }
        }
    }
    checks_done();
}

/* ---- reflection and refraction --------------------------------------------------------------- */

static void test_reflect_refract(void **state)
{
    (void)state;
    for (int i = 0; i < N_EDGE_D; i++) {
        dir3 d = dir_from(edge_dirs[i]);
        double de[3];
        dd_from_dir(d, de);
        for (int j = 0; j < N_EDGE_D; j++) {
            dir3 n = dir_from(edge_dirs[j]);
            double ne[3];
            dd_from_dir(n, ne);
            double k = dd_dot(de, ne), e[3];
            for (int c = 0; c < 3; c++)
                e[c] = de[c] - 2 * k * ne[c];
            char what[64];
            snprintf(what, sizeof what, "dir %d about dir %d", i, j);
            check_dir("d3_reflect", e, d3_reflect(d, n), TOL_NORM.abs, what);
        }
    }
    /* mirror at normal incidence and at 45 degrees */
    dir3 n = {0, U_ONE, 0};
    dir3 down = {0, -U_ONE, 0};
    dir3 r = d3_reflect(down, n);
    assert_true(r.x == 0 && r.y == U_ONE && r.z == 0);

    /* refraction against Snell's law, over angles of incidence and ratios of indices */
    static const double incid[] = {0, 1, 10, 30, 41, 45, 60, 75, 80, 89};
    static const double etas[] = {1.0, 1 / 1.5, 1.5, 1 / 1.33, 1.33, 1 / 2.4, 2.4, 0.5, 3.0};
    static const double normals[][3] = {{0, 1, 0}, {0.36, 0.48, 0.8}, {-1, 2, -2}};
    for (int ni = 0; ni < 3; ni++) {
        dir3 nd = dir_from(normals[ni]);
        double ne[3];
        dd_from_dir(nd, ne);
        /* a tangent perpendicular to the normal */
        double tg[3] = {ne[1], -ne[0], 0};
        if (fabs(ne[2]) > 0.9 || (ne[0] == 0 && ne[1] == 0)) {
            tg[0] = 0;
            tg[1] = ne[2];
            tg[2] = -ne[1];
        }
        double tl = sqrt(dd_dot(tg, tg));
        for (int i = 0; i < (int)(sizeof incid / sizeof incid[0]); i++) {
            double th = incid[i] * PI_D / 180, v[3];
            for (int c = 0; c < 3; c++)
                v[c] = -cos(th) * ne[c] + sin(th) * tg[c] / tl;
            dir3 d = dir_from(v);
            double de[3];
            dd_from_dir(d, de);
            for (int k = 0; k < (int)(sizeof etas / sizeof etas[0]); k++) {
                real eta = d2r(etas[k]);
                double et = r2d(eta), cosi = -dd_dot(de, ne);
                double kk = 1 - et * et * (1 - cosi * cosi);
                char what[96];
                snprintf(what, sizeof what, "normal %d, incidence %g deg, eta %.6g", ni, incid[i],
                         et);
                if (fabs(kk) < 1e-4)
                    continue; /* at the critical angle either answer is right */
                dir3 out = {7, 7, 7};
                int got = d3_refract(d, nd, eta, &out);
                check_i("d3_refract:ok", kk >= 0, got, 0.0, "%s", what);
                if (kk < 0 || !got)
                    continue;
                double m = et * cosi - sqrt(kk), e[3];
                for (int c = 0; c < 3; c++)
                    e[c] = et * de[c] + m * ne[c];
                check_dir("d3_refract", e, out, tol_at(TOL_REFRACT, et * et / sqrt(kk)), what);
            }
        }
    }
    /* normal incidence passes straight through; eta = 1 changes nothing */
    dir3 out;
    assert_int_equal(d3_refract(down, n, R(1.0 / 1.5), &out), 1);
    assert_true(out.x == 0 && out.y == -U_ONE && out.z == 0);
    dir3 obl = dir_from((const double[3]){0.6, -0.8, 0});
    assert_int_equal(d3_refract(obl, n, R_ONE, &out), 1);
    check_u("d3_refract", u2d(obl.x), out.x, TOL_NORM.abs, "eta 1: x");
    check_u("d3_refract", u2d(obl.y), out.y, TOL_NORM.abs, "eta 1: y");
    /* total internal reflection: glass to air at 45 degrees */
    dir3 g45 = dir_from((const double[3]){1, -1, 0});
    out = obl;
    assert_int_equal(d3_refract(g45, n, R(1.5), &out), 0);
    assert_true(out.x == obl.x && out.y == obl.y && out.z == obl.z); /* untouched */
    checks_done();
}

#if REAL_FIXED
/* The shadow test's square-root-free steps (r_sphere_span, r_sqrt_w_below) and the shadow cull's
 * one bound (r_cull): the same answers as the forms they replace, at random and at every
 * rounding edge of the square root (a = t^2 - t and t^2 + t, and one off). */
static void test_sphere_span(void **state)
{
    (void)state;
    int agree = 0;
    for (int k = 0; k < 400000; k++) {
        int64_t t = (int64_t)(rng() % ((uint64_t)2048 * 65536 + 1)); /* a root up to r = 2048 */
        static const int64_t off[] = {0, 1, -1};
        int64_t a = k % 4 == 0 ? (int64_t)(rng() % (((uint64_t)1 << 54) + 1))
                               : t * t + (k % 2 ? t : -t) + off[k % 3];
        if (a < 0)
            a = 0;
        if (a > ((int64_t)1 << 54))
            a = (int64_t)1 << 54;
        real thc = r_sqrt_w(a);
        /* tca and tmax at random, or where one of the compared values meets thc */
        int64_t lim = (int64_t)30572 * 65536;
        real tca = (real)((int64_t)(rng() % (uint64_t)(2 * lim + 1)) - lim);
        real tmax = (real)(rng() % ((uint64_t)30573 * 65536 + 1));
        switch (k % 5) {
        case 1: tca = thc + (real)(rng() % 3) - 1; break;              /* thc ~ tca */
        case 2: tca = -thc + (real)(rng() % 3) - 1; break;             /* thc ~ -tca */
        case 3: tmax = r_add(tca, thc) + (real)(rng() % 3) - 1; break; /* far ~ tmax */
        case 4: tmax = r_sub(tca, thc) + (real)(rng() % 3) - 1; break; /* near ~ tmax */
        default: break;
        }
        if (tmax < 0)
            tmax = 0;
        real hit = r_sub(tca, thc);
        if (hit <= 0)
            hit = r_add(tca, thc);
        int want = hit > 0 && hit < tmax;
        if (r_sphere_span(a, tca, tmax) != want)
            fail_msg("r_sphere_span(%lld, %d, %d) = %d, the square root gives %d", (long long)a,
                     tca, tmax, !want, want);
        int64_t lt = (int64_t)(rng() % ((uint64_t)1 << 30)) - ((int64_t)1 << 29);
        if (k % 3 == 0)
            lt = thc + (int64_t)(rng() % 3) - 1;
        if (r_sqrt_w_below(a, lt) != (thc < lt))
            fail_msg("r_sqrt_w_below(%lld, %lld) wrong (root %d)", (long long)a, (long long)lt,
                     thc);
        /* r_cull: "cd >= 0 or cd^2 < kc" for kc > 0 */
        wide kc = (wide)(rng() % ((uint64_t)1 << 60)) + 1;
        if (k % 2)
            kc = t * t + off[k % 3] + 1;
        real cd = k % 2 ? -(real)t + (real)(rng() % 3) - 1
                        : (real)((int64_t)(rng() % ((uint64_t)1 << 32)) - ((int64_t)1 << 31) + 1);
        if (r_cull_rejects(cd, r_cull(kc)) != (cd >= 0 || w_sq(cd) < kc))
            fail_msg("r_cull(%lld) rejects %d wrongly", (long long)kc, cd);
        agree++;
    }
    print_message("sphere span: %d cases agree with the square root, r_cull with (c.d)^2 < k\n",
                  agree);
    assert_int_equal(r_cull(0), 0);
    assert_int_equal(r_cull(-5), 0);
}
#endif

#if REAL_FIXED && FX_UNIT_FRAC == 30
/* A random unit vector as the tracer forms them: d3_norm of reals of mixed scales (some
 * components zero or tiny), or a sphere's normal (d3_norm_near). */
static dir3 rng_dir(void)
{
    real c[3];
    for (int i = 0; i < 3; i++)
        c[i] = rng() % 8 == 0 ? 0 : rng_real(-6, 12);
    if (c[0] == 0 && c[1] == 0 && c[2] == 0)
        c[1] = R_ONE;
    if (rng() % 3 == 0) { /* a point near a sphere minus its centre */
        real r = rng_real(-2, 10);
        r = r < 0 ? -r : r;
        dir3 u = d3_norm(v3(c[0], c[1], c[2]), 0);
        vec3 v = v3(r_mul_u(r, u.x), r_mul_u(r, u.y), r_mul_u(r, u.z));
        if (!v3_is_zero(v))
            return d3_norm_near(v, r_inv_len(r));
    }
    return d3_norm(v3(c[0], c[1], c[2]), 0);
}

/* d3_reflect_k's renormalisation (fx_renorm_unit): for unit d and n the mirrored vector is unit
 * to within 2^-23, so the release build's form without fx_renorm's checks and square term gives
 * fx_renorm's result. Checked on random directions and normals, on chains of mirrorings (the
 * tracer's bounces) and at grazing and normal incidence, with no FX_EV_OVERFLOW (the event
 * build counts one where the bound fails); the worst length error is printed. */
static void test_reflect_unit(void **state)
{
    (void)state;
    fx_events_reset();
    double worst = 0;
    dir3 d = rng_dir();
    for (int k = 0; k < 300000; k++) {
        dir3 n = rng_dir();
        if (k % 5 == 0) /* grazing: n at right angles to d, to rounding */
            n = d3_cross(d, d3_cross(d, n, 0), 0);
        if (k % 7 == 0) /* normal incidence */
            n = d3_neg(d);
        if (n.x == 0 && n.y == 0 && n.z == 0)
            continue;
        unit dn = d3_dot(d, n);
        const int64_t half = (int64_t)1 << 29;
        const int32_t m = -dn;
        int64_t x = 2 * ((int64_t)d.x * half + (int64_t)m * n.x);
        int64_t y = 2 * ((int64_t)d.y * half + (int64_t)m * n.y);
        int64_t z = 2 * ((int64_t)d.z * half + (int64_t)m * n.z);
        double len = sqrt(ldexp((double)x, -60) * ldexp((double)x, -60) +
                          ldexp((double)y, -60) * ldexp((double)y, -60) +
                          ldexp((double)z, -60) * ldexp((double)z, -60));
        if (fabs(len - 1) > worst)
            worst = fabs(len - 1);
        dir3 fast = fx_renorm_unit_fast(x, y, z); /* the release builds' form */
        dir3 want = fx_renorm(x, y, z), got = d3_reflect_k(d, n, dn);
        if (fast.x != want.x || fast.y != want.y || fast.z != want.z || got.x != want.x ||
            got.y != want.y || got.z != want.z) {
            n_failed++;
            print_error("reflection %d: release form (%d %d %d), fx_renorm (%d %d %d)\n", k, fast.x,
                        fast.y, fast.z, want.x, want.y, want.z);
            break;
        }
        d = k % 3 == 0 ? rng_dir() : got; /* chains of mirrorings */
    }
    print_message("reflect: worst |length - 1| of the mirrored vector %.3g (bound 2^-23 = %.3g)\n",
                  worst, ldexp(1, -23));
    assert_true(worst < ldexp(1, -23));
    /* (domain events: the grazing normals' cross products of parallel vectors, skipped) */
    check_events("d3_reflect_k", 0, fx_event_count[FX_EV_DOMAIN]);
    checks_done();
}
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_real_arithmetic, reset_checks),
        cmocka_unit_test_setup(test_real_conversions, reset_checks),
        cmocka_unit_test_setup(test_to_byte, reset_checks),
        cmocka_unit_test_setup(test_domain_events, reset_checks),
#if REAL_FIXED
        cmocka_unit_test_setup(test_saturation, reset_checks),
#endif
        cmocka_unit_test_setup(test_no_events_in_range, reset_checks),
        cmocka_unit_test_setup(test_units, reset_checks),
        cmocka_unit_test_setup(test_trig, reset_checks),
        cmocka_unit_test_setup(test_wide, reset_checks),
#if REAL_FIXED
        cmocka_unit_test_setup(test_fixed_internals, reset_checks),
        cmocka_unit_test_setup(test_armv6m_products, reset_checks),
        cmocka_unit_test_setup(test_sphere_span, reset_checks),
#endif
        cmocka_unit_test_setup(test_vectors, reset_checks),
        cmocka_unit_test_setup(test_primary_rays, reset_checks),
        cmocka_unit_test_setup(test_reflect_refract, reset_checks),
#if REAL_FIXED && FX_UNIT_FRAC == 30
        cmocka_unit_test_setup(test_reflect_unit, reset_checks),
#endif
    };
#ifdef TEST_NUMERIC_REPORT
    return cmocka_run_group_tests(tests, NULL, print_worst);
#else
    return cmocka_run_group_tests(tests, NULL, NULL);
#endif
}
