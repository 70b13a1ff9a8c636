/* real.h: the numeric layer: one scalar type and vector operations, float or fixed at compile time.
 *
 * The tracer is written once against this header. REAL_FIXED selects the number system:
 *   0  float: real, unit and wide are all `float` (real_float.h);
 *   1  fixed: real is libfixmath's Q16.16 fix16_t, unit is Q2.30 (unit-vector components and
 *      cosines, with 64-bit products), wide is Q32.32 in 64 bits (squared lengths)
 *      (real_fixed.h). FX_UNIT_FRAC (fixed only) sets unit's fraction bits: 30 (the default,
 *      Q2.30) or 16 (plain Q16.16: the cheaper, less precise variant rt-fixed16, see
 *      docs/numerics.md).
 *
 * Types:
 *   real   positions, distances, colours, coefficients        (Q16.16 | float)
 *   unit   components of unit vectors, cosines, in [-2, 2)      (Q2.30 or Q16.16 | float)
 *   ustep  the camera's image-plane step per half pixel        (Q2.30 in both fixed | float)
 *   wide   squares of reals: squared lengths, discriminants    (Q32.32 | float)
 *   vec3   three reals; dir3: three units (a direction, |d| = 1)
 * Literals: R(1.5) for real, U(0.5) for unit: constant expressions, folded by the compiler.
 * Comparisons of two values of the same type may use the C operators (<, >, ==) in both
 * builds; arithmetic goes through the functions so that the fixed build can saturate.
 *
 * Fixed-point arithmetic never wraps: a result out of range saturates to +-R_MAX, and a
 * domain error (square root of a negative, division by zero, normalising a zero vector)
 * returns a defined value. With FX_COUNT_EVENTS=1 each such event is counted in
 * fx_event_count[] so that tests can assert none happened; the float build then also counts
 * every NaN or infinity an operation returns (FX_EV_NONFINITE).
 *
 * Names: the prefix says the type worked on, the suffixes what the caller promises or gets.
 * Prefixes:
 *   r_   real          u_   unit          w_   wide           fx_  the fixed build's helpers
 *   v3_  vec3          d3_  dir3          c3_  colour (a vec3 in [0, 1161], docs/numerics.md)
 * Operand suffixes (what the second operand is):
 *   _u   a unit (r_mul_u: real x unit)     _i   an int (r_muli, u_divi)
 *   _d   a dir3 (v3_dot_d)                 _w   a wide (r_sqrt_w: the root of a wide)
 * Promise suffixes (the caller guarantees more, the operation checks less; the event-counting
 * builds take the checked form, so a broken promise shows there as FX_EV_OVERFLOW):
 *   _in     the result is in range (docs/numerics.md bounds it): no saturation test
 *   _c      both operands are colours or weights, in [0, 1161]: r_mul_in without the sign term
 *   _p      c3_ operations on such non-negative colours (through r_mul_c)
 *   _pos    both operands positive (r_div_u_pos): no signs, no zero divisor
 * Shortcut suffixes (the same answer by a cheaper route):
 *   _k      takes a product the caller has already formed (d3_reflect_k: dn = d . n)
 *   _near   the input is near a known length (d3_norm_near: |v| near the r of rinv k)
 *   _fast   the input is near unit length: the correction without its checks (fx_renorm_unit)
 *   _above, _below   a comparison with a bound without forming the value compared
 *                    (r_div_u_above: a quotient; d3_below: a . b < 0)
 *   _from   completes a part prepared once for many calls (v3_dot_d_from)
 * Other suffixes: _len (d3_norm_len: the length too), _to (writes through a pointer), _at (takes
 * its vectors by pointer), _pow2 (for a power-of-two modulus), _round (rounded, not truncated),
 * _q16 / _q30 (a raw Q16.16 or Q2.30 integer in or out), _w32 / _w64 (fx_sat for 32- or 64-bit
 * machines).
 * The tracer's own kernels built on these (r_cull, r_sphere_span, r_perp_within, v3_dot_part)
 * are in src/core/rt_kernels.h.
 */
#ifndef FIXRAY_REAL_H
#define FIXRAY_REAL_H

#include <stdint.h>

#ifndef REAL_FIXED
#define REAL_FIXED 0
#endif
#ifndef FX_COUNT_EVENTS
#define FX_COUNT_EVENTS 0
#endif
#if REAL_FIXED != 0 && REAL_FIXED != 1
#error "REAL_FIXED must be 0 (float) or 1 (fixed point)"
#endif
#ifndef FX_UNIT_FRAC
#define FX_UNIT_FRAC 30
#endif
#if FX_UNIT_FRAC != 30 && FX_UNIT_FRAC != 16
#error "FX_UNIT_FRAC must be 30 (unit in Q2.30) or 16 (unit in Q16.16)"
#endif
#if FX_UNIT_FRAC != 30 && !REAL_FIXED
#error "FX_UNIT_FRAC applies to the fixed-point build only"
#endif
/* The number system's name, as the programs print it (real=...). */
#if !REAL_FIXED
#define REAL_NAME "float"
#elif FX_UNIT_FRAC == 30
#define REAL_NAME "fixed"
#else
#define REAL_NAME "fixed16"
#endif

/* Kinds of numeric events (only counted when FX_COUNT_EVENTS=1): saturation, domain errors,
 * and in the float build any operation that produced a NaN or an infinity. */
enum { FX_EV_OVERFLOW, FX_EV_DOMAIN, FX_EV_NONFINITE, FX_EV_COUNT };
#if FX_COUNT_EVENTS
extern unsigned long fx_event_count[FX_EV_COUNT];
/* Resets the event counters to zero. */
void fx_events_reset(void);
/* Atomic: bands of a frame may run on several threads. */
#define FX_EVENT(k) ((void)__atomic_fetch_add(&fx_event_count[k], 1, __ATOMIC_RELAXED))
#else
#define FX_EVENT(k) ((void)0)
#endif

/* Code the ARM926 board image compiles as Thumb at -Os, within files otherwise ARM code at -O2:
 * functions that run outside the counted frames (once per frame or per command) or only in
 * non-default modes (probe mode), where Thumb's smaller code costs no rendering instruction of
 * the default settings (Makefile, ARM_COLD_SRCS; docs/arm.md). Nothing elsewhere (x86-64, the
 * Cortex-M3's Thumb-2). GCC documents its optimize attribute as a tool for such tuning rather
 * than for setting options in production code: only -Os is asked for here, the file's other
 * flags stay, and the pictures are byte-identical with and without it (tests/arm.sh compares the
 * board's frames with the host's). A function marked so must not inline r_add and the like,
 * whose saturating __qadd Thumb-1 lacks (the compiler refuses it). */
#if defined(__arm__) && !defined(__thumb2__)
#define FX_BOARD_THUMB __attribute__((target("thumb"), optimize("Os")))
#else
#define FX_BOARD_THUMB
#endif

#if REAL_FIXED
#include <fix16.h>
typedef fix16_t real;  /* Q16.16 */
typedef int32_t unit;  /* Q2.30 (FX_UNIT_FRAC 30) or Q16.16 (16) */
typedef int32_t ustep; /* Q2.30 */
typedef int64_t wide;  /* Q32.32 */
typedef struct rinv {  /* 1/r prepared for d3_norm_near: m = 2^s / r, and r */
    uint32_t m;
    int32_t s;
    fix16_t r;
} rinv;
#else
typedef float real;
typedef float unit;
typedef float ustep;
typedef float wide;
typedef float rinv;
#endif

typedef struct vec3 {
    real x, y, z;
} vec3;

typedef struct dir3 {
    unit x, y, z;
} dir3;

static inline vec3 v3(real x, real y, real z)
{
    vec3 v = {x, y, z};
    return v;
}

#if REAL_FIXED
#include "real_fixed.h"
#else
#include "real_float.h"
#endif

/* Limits of the scene, the same in both builds: every coordinate lies within +-R_SCENE_MAX,
 * so differences of positions stay within 2 * R_SCENE_MAX and squared lengths fit in wide.
 * R_T_MAX bounds ray distances (longer than any segment inside the scene cube). */
#define R_SCENE_MAX R(4096.0)
#define R_T_MAX R(16384.0)
/* Secondary rays start this far off the surface along the normal: larger than the error of
 * a hit point in either build (see docs/numerics.md), small against any object. */
#define R_EPS_OFFSET R(0.001953125)
/* A ray whose cosine with a plane is below this is treated as parallel to it. */
#define U_EPS_PARALLEL U(0.0001)
/* The camera's up vector counts as parallel to the view when the squared cosine of their angle
 * exceeds this: a sine below 2^-10 (with unit in Q16.16, whose step is 2^-16, below 2^-8). */
#if FX_UNIT_FRAC == 16
#define U_COS2_PARALLEL (U_ONE - U_LSB)
#else
#define U_COS2_PARALLEL U(1.0 - 1.0 / 1048576)
#endif
/* A unit vector's length is 1 to within 2^-U_LEN_ERR_SHIFT / 4 (fixed Q2.30: 2^-28, float:
 * 2^-21 is well inside; unit in Q16.16: 1.3 * 2^-16): margins that scale with it use this. */
#if FX_UNIT_FRAC == 16
#define U_LEN_ERR_SHIFT 14
#else
#define U_LEN_ERR_SHIFT 18
#endif

static inline vec3 v3_add(vec3 a, vec3 b)
{
    return v3(r_add(a.x, b.x), r_add(a.y, b.y), r_add(a.z, b.z));
}

static inline vec3 v3_sub(vec3 a, vec3 b)
{
    return v3(r_sub(a.x, b.x), r_sub(a.y, b.y), r_sub(a.z, b.z));
}

static inline vec3 v3_scale(vec3 a, real s)
{
    return v3(r_mul(a.x, s), r_mul(a.y, s), r_mul(a.z, s));
}

/* Component-wise product (colours). */
static inline vec3 v3_mul(vec3 a, vec3 b)
{
    return v3(r_mul(a.x, b.x), r_mul(a.y, b.y), r_mul(a.z, b.z));
}

/* a + b * s, component-wise. */
static inline vec3 v3_madd(vec3 a, vec3 b, real s) { return v3_add(a, v3_scale(b, s)); }

/* Colours (rt_color): a * s, a * b component-wise, and a + b * s, by r_mul_in and r_add_in: no
 * range check in the fixed release build, where the colour bound makes none necessary. */
static inline vec3 c3_scale(vec3 a, real s)
{
    return v3(r_mul_in(a.x, s), r_mul_in(a.y, s), r_mul_in(a.z, s));
}

static inline vec3 c3_mul(vec3 a, vec3 b)
{
    return v3(r_mul_in(a.x, b.x), r_mul_in(a.y, b.y), r_mul_in(a.z, b.z));
}

static inline vec3 c3_madd(vec3 a, vec3 b, real s)
{
    return v3(r_add_in(a.x, r_mul_in(b.x, s)), r_add_in(a.y, r_mul_in(b.y, s)),
              r_add_in(a.z, r_mul_in(b.z, s)));
}

/* The same for the shading's non-negative colours and weights (within [0, 1161]; not for
 * differences of colours): products by r_mul_c, the same values. */
static inline vec3 c3_scale_p(vec3 a, real s)
{
    return v3(r_mul_c(a.x, s), r_mul_c(a.y, s), r_mul_c(a.z, s));
}

static inline vec3 c3_mul_p(vec3 a, vec3 b)
{
    return v3(r_mul_c(a.x, b.x), r_mul_c(a.y, b.y), r_mul_c(a.z, b.z));
}

static inline vec3 c3_madd_p(vec3 a, vec3 b, real s)
{
    return v3(r_add_in(a.x, r_mul_c(b.x, s)), r_add_in(a.y, r_mul_c(b.y, s)),
              r_add_in(a.z, r_mul_c(b.z, s)));
}

/* The point o + d * t on a ray. */
static inline vec3 v3_along(vec3 o, dir3 d, real t)
{
    return v3(r_add(o.x, r_mul_u(t, d.x)), r_add(o.y, r_mul_u(t, d.y)),
              r_add(o.z, r_mul_u(t, d.z)));
}

/* v3_along where the result is known to lie inside real's range: o inside the scene cube (the
 * eye, or a point checked with v3_within) and 0 <= t < R_T_MAX, so within R_SCENE_MAX + R_T_MAX
 * = 20480 of the centre; or o such a point and |t| <= R_EPS_OFFSET. In the fixed release build
 * it is formed without range checks (r_mul_u_in, r_add_in). */
static inline vec3 v3_along_in(vec3 o, dir3 d, real t)
{
    return v3(r_add_in(o.x, r_mul_u_in(t, d.x)), r_add_in(o.y, r_mul_u_in(t, d.y)),
              r_add_in(o.z, r_mul_u_in(t, d.z)));
}

/* Is every coordinate of p within [-lim, lim]? */
static inline int v3_within(vec3 p, real lim)
{
#if REAL_FIXED
    /* for 0 <= lim <= R_MAX: a in [-lim, lim] exactly when a + lim, taken modulo 2^32, is at most
     * 2 lim (one add and one unsigned compare a coordinate) */
    uint32_t span = 2u * (uint32_t)lim;
    return ((uint32_t)p.x + (uint32_t)lim <= span) & ((uint32_t)p.y + (uint32_t)lim <= span) &
        ((uint32_t)p.z + (uint32_t)lim <= span);
#else
    return p.x <= lim && p.x >= -lim && p.y <= lim && p.y >= -lim && p.z <= lim && p.z >= -lim;
#endif
}

/* Is v the zero vector (which has no direction: test before d3_norm)? */
static inline int v3_is_zero(vec3 v) { return v.x == 0 && v.y == 0 && v.z == 0; }

static inline dir3 d3_neg(dir3 d)
{
    dir3 n = {u_neg(d.x), u_neg(d.y), u_neg(d.z)};
    return n;
}

/* Linear interpolation a + (b - a) * t. */
static inline real r_lerp(real a, real b, real t) { return r_add(a, r_mul(r_sub(b, a), t)); }

static inline real r_clamp(real x, real lo, real hi) { return x < lo ? lo : (x > hi ? hi : x); }

static inline real r_min(real a, real b) { return a < b ? a : b; }

static inline real r_max(real a, real b) { return a > b ? a : b; }

/* base^n for base in [0, 1] (to a few steps of unit) and n >= 1, by repeated squaring (the same
 * steps in both builds; every product within [0, 1], so u_mul_in). The result starts as the
 * power of n's lowest set bit itself: the same value as U_ONE times it (a product by one is
 * exact), one product fewer; the squarings stop at n's top bit. */
static inline unit u_pow(unit base, unsigned n)
{
    if (n == 0)
        return U_ONE;
    for (; !(n & 1u); n >>= 1)
        base = u_mul_in(base, base);
    unit result = base;
    while (n >>= 1) {
        base = u_mul_in(base, base);
        if (n & 1u)
            result = u_mul_in(result, base);
    }
    return result;
}

#endif
