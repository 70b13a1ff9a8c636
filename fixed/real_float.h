/* real_float.h: float operations of the numeric layer (included by real.h only).
 *
 * The same functions as real_fixed.h with plain IEEE single precision; the tracer cannot tell
 * the two apart. Build with -ffp-contract=off so that no fused multiply-add changes results
 * between machines.
 */
#ifndef FIXRAY_REAL_FLOAT_H
#define FIXRAY_REAL_FLOAT_H

#include <math.h>
#include <stdint.h>

#define R(x) ((real)(x))
#define U(x) ((unit)(x))
#define R_ONE 1.0f
#define U_ONE 1.0f
/* The largest meaningful magnitude, the same as the fixed build's range. */
#define R_MAX 32767.99998f
#define R_PI 3.14159265f
#define R_LSB 1.1920929e-7f
#define U_LSB 1.1920929e-7f

/* With event counting (the test builds), every result is checked: a NaN or an infinity is
 * counted as FX_EV_NONFINITE where it is produced. Without it the check compiles to nothing. */
#if FX_COUNT_EVENTS
static inline float fl_chk(float x)
{
    if (!isfinite(x))
        FX_EVENT(FX_EV_NONFINITE);
    return x;
}
#else
#define fl_chk(x) (x)
#endif

/* ---- real -------------------------------------------------------------------------------- */

static inline real r_from_int(int32_t i) { return (real)i; }

/* A Q16.16 integer (65536 = 1.0) as a real: exact below 256 in magnitude. */
static inline real r_from_q16(int32_t v) { return (real)v * (1.0f / 65536.0f); }

/* A value in [0, 1] as a Q16.16 integer (0..65536), rounded. */
static inline int32_t r_unit_to_q16(real a) { return (int32_t)(a * 65536.0f + 0.5f); }

static inline int32_t r_to_int(real a) { return (int32_t)floorf(a + 0.5f); }

static inline real r_from_ratio(int32_t num, int32_t den) { return fl_chk((real)num / (real)den); }

static inline real r_add(real a, real b) { return fl_chk(a + b); }

static inline real r_sub(real a, real b) { return fl_chk(a - b); }

static inline real r_neg(real a) { return -a; }

static inline real r_abs(real a) { return fabsf(a); }

static inline real r_mul(real a, real b) { return fl_chk(a * b); }

/* a * 2^-n by a product with the exact power of two (folded to a constant for a constant n):
 * the same correctly rounded result as ldexpf, without the library call. */
static inline real r_shr(real a, int n)
{
    return n >= 0 && n < 32 ? a * (1.0f / (float)(1u << n)) : ldexpf(a, -n);
}

/* v * g for g in {-1, 0, 1}: g > 0 ? v : g < 0 ? -v : 0 (a product would give -0 for g = 0
 * and v < 0, so it stays a selection). */
/* In-range arithmetic: the same operations (the fixed build's release form skips range checks). */
static inline real r_mul_in(real a, real b) { return r_mul(a, b); }
static inline real r_add_in(real a, real b) { return r_add(a, b); }
static inline real r_neg_in(real a) { return r_neg(a); }
/* r_mul_in of two colour values or weights (the fixed build's r_mul_c): the same. */
static inline real r_mul_c(real a, real b) { return r_mul_in(a, b); }

static inline real r_mul_sign(real v, int g) { return g > 0 ? v : (g < 0 ? -v : 0.0f); }

static inline real r_muli(real a, int32_t i) { return fl_chk(a * (real)i); }

static inline real r_div(real a, real b)
{
    if (b == 0.0f) {
        FX_EVENT(FX_EV_DOMAIN);
        return a == 0.0f ? 0.0f : (a < 0.0f ? -R_MAX : R_MAX);
    }
    return fl_chk(a / b);
}

static inline real r_sqrt(real a)
{
    if (a < 0.0f) {
        FX_EVENT(FX_EV_DOMAIN);
        return 0.0f;
    }
    return fl_chk(sqrtf(a));
}

static inline real r_sin(real a) { return fl_chk(sinf(a)); }

static inline real r_cos(real a) { return fl_chk(cosf(a)); }

/* floor(x) and x - floor(x). On x86-64 without SSE4.1 (the default target), where floorf is no
 * instruction but an inlined sequence of about 17 with a branch, from the truncated integer
 * instead: n = (int32_t)x, one less where x lies below it, and floor(x) = n with x's sign (a
 * zero floor keeps it: floorf(-0.0) is -0.0), so the same bits as floorf for every x the
 * callers give (|x| < 2^31: the integer is taken in both; beyond 2^23 x is an integer and n is
 * x). The noise lattice (noise_q16, two a coordinate), checker cells (r_mul_round_in) and the
 * palettes take it per texture look-up. */
static inline real r_floor_split(real x, int32_t *i)
{
#if defined(__x86_64__) && !defined(__SSE4_1__)
    int32_t n = (int32_t)x;
    real t = (real)n;
    if (x < t) {
        n--;
        t -= 1.0f; /* exact: |t| <= 2^23 here */
    }
    *i = n;
    return x - copysignf(t, x);
#else
    real f = floorf(x);
    *i = (int32_t)f;
    return x - f;
#endif
}

/* floor(a * b + 1/2) (the fixed build forms it from one 64-bit sum). */
static inline int32_t r_mul_round_in(real a, real b)
{
    int32_t i;
    r_floor_split(r_add(r_mul(a, b), 0.5f), &i);
    return i;
}

static inline real r_mod(real x, real m)
{
    real r = fmodf(x, m);
    return r < 0.0f ? r + m : r;
}

/* x modulo m for m a positive power of two: bit for bit what r_mod returns (the same single
 * rounding of the same exact value, and fmodf's zero with the sign of x), without fmodf's
 * library call: x / m and m * floor(x / m) are exact, unless x / m underflows. */
static inline real r_mod_pow2(real x, real m)
{
    real r = x - m * floorf(x / m);
    if (r < 0.0f)
        r = r + m; /* only when x / m underflowed to -0 (tiny negative x): fmodf's x + m */
    return r == 0.0f ? copysignf(0.0f, x) : r;
}

/* r_mod_pow2(r_muli(x, 2), m) for x = r_mod_pow2(y, m), i.e. in [0, m] or -0: 2x < 4m is
 * exact, so at most two exact subtractions of m give the same bits (zeros signed alike)
 * without the floor. */
static inline real r_mod_pow2_twice(real x, real m)
{
    real t = x * 2.0f;
    if (t >= m)
        t = t - m;
    if (t >= m)
        t = t - m;
    return t;
}

static inline real r_mul_u(real a, unit u) { return fl_chk(a * u); }

static inline real r_mul_u_in(real a, unit u) { return r_mul_u(a, u); }

static inline real r_div_u(real a, unit b) { return r_div(a, b); }

/* r_div_u(a, b) for a >= 0 and b > 0 (the fixed build skips the signs there). */
static inline real r_div_u_pos(real a, unit b) { return r_div_u(a, b); }

/* Is r_div_u(a, b) > s (a > 0, b > 0, s >= 0)? */
static inline int r_div_u_above(real a, unit b, real s) { return r_div_u(a, b) > s; }

/* ---- unit -------------------------------------------------------------------------------- */

static inline unit u_mul(unit a, unit b) { return fl_chk(a * b); }

static inline unit u_mul_in(unit a, unit b) { return u_mul(a, b); }

static inline unit u_neg(unit a) { return -a; }

static inline unit u_neg_in(unit a) { return u_neg(a); }

static inline unit u_add(unit a, unit b) { return fl_chk(a + b); }

/* u_add inside a proven bound (the fixed build's u_add_in): the same. */
static inline unit u_add_in(unit a, unit b) { return u_add(a, b); }

static inline unit u_muli(unit a, int32_t i) { return fl_chk(a * (unit)i); }

static inline unit u_from_real(real a) { return a; }

static inline real u_to_real(unit a) { return a; }

static inline unit u_divi(unit a, int32_t i) { return a / (float)i; }

static inline unit u_div(unit a, unit b) { return r_div(a, b); }

/* The camera's step per half pixel: tan / height with tan = s / c. */
static inline ustep u_tan_step(unit s, unit c, int32_t height)
{
    return u_divi(u_div(s, c), height);
}

static inline void u_sincos_deg(real deg, unit *s, unit *c)
{
    float rad = fmodf(deg, 360.0f) * (R_PI / 180.0f);
    *s = sinf(rad);
    *c = cosf(rad);
}

static inline uint8_t r_to_byte(real c)
{
    if (fl_chk(c) <= 0.0f)
        return 0;
    if (c >= 1.0f)
        return 255;
    return (uint8_t)(c * 255.0f + 0.5f);
}

/* ---- wide -------------------------------------------------------------------------------- */

static inline wide w_sq(real a) { return fl_chk(a * a); }

static inline wide w_mul(real a, real b) { return fl_chk(a * b); }

static inline wide w_add(wide a, wide b) { return a + b; }

static inline wide w_sub(wide a, wide b) { return a - b; }

static inline wide w_len2(vec3 a) { return fl_chk(a.x * a.x + a.y * a.y + a.z * a.z); }

static inline real r_sqrt_w(wide a) { return r_sqrt(a); }
static inline real r_sqrt_w_in(wide a) { return r_sqrt_w(a); }

static inline real r_hypot(real a, real b) { return fl_chk(sqrtf(a * a + b * b)); }

/* ---- vectors ----------------------------------------------------------------------------- */

static inline real v3_dot_d(vec3 v, dir3 d) { return fl_chk(v.x * d.x + v.y * d.y + v.z * d.z); }

/* Is v . d > 0? */
static inline int v3_faces(vec3 v, dir3 d) { return v.x * d.x + v.y * d.y + v.z * d.z > 0; }

static inline unit d3_dot(dir3 a, dir3 b) { return fl_chk(a.x * b.x + a.y * b.y + a.z * b.z); }

/* Is a . b < 0 (as d3_dot forms it)? */
static inline int d3_below(dir3 a, dir3 b) { return d3_dot(a, b) < 0; }

static inline vec3 d3_scale(dir3 d, real s)
{
    vec3 v = {d.x * s, d.y * s, d.z * s};
    return v;
}

static inline dir3 fl_norm(float x, float y, float z, real *len)
{
    float l = fl_chk(sqrtf(x * x + y * y + z * z));
    dir3 d = {0.0f, 0.0f, 0.0f};
    if (len)
        *len = l;
    if (l == 0.0f) {
        FX_EVENT(FX_EV_DOMAIN);
        return d;
    }
    float inv = fl_chk(1.0f / l);
    d.x = x * inv;
    d.y = y * inv;
    d.z = z * inv;
    return d;
}

static inline dir3 d3_norm(vec3 v, real *len) { return fl_norm(v.x, v.y, v.z, len); }

/* d3_norm(v, &len) with the unit vector into *out and the length returned. */
static inline real d3_norm_len(vec3 v, dir3 *out)
{
    real len;
    *out = fl_norm(v.x, v.y, v.z, &len);
    return len;
}

/* 1/r prepared for d3_norm_near (the float build normalises exactly and does not use it). */
static inline rinv r_inv_len(real r) { return r; }

/* Unit vector along v, whose length is about the r that k was made from. */
static inline dir3 d3_norm_near(vec3 v, rinv k)
{
    (void)k;
    return fl_norm(v.x, v.y, v.z, 0);
}

static inline dir3 d3_ray(dir3 f, dir3 r, dir3 u, ustep step, int32_t ia, int32_t ib)
{
    float a = step * (float)ia, b = step * (float)ib;
    return fl_norm(f.x + r.x * a + u.x * b, f.y + r.y * a + u.y * b, f.z + r.z * a + u.z * b, 0);
}

/* d3_ray of the vectors in place (the fixed build's form for the camera). */
static inline dir3 d3_ray_at(const dir3 *f, const dir3 *r, const dir3 *u, ustep step, int32_t ia,
                             int32_t ib)
{
    return d3_ray(*f, *r, *u, step, ia, ib);
}

static inline dir3 d3_cross(dir3 a, dir3 b, real *len)
{
    return fl_norm(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x, len);
}

/* d3_reflect and d3_refract given dn = d3_dot(d, n) (the fixed build's d3_reflect_k,
 * d3_refract_k). */
static inline dir3 d3_reflect_k(dir3 d, dir3 n, unit dn)
{
    float k = 2.0f * dn;
    return fl_norm(d.x - k * n.x, d.y - k * n.y, d.z - k * n.z, 0);
}

static inline dir3 d3_reflect(dir3 d, dir3 n) { return d3_reflect_k(d, n, d3_dot(d, n)); }

static inline int d3_refract_k(dir3 d, dir3 n, unit dn, real eta, dir3 *out)
{
    float cosi = -dn;
    float k = 1.0f - eta * eta * (1.0f - cosi * cosi);
    if (k < 0.0f)
        return 0;
    float m = eta * cosi - sqrtf(k);
    *out = fl_norm(eta * d.x + m * n.x, eta * d.y + m * n.y, eta * d.z + m * n.z, 0);
    return 1;
}

static inline int d3_refract(dir3 d, dir3 n, real eta, dir3 *out)
{
    return d3_refract_k(d, n, d3_dot(d, n), eta, out);
}

static inline vec3 v3_sub_in(vec3 a, vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline real v3_dot_d_in(vec3 v, dir3 d) { return v3_dot_d(v, d); }
static inline vec3 d3_scale_in(dir3 d, real s) { return d3_scale(d, s); }
#endif
