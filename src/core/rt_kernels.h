/* rt_kernels.h: the sphere test's and the shadow rays' numeric kernels, in both builds (float and fixed).
 *
 * Steps of the tracer's intersection tests written against the number formats themselves: the
 * shadow rays' one-compare rejection of a sphere (r_cull), the shadow segment's last step
 * without a square root (r_sphere_span), the sphere test's discriminant (r_perp_within), and a
 * ray's dot products against many centres (v3_dot_part). Each has its fixed-point form, whose
 * reasoning is beside it, and its float twin; tests/test_numeric.c checks the fixed forms
 * against the plain ones. They live with the tracer (shapes.c, prepare.c), not in fixed/,
 * which holds the numeric primitives only.
 */
#ifndef FIXRAY_RT_KERNELS_H
#define FIXRAY_RT_KERNELS_H

#include "real.h"

#if REAL_FIXED

typedef int32_t rcull; /* a sphere's quick ray rejection as a bound on c . d: r_cull */

/* A sphere's quick rejection of rays, the test "c . d >= 0 or (c . d)^2 < k" for a k > 0
 * (rt_scene_prepare's scene_cull), prepared once per frame as one bound: for an integer cd < 0,
 * cd^2 < k exactly when -cd < T, T = ceil(sqrt(k)) (T >= 1), so the test is cd > -T, one 32-bit
 * compare. T is below 2^30 for the scene's k (below |c|^2, |c| < 14190); it is capped at R_MAX
 * all the same. k <= 0 (no rejection) gives 0, which r_cull_rejects is not asked about. */
static inline rcull r_cull(wide k)
{
    if (k <= 0)
        return 0;
    uint64_t t = fx_isqrt64((uint64_t)k); /* rounded: ceil(sqrt(k)) or one below */
    if (t * t < (uint64_t)k)
        t++;
    return t > (uint64_t)R_MAX ? -R_MAX : -(rcull)t;
}

/* Does the rejection c (non-zero, from r_cull) reject a ray with c . d = cd? */
static inline int r_cull_rejects(real cd, rcull c) { return cd > c; }

/* r_sqrt_w(a) < t, for 0 <= a <= 2^56 and any t, without the square root: r_sqrt_w is
 * fx_isqrt64, the rr with a - rr^2 in (-rr, rr], at most 2^28; for t >= 1, rr < t exactly when
 * rr <= t - 1, i.e. when a <= (t - 1)^2 + (t - 1) = t^2 - t (x^2 + x grows with x). */
static inline int r_sqrt_w_below(wide a, int64_t t)
{
    if (t <= 0)
        return 0;
    if (t > ((int64_t)1 << 28))
        return 1;
    uint32_t u = (uint32_t)t; /* in [1, 2^28]: t^2 - t = t (t - 1), one 32 x 32-bit product */
    return a <= (int64_t)(FX_UMUL(u, (u - 1)));
}

/* The sphere test's last step for a shadow segment, without its square root: with
 * thc = r_sqrt_w(a) (a = r^2 - |perp|^2 in [0, r^2], r <= 2048: a <= 2^54), the near hit
 * tca - thc if positive, else the far one tca + thc: is it in (0, tmax)? The same answer as
 * forming them (|tca| <= 30572 and thc <= 2048, so neither sum saturates), from comparisons of
 * thc with the integers tca - tmax, -tca and tmax - tca (formed in 64 bits). */
static inline int r_sphere_span(wide a, real tca, real tmax)
{
    if (r_sqrt_w_below(a, tca)) /* thc < tca: the near hit is positive; before tmax? */
        return !r_sqrt_w_below(a, (int64_t)tca - tmax + 1);
    return !r_sqrt_w_below(a, 1 - (int64_t)tca) && r_sqrt_w_below(a, (int64_t)tmax - tca);
}

/* The sphere test's discriminant step: is |perp|^2 <= r2, perp = v3_sub_in(l, d3_scale_in(d,
 * tca)) and r2 = w_sq(r) (r > 0, a sphere's radius2)? Where it is, *d2 gets w_len2(perp). The
 * same answer with fewer instructions for most misses: each component is tested as it is
 * formed, and one beyond r (|p| >= r + 1 step) already has p^2 >= (r + 1)^2 > r^2, so |perp|^2 >
 * r2 exactly (the squares are exact integers, none negative): the rest is not formed. |p| > r
 * as one unsigned compare, p + r > 2r (2r <= 2^28, |p| < 2^31: no wrap past it). */
static inline int r_perp_within(vec3 l, dir3 d, real tca, real r, wide r2, wide *d2)
{
    const uint32_t lim = 2u * (uint32_t)r;
    real py = l.y - (real)fx_round_shift(FX_SMUL(tca, d.y), FX_UF);
    if ((uint32_t)py + (uint32_t)r > lim)
        return 0;
    real px = l.x - (real)fx_round_shift(FX_SMUL(tca, d.x), FX_UF);
    if ((uint32_t)px + (uint32_t)r > lim)
        return 0;
    real pz = l.z - (real)fx_round_shift(FX_SMUL(tca, d.z), FX_UF);
    if ((uint32_t)pz + (uint32_t)r > lim)
        return 0;
    *d2 = w_len2(v3(px, py, pz));
    return *d2 <= r2;
}

/* v3_dot_d_in(v3_sub_in(c, l), d) in two parts, for one ray d against many points c:
 * part = v3_dot_part(l, d) once, then v3_dot_d_from(c, d, part) per point. The same value:
 * the unrounded sums c . d - l . d and (c - l) . d are equal (in-scene c and l: each sum
 * below 2^61). The part holds the rounding's half too, 2^(F-1) - l . d, so that each point's
 * dot product accumulates onto it (smlal on ARM) and is rounded by the shift alone. */
typedef int64_t dotpart;
static inline dotpart v3_dot_part(vec3 l, dir3 d)
{
    return ((int64_t)1 << (FX_UF - 1)) -
        (FX_SMUL(l.x, d.x) + FX_SMUL(l.y, d.y) + FX_SMUL(l.z, d.z));
}
static inline real v3_dot_d_from(vec3 c, dir3 d, dotpart part)
{
    int64_t s = part + FX_SMUL(c.x, d.x) + FX_SMUL(c.y, d.y) + FX_SMUL(c.z, d.z);
    return (real)(s >> FX_UF);
}

#else

typedef float rcull;

/* A sphere's quick rejection of rays (the fixed build's r_cull): k itself, 0 for none; it
 * rejects when c . d >= 0 or (c . d)^2 < k. */
static inline rcull r_cull(wide k) { return k > 0 ? k : 0; }

static inline int r_cull_rejects(real cd, rcull c) { return cd >= 0 || w_sq(cd) < c; }

/* The sphere test's last step for a shadow segment (the fixed build forms it without the
 * square root): the near hit tca - thc if positive, else tca + thc, in (0, tmax)? */
static inline int r_sphere_span(wide a, real tca, real tmax)
{
    real thc = r_sqrt_w(a);
    real hit = r_sub(tca, thc);
    if (hit <= 0)
        hit = r_add(tca, thc);
    return hit > 0 && hit < tmax;
}

/* The sphere test's discriminant step (the fixed build's r_perp_within): the sum of squares
 * compared with r2 (float keeps no component shortcut: a square's rounding could tie r2). */
static inline int r_perp_within(vec3 l, dir3 d, real tca, real r, wide r2, wide *d2)
{
    (void)r;
    *d2 = w_len2(v3_sub_in(l, d3_scale_in(d, tca)));
    return *d2 <= r2;
}

/* The split form of v3_dot_d_in(v3_sub_in(c, l), d): float keeps l and subtracts first. */
typedef vec3 dotpart;
static inline dotpart v3_dot_part(vec3 l, dir3 d)
{
    (void)d;
    return l;
}
static inline real v3_dot_d_from(vec3 c, dir3 d, dotpart part)
{
    return v3_dot_d_in(v3_sub_in(c, part), d);
}

#endif

#endif
