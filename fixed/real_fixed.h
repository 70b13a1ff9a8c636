/* real_fixed.h: fixed-point operations of the numeric layer (included by real.h only).
 *
 * Scalars are libfixmath's Q16.16; multiply, divide, square root and sine go through
 * libfixmath. Unit vectors are Q2.30 and every product involving them is formed in 64 bits
 * and rounded once, so a hit point o + d*t is as exact as its Q16.16 coordinates allow.
 * FX_UNIT_FRAC = 16 (rt-fixed16) makes unit plain Q16.16: the same code with every shift by
 * FX_UF = FX_UNIT_FRAC bits and products of two units in Q.FX_UF2 (Q.60, or Q.32), except
 * where the variant has a cheaper path of its own (32-bit normalisation, no second-order terms).
 * Nothing here wraps: out-of-range results saturate to +-R_MAX and count FX_EV_OVERFLOW.
 * Right shifts of negative values are arithmetic (GCC and Clang define it so).
 */
#ifndef FIXRAY_REAL_FIXED_H
#define FIXRAY_REAL_FIXED_H

#include <fix16.h>
#include <stdint.h>
#if defined(__ARM_FEATURE_DSP)
#include <arm_acle.h> /* __qadd, __qsub */
#endif

/* The 32 x 32 -> 64-bit products, FX_SMUL (signed) and FX_UMUL (unsigned), of operands of at
 * most 32 bits (checked at compile time): the compiler's own, or on ARMv6-M (Cortex-M0), which
 * has no long multiply, fx_armv6m.h's in 32-bit pieces. The same bits either way. */
#if defined(__ARM_ARCH_6M__)
#include "fx_armv6m.h"
#define FX_SMUL_OP(a, b) fx_v6m_smul((int32_t)(a), (int32_t)(b))
#define FX_UMUL_OP(a, b) fx_v6m_umul((uint32_t)(a), (uint32_t)(b))
#else
#define FX_SMUL_OP(a, b) ((int64_t)(a) * (int64_t)(b))
#define FX_UMUL_OP(a, b) ((uint64_t)(a) * (uint64_t)(b))
#endif
#define FX_NARROW(a, b) ((void)sizeof(char[sizeof(a) <= 4 && sizeof(b) <= 4 ? 1 : -1]))
#define FX_SMUL(a, b) (FX_NARROW(a, b), FX_SMUL_OP(a, b))
#define FX_UMUL(a, b) (FX_NARROW(a, b), FX_UMUL_OP(a, b))

/* Fraction bits of unit, and of a product of two units. */
#define FX_UF FX_UNIT_FRAC
#define FX_UF2 (2 * FX_UNIT_FRAC)

#define R(x) ((real)F16(x))
#define U(x) \
    ((unit)((x) >= 0 ? (x) * (double)(1LL << FX_UF) + 0.5 : (x) * (double)(1LL << FX_UF) - 0.5))
#define R_ONE ((real)0x00010000)
#define U_ONE ((unit)1 << FX_UF)
/* Largest magnitude; -R_MAX is the most negative value produced (never INT32_MIN, which
 * libfixmath uses as its overflow marker). */
#define R_MAX ((real)INT32_MAX)
#define R_PI ((real)205887)
/* Smallest positive step of each type (used by tests and tolerances). */
#define R_LSB ((real)1)
#define U_LSB ((unit)1)

/* 1 on processors without a divide instruction (the ARM926): there the divisions of the
 * per-ray path go through exact division-free equivalents (a libgcc 64-bit division costs
 * hundreds of instructions). Elsewhere the hardware divides. Results are the same either way;
 * -DFX_SOFT_DIVIDE=1 runs the board's path on the host (the san-fixed-sd tests). */
#ifndef FX_SOFT_DIVIDE
#if defined(__arm__) && !defined(__ARM_FEATURE_IDIV)
#define FX_SOFT_DIVIDE 1
#else
#define FX_SOFT_DIVIDE 0
#endif
#endif

/* n / m rounded down, for n < 2^62 and m >= 1, without a divide instruction when the quotient
 * is below about 2^31 (larger ones fall back to the library's division). */
uint64_t fx_udiv64(uint64_t n, uint32_t m);

/* Integer square root of a 64-bit value, rounded to nearest. */
uint32_t fx_isqrt64(uint64_t n);
/* Unit vector of (x, y, z) given in any common scale; *len receives the length in the same
 * scale shifted right by `frac` bits less than Q16.16 uses, i.e. for Q16.16 inputs pass
 * frac = 16 and get a Q16.16 length (may be NULL). A zero vector gives (0,0,0), length 0,
 * and counts FX_EV_DOMAIN. */
dir3 fx_norm64(int64_t x, int64_t y, int64_t z, int frac, real *len);
/* d3_ray(*f, *r, *u, step, ia, ib) (below): the primary ray's direction, formed and normalised
 * in one function (the view's vectors read in place, nothing passed on the stack but the three
 * numbers). */
dir3 fx_ray_dir(const dir3 *f, const dir3 *r, const dir3 *u, ustep step, int32_t ia, int32_t ib);
/* fx_norm64(x, y, z, 16, len) for a vector of reals (Q16.16): d3_norm, for once-a-frame callers
 * and fallbacks. */
dir3 fx_norm32(int32_t x, int32_t y, int32_t z, real *len);
#define FX_NORM_REALS(x, y, z, len) fx_norm32(x, y, z, len)
/* fx_norm32's unit vector into *out and its length returned (always formed), the same results
 * in 32-bit arithmetic from the start: the light direction's form (d3_norm_len), which writes
 * the direction where the caller keeps it and passes no length pointer. */
real fx_norm32_to(dir3 *out, int32_t x, int32_t y, int32_t z);

/* Sine and cosine of an angle given in degrees, to about 2e-9: for the camera and other
 * once-per-frame set-up where libfixmath's Q16.16 sine (about 1e-4 relative) is too coarse. */
void u_sincos_deg(real deg, unit *s, unit *c);

/* Saturate a 64-bit integer to the range of real, [-R_MAX, R_MAX], on a 64-bit machine: one
 * range check of the 64-bit value (an addition, a compare and a branch). */
static inline real fx_sat_w64(int64_t v)
{
    if (__builtin_expect((uint64_t)v + R_MAX > 2 * (uint64_t)R_MAX, 0)) {
        FX_EVENT(FX_EV_OVERFLOW);
        return v > 0 ? R_MAX : -R_MAX;
    }
    return (real)v;
}

/* The same on a 32-bit core, where that check is a 64-bit addition and compare: v is in range
 * when its high word is the sign of its low word and the low word is not INT32_MIN, two
 * compares of 32-bit words that the compiler turns into conditional moves (cmp, mvnne, eorne,
 * cmp, movlt on ARM: no branch, no literal). test_numeric checks that both give the same. */
static inline real fx_sat_w32(int64_t v)
{
    int32_t lo = (int32_t)v, hi = (int32_t)((uint64_t)v >> 32);
#if FX_COUNT_EVENTS
    if (hi != (lo >> 31) || lo == INT32_MIN)
        FX_EVENT(FX_EV_OVERFLOW);
#endif
    if (hi != (lo >> 31))
        lo = (hi >> 31) ^ R_MAX; /* R_MAX; for a negative v INT32_MIN, made -R_MAX below */
    if (lo == INT32_MIN)
        lo = -R_MAX;
    return lo;
}

/* 1 where a 64-bit value fits a register. */
#if UINTPTR_MAX > 0xFFFFFFFFu
#define FX_WORD64 1
#else
#define FX_WORD64 0
#endif

/* Saturate a 64-bit integer to the range of real (counting FX_EV_OVERFLOW when it does). */
static inline real fx_sat(int64_t v) { return FX_WORD64 ? fx_sat_w64(v) : fx_sat_w32(v); }

/* Round a 64-bit value with `s` fraction bits to an integer (s >= 1), half up. */
static inline int64_t fx_round_shift(int64_t v, int s)
{
    return (v + ((int64_t)1 << (s - 1))) >> s;
}

/* fx_round_shift of a 32-bit value, s in [1, 31], in 32-bit arithmetic: the kept bits plus
 * the first bit below them (the carry that adding one half would make); no overflow. */
static inline int32_t fx_round_shift32(int32_t v, int s) { return (v >> s) + ((v >> (s - 1)) & 1); }

/* ---- real: Q16.16 ------------------------------------------------------------------------ */

static inline real r_from_int(int32_t i) { return fx_sat((int64_t)i * 65536); }

/* A Q16.16 integer (65536 = 1.0) as a real: exact. */
static inline real r_from_q16(int32_t v) { return (real)v; }

/* A value in [0, 1] as a Q16.16 integer (0..65536): exact. */
static inline int32_t r_unit_to_q16(real a) { return a; }

/* Nearest integer (half up). */
static inline int32_t r_to_int(real a) { return fx_round_shift32(a, 16); }

/* a * num / den for integers, rounded (den > 0): exact ratios such as pixel offsets. */
static inline real r_from_ratio(int32_t num, int32_t den)
{
    int64_t n = (int64_t)num * 65536;
    return fx_sat(n >= 0 ? (n + den / 2) / den : -((-n + den / 2) / den));
}

/* ARMv5TE and later DSP cores saturate a 32-bit sum in one instruction (qadd, qsub: to INT32_MIN
 * or INT32_MAX); only INT32_MIN is left to move to -R_MAX. The same results as fx_sat of the
 * 64-bit sum, which the other targets and the event-counting builds use. */
#if defined(__ARM_FEATURE_DSP) && !FX_COUNT_EVENTS
#define FX_QADD 1
#else
#define FX_QADD 0
#endif

static inline real r_add(real a, real b)
{
#if FX_QADD
    int32_t r = __qadd(a, b);
    return r == INT32_MIN ? -R_MAX : r;
#else
    return fx_sat((int64_t)a + b);
#endif
}

static inline real r_sub(real a, real b)
{
#if FX_QADD
    int32_t r = __qsub(a, b);
    return r == INT32_MIN ? -R_MAX : r;
#else
    return fx_sat((int64_t)a - b);
#endif
}

/* -a: fx_sat(-a), whose only out-of-range case is a = INT32_MIN (to R_MAX), tested alone. */
static inline real r_neg(real a)
{
    if (__builtin_expect(a == INT32_MIN, 0)) {
        FX_EVENT(FX_EV_OVERFLOW);
        return R_MAX;
    }
    return -a;
}

static inline real r_abs(real a) { return a < 0 ? r_neg(a) : a; }

/* The same result as libfixmath's fix16_mul (rounded, overflow detected; the unit test checks
 * them bit for bit), written inline: fix16_mul lives in a separate object and is called about
 * a million times per frame. On overflow it saturates where fix16_mul returns 0x80000000. */
static inline real r_mul(real a, real b)
{
    /* One signed 32x32 -> 64 multiply (smull), rounded as libfixmath rounds (negatives from
     * product - 1, then half up: one addend, 0x8000 or 0x7FFF), and fx_sat of the quotient:
     * it saturates exactly where the rounded result does not fit 32 bits or is fix16_overflow
     * (INT32_MIN), and by the sign of the product, which is the sign of the quotient then. */
    int64_t p = FX_SMUL(a, b);
    return fx_sat((p + (0x8000 + (int32_t)(p >> 63))) >> 16);
}

/* In-range arithmetic: r_mul, r_add and r_mul_u where docs/numerics.md bounds the result well
 * inside real's range (colours and their weights, within [0, 1161]; points on rays from inside
 * the scene cube, within 20481 of the centre). The release build forms them without the range
 * check: the same results as the checked operations inside the bound. The event-counting builds
 * (the san-* tests) use the checked operations, which count FX_EV_OVERFLOW: a broken bound shows
 * there as an event, and as pictures that differ from the release build's. */
#if FX_COUNT_EVENTS
static inline real r_mul_in(real a, real b) { return r_mul(a, b); }
static inline real r_add_in(real a, real b) { return r_add(a, b); }
static inline real r_neg_in(real a) { return r_neg(a); }
#else
/* -a for any a but INT32_MIN, which no operation here returns (saturation stops at -R_MAX). */
static inline real r_neg_in(real a) { return -a; }
static inline real r_mul_in(real a, real b)
{
    int64_t p = FX_SMUL(a, b);
    return (real)((p + (0x8000 + (int32_t)(p >> 63))) >> 16);
}
static inline real r_add_in(real a, real b) { return (real)((uint32_t)a + (uint32_t)b); }
#endif

/* r_mul_in of two colour values or weights, within [0, 1161] (docs/numerics.md, Colours): the
 * product is not negative, so the rounding needs no sign term (two instructions fewer on ARM);
 * the same result. The event-counting builds use r_mul (see r_mul_in). */
#if FX_COUNT_EVENTS
static inline real r_mul_c(real a, real b) { return r_mul(a, b); }
#else
static inline real r_mul_c(real a, real b) { return (real)((FX_SMUL(a, b) + 0x8000) >> 16); }
#endif

/* a * 2^-n for n >= 0, rounded. */
static inline real r_shr(real a, int n)
{
    return n <= 0 ? a : n < 32 ? fx_round_shift32(a, n) : (real)fx_round_shift(a, n);
}

/* v * g for g in {-1, 0, 1}: exactly g > 0 ? v : g < 0 ? r_neg(v) : 0, without branches. */
static inline real r_mul_sign(real v, int g) { return fx_sat(FX_SMUL(v, g)); }

/* Multiply by a small non-negative integer. */
static inline real r_muli(real a, int32_t i) { return fx_sat(FX_SMUL(a, i)); }

static inline real r_div(real a, real b)
{
    if (b == 0) {
        FX_EVENT(FX_EV_DOMAIN);
        return a == 0 ? 0 : (a < 0 ? -R_MAX : R_MAX);
    }
    real q = fix16_div(a, b);
    if (q == fix16_overflow) {
        FX_EVENT(FX_EV_OVERFLOW);
        return ((a < 0) != (b < 0)) ? -R_MAX : R_MAX;
    }
    return q;
}

static inline real r_sqrt(real a)
{
    if (a < 0) {
        FX_EVENT(FX_EV_DOMAIN);
        return 0;
    }
    return fix16_sqrt(a);
}

/* x reduced modulo 2 pi into (-pi, pi]. 2 pi is 411774.83 LSB in Q16.16, so the reduction is
 * done in Q.32 where 2 pi is exact to 2^-33: no drift for large angles. The remainder is the
 * 64-bit % operator's, (a 2^16) % 2 pi, without its division (a library call on 32-bit ARM):
 * the quotient of |a| 2^16 is |a| 2^50 / (2 pi) / 2^50, and |a| floor(2^66 / (2 pi)) / 2^50
 * falls short of it by less than 2^31 / 2^50, so its floor is the quotient or one less (one
 * correction); the remainder takes a's sign, as %'s does (checked for every 32-bit a). */
static inline real r_reduce_angle(real a)
{
    const int64_t two_pi = 26986075409LL, pi = 13493037705LL; /* Q.32 */
    const uint32_t m = a < 0 ? 0u - (uint32_t)a : (uint32_t)a;
    const uint32_t q = (uint32_t)(((uint64_t)m * 2734261102u) >> 50); /* 2^66 / (2 pi), floored */
    uint64_t r = ((uint64_t)m << 16) - (uint64_t)q * (uint64_t)two_pi;
    if (r >= (uint64_t)two_pi)
        r -= (uint64_t)two_pi;
    int64_t v = a < 0 ? -(int64_t)r : (int64_t)r;
    if (v > pi)
        v -= two_pi;
    else if (v <= -pi)
        v += two_pi;
    return (real)fx_round_shift(v, 16);
}

/* Sine. libfixmath's series is accurate on [-pi/2, pi/2] only, so the angle is reduced to
 * (-pi, pi] and folded into that interval first. */
static inline real r_sin(real a)
{
    int32_t x = r_reduce_angle(a);
    if (x > R_PI / 2)
        x = R_PI - x;
    else if (x < -R_PI / 2)
        x = -R_PI - x;
    return fix16_sin(x);
}

static inline real r_cos(real a)
{
    /* cos a = sin(pi/2 - a); the reduced angle keeps the sum in range */
    return r_sin(R_PI / 2 - r_reduce_angle(a));
}

/* Split x into floor(x) (returned through *i) and the fraction x - floor(x) in [0, 1). */
static inline real r_floor_split(real x, int32_t *i)
{
    *i = x >> 16;
    return x & 0xFFFF;
}

/* floor(r_mul(a, b) + 1/2) where the product lies well inside real's range (texture coordinates,
 * docs/numerics.md): r_mul's rounding and the half's floor are nested floor divisions, so the
 * integer is (P + 0x8000 - [P < 0] + 2^15 * 2^16) >> 32 for the 64-bit product P, one sum.
 * The event-counting builds compose the checked operations instead (a broken bound shows). */
static inline int32_t r_mul_round_in(real a, real b)
{
#if FX_COUNT_EVENTS
    int32_t i;
    r_floor_split(r_add(r_mul(a, b), 0x8000), &i);
    return i;
#else
    int64_t p = FX_SMUL(a, b);
    uint32_t k = 0x80008000u + (uint32_t)(p >> 63); /* 0x80007FFF for a negative product */
    return (int32_t)((p + k) >> 32);
#endif
}

/* x modulo m for m > 0: the result lies in [0, m). */
static inline real r_mod(real x, real m)
{
    int32_t r = x % m;
    return r < 0 ? r + m : r;
}

/* x modulo m for m a positive power of two (as a real): the same as r_mod, by a mask. */
static inline real r_mod_pow2(real x, real m) { return x & (m - 1); }

/* r_mod_pow2(r_muli(x, 2), m) for x = r_mod_pow2(y, m) (so in [0, m]): the same mask. */
static inline real r_mod_pow2_twice(real x, real m) { return r_mod_pow2(r_muli(x, 2), m); }

/* 1 where a is a compile-time constant 2^k with 2^k < U_ONE (R_EPS_OFFSET, 2^-9): then
 * round(a u / U_ONE) = round(u / 2^(FX_UF - k)), since a u + 2^(FX_UF - 1) is 2^k (u +
 * 2^(FX_UF - 1 - k)); fx_round_shift32 forms it in 32 bits (two or three instructions on ARM
 * instead of a 64-bit product), the same value, never outside real's range. */
#define FX_POW2_BELOW_UNIT(a) \
    (__builtin_constant_p(a) && (a) > 0 && (a) < ((int32_t)1 << FX_UF) && ((a) & ((a)-1)) == 0)

/* real * unit -> real, rounded. */
static inline real r_mul_u(real a, unit u)
{
    if (FX_POW2_BELOW_UNIT(a))
        return fx_round_shift32(u, FX_UF - __builtin_ctz((uint32_t)a));
    return fx_sat(fx_round_shift(FX_SMUL(a, u), FX_UF));
}

/* r_mul_u inside a proven bound (see r_mul_in). */
#if FX_COUNT_EVENTS
static inline real r_mul_u_in(real a, unit u) { return r_mul_u(a, u); }
#else
static inline __attribute__((always_inline)) real r_mul_u_in(real a, unit u)
{
    if (FX_POW2_BELOW_UNIT(a))
        return fx_round_shift32(u, FX_UF - __builtin_ctz((uint32_t)a));
    return (real)fx_round_shift(FX_SMUL(a, u), FX_UF);
}
#endif

/* real / unit -> real, rounded to nearest. */
static inline real r_div_u(real a, unit b)
{
    if (b == 0) {
        FX_EVENT(FX_EV_DOMAIN);
        return a == 0 ? 0 : (a < 0 ? -R_MAX : R_MAX);
    }
    int neg = (a < 0) != (b < 0);
    uint64_t n = (uint64_t)(a < 0 ? -(int64_t)a : a) << FX_UF; /* below 2^(31 + FX_UF) */
    uint64_t m = (uint64_t)(b < 0 ? -(int64_t)b : b);
#if FX_SOFT_DIVIDE /* the plane test's t = num / den: quotients below 2^30 */
    int64_t q = (int64_t)fx_udiv64(n + m / 2, (uint32_t)m);
#else
    int64_t q = (int64_t)((n + m / 2) / m);
#endif
    return fx_sat(neg ? -q : q);
}

/* r_div_u(a, b) for a >= 0 and b > 0 (a plane test's num / den, both turned positive): the
 * same quotient without the signs and the zero divisor. */
static inline real r_div_u_pos(real a, unit b)
{
    uint64_t n = (uint64_t)a << FX_UF, m = (uint64_t)b;
#if FX_SOFT_DIVIDE
    int64_t q = (int64_t)fx_udiv64(n + m / 2, (uint32_t)m);
#else
    int64_t q = (int64_t)((n + m / 2) / m);
#endif
    /* the plane tests call it once num < tmax den (rounded) holds for a tmax <= 30573: the
     * quotient then exceeds tmax by at most 5001 steps (half a step of the rounded product over
     * den >= U_EPS_PARALLEL), in range, and the release build takes it unchecked (r_mul_in) */
#if FX_COUNT_EVENTS
    return fx_sat(q);
#else
    return (real)q;
#endif
}

/* Is r_div_u(a, b) > s, for a > 0, b > 0 and 0 <= s < R_MAX? The same answer without the
 * division: the quotient floor((a 2^F + b/2) / b) (saturated at R_MAX, above s) exceeds s exactly
 * when a 2^F + b/2 >= (s + 1) b (below 2^62). */
static inline int r_div_u_above(real a, unit b, real s)
{
    return ((uint64_t)a << FX_UF) + (uint64_t)b / 2 >= ((uint64_t)s + 1) * (uint64_t)b;
}

/* ---- unit: Q2.30 (or Q16.16) ------------------------------------------------------------- */

/* Saturate to unit's 32 bits, +-INT32_MAX: fx_sat. */
static inline unit u_sat(int64_t v) { return fx_sat(v); }

static inline unit u_mul(unit a, unit b) { return u_sat(fx_round_shift(FX_SMUL(a, b), FX_UF)); }

/* u_mul of two values within [-1 - 2^-20, 1 + 2^-20] (powers of a cosine): the product stays
 * inside unit's range, so the release build skips the saturation test (see r_mul_in). */
#if FX_COUNT_EVENTS
static inline unit u_mul_in(unit a, unit b) { return u_mul(a, b); }
#else
static inline unit u_mul_in(unit a, unit b) { return (unit)fx_round_shift(FX_SMUL(a, b), FX_UF); }
#endif

static inline unit u_neg(unit a) { return r_neg(a); }

/* u_neg of a unit that is not INT32_MIN (a dot product of unit vectors, |a| <= 1 + 2^-28, or
 * any saturated one): the range check left out as r_neg_in does. */
static inline unit u_neg_in(unit a) { return r_neg_in(a); }

static inline unit u_add(unit a, unit b) { return r_add(a, b); }

/* u_add of values whose sum docs/numerics.md bounds inside unit's range (the Phong term's
 * partial sums, within [-1, 1]): unchecked in the release build (see r_mul_in). */
#if FX_COUNT_EVENTS
static inline unit u_add_in(unit a, unit b) { return u_add(a, b); }
#else
static inline unit u_add_in(unit a, unit b) { return (unit)((uint32_t)a + (uint32_t)b); }
#endif

/* unit * integer (pixel offsets along the image plane). */
static inline unit u_muli(unit a, int32_t i) { return u_sat(FX_SMUL(a, i)); }

static inline unit u_from_real(real a) { return u_sat((int64_t)a * (1 << (FX_UF - 16))); }

static inline real u_to_real(unit a)
{
#if FX_UF > 16
    return fx_round_shift32(a, FX_UF - 16);
#else
    return a;
#endif
}

/* unit / positive integer, rounded. */
static inline unit u_divi(unit a, int32_t i)
{
    return (unit)(a >= 0 ? ((int64_t)a + i / 2) / i : -((-(int64_t)a + i / 2) / i));
}

/* a / b for units, rounded to nearest; |a / b| must stay below 2. */
static inline unit u_div(unit a, unit b)
{
    if (b == 0) {
        FX_EVENT(FX_EV_DOMAIN);
        return a == 0 ? 0 : (a < 0 ? -INT32_MAX : INT32_MAX);
    }
    uint64_t n = (uint64_t)(a < 0 ? -(int64_t)a : a) << FX_UF;
    uint64_t m = (uint64_t)(b < 0 ? -(int64_t)b : b);
    int64_t q = (int64_t)((n + m / 2) / m);
    return u_sat((a < 0) != (b < 0) ? -q : q);
}

/* The camera's step per half pixel, tan / height with tan = s / c (c >= 1/2, so tan < 2), as a
 * Q2.30 ustep whatever unit's format (Q16.16 would round it by up to 0.5% on a 480-line frame,
 * shifting the picture's edges by pixels). */
static inline ustep u_tan_step(unit s, unit c, int32_t height)
{
#if FX_UF == 30
    return u_divi(u_div(s, c), height);
#else
    if (c <= 0) {
        FX_EVENT(FX_EV_DOMAIN);
        return 0;
    }
    int64_t n = (int64_t)s * ((int64_t)1 << 30);
    int64_t t = n >= 0 ? (n + c / 2) / c : -((-n + c / 2) / c); /* Q2.30: |s / c| < 2 */
    return (ustep)(t >= 0 ? (t + height / 2) / height : -((-t + height / 2) / height));
#endif
}

/* A colour channel as a byte: clamped to [0, 1], scaled to 0..255 and rounded. */
static inline uint8_t r_to_byte(real c)
{
    /* c clamped to [0, R_ONE] first (R_ONE itself gives 255): two conditional moves on ARM
     * instead of two branches */
    c = c < 0 ? 0 : c;
    c = c > R_ONE ? R_ONE : c;
    return (uint8_t)(((uint32_t)c * 255u + 0x8000u) >> 16);
}

/* ---- wide: Q32.32 ------------------------------------------------------------------------ */

static inline wide w_sq(real a) { return FX_SMUL(a, a); }

/* a * b as a wide (Q32.32), exact. */
static inline wide w_mul(real a, real b) { return FX_SMUL(a, b); }

static inline wide w_add(wide a, wide b) { return a + b; }

static inline wide w_sub(wide a, wide b) { return a - b; }

/* Squared length |a|^2. Every vector given here is a difference of a scene position and a ray
 * origin (see the in-scene variants below): each component is below 24576 (raw < 2^31), so the
 * sum of squares stays below 2^63. */
static inline wide w_len2(vec3 a)
{
    return FX_SMUL(a.x, a.x) + FX_SMUL(a.y, a.y) + FX_SMUL(a.z, a.z);
}

/* sqrt of a Q32.32 value is a Q16.16 value: the integer square root does it exactly. */
static inline real r_sqrt_w(wide a)
{
    if (a < 0) {
        FX_EVENT(FX_EV_DOMAIN);
        return 0;
    }
    return fx_sat(fx_isqrt64((uint64_t)a));
}

/* r_sqrt_w of a discriminant, 0 <= a < 2^62 (the sphere test's r^2 - |perp|^2, at most r^2 <=
 * 2^54, docs/numerics.md): the root is below 2^31, in range, so the release build takes it
 * without the sign and range tests (see r_mul_in). */
#if FX_COUNT_EVENTS
static inline real r_sqrt_w_in(wide a) { return r_sqrt_w(a); }
#else
static inline real r_sqrt_w_in(wide a) { return (real)fx_isqrt64((uint64_t)a); }
#endif

/* sqrt(a^2 + b^2) without overflow for any a, b (saturates only when the result does). */
static inline real r_hypot(real a, real b)
{
    return fx_sat(fx_isqrt64((uint64_t)(FX_SMUL(a, a)) + (uint64_t)(FX_SMUL(b, b))));
}

/* ---- vectors ----------------------------------------------------------------------------- */

/* v . d for a position-like v and a unit d: |v . d| <= |v|. Each product is below 2^61. */
static inline real v3_dot_d(vec3 v, dir3 d)
{
    int64_t s = FX_SMUL(v.x, d.x) + FX_SMUL(v.y, d.y) + FX_SMUL(v.z, d.z);
    return fx_sat(fx_round_shift(s, FX_UF));
}

/* Is v . d > 0, exactly (no rounding of the sum)? */
static inline int v3_faces(vec3 v, dir3 d)
{
    return FX_SMUL(v.x, d.x) + FX_SMUL(v.y, d.y) + FX_SMUL(v.z, d.z) > 0;
}

/* Is a . b < 0 for unit vectors, exactly (no rounding of the sum)? */
static inline int d3_below(dir3 a, dir3 b)
{
    return FX_SMUL(a.x, b.x) + FX_SMUL(a.y, b.y) + FX_SMUL(a.z, b.z) < 0;
}

/* a . b for unit vectors: within 1 + 2^-28 (docs/numerics.md, "Dot products"), inside unit's
 * range, so the release build takes it without the saturation test (see r_mul_in); the
 * event-counting builds saturate and count. */
static inline unit d3_dot(dir3 a, dir3 b)
{
    int64_t s = FX_SMUL(a.x, b.x) + FX_SMUL(a.y, b.y) + FX_SMUL(a.z, b.z);
#if FX_COUNT_EVENTS
    return u_sat(fx_round_shift(s, FX_UF));
#else
    return (unit)fx_round_shift(s, FX_UF);
#endif
}

/* d * s as a vector of reals. */
static inline vec3 d3_scale(dir3 d, real s)
{
    return v3(r_mul_u(s, d.x), r_mul_u(s, d.y), r_mul_u(s, d.z));
}

/* The unit vector along v; its length goes to *len when len is not NULL. */
static inline dir3 d3_norm(vec3 v, real *len) { return FX_NORM_REALS(v.x, v.y, v.z, len); }

/* d3_norm(v, &len) with the unit vector into *out and the length returned. */
static inline real d3_norm_len(vec3 v, dir3 *out) { return fx_norm32_to(out, v.x, v.y, v.z); }

/* Unit vector along f + r*(step*ia) + u*(step*ib): the primary ray through a pixel, where
 * ia and ib are the pixel's offsets from the image centre in half pixels (fx_ray_dir, fx.c,
 * tells how it is formed). */
static inline dir3 d3_ray(dir3 f, dir3 r, dir3 u, ustep step, int32_t ia, int32_t ib)
{
    return fx_ray_dir(&f, &r, &u, step, ia, ib);
}

/* d3_ray of the vectors in place: what the camera calls per pixel. */
static inline dir3 d3_ray_at(const dir3 *f, const dir3 *r, const dir3 *u, ustep step, int32_t ia,
                             int32_t ib)
{
    return fx_ray_dir(f, r, u, step, ia, ib);
}

/* Unit vector along a x b; *len (may be NULL) gets |a x b| = sin of the angle. */
static inline dir3 d3_cross(dir3 a, dir3 b, real *len)
{
    int64_t x = FX_SMUL(a.y, b.z) - FX_SMUL(a.z, b.y);
    int64_t y = FX_SMUL(a.z, b.x) - FX_SMUL(a.x, b.z);
    int64_t z = FX_SMUL(a.x, b.y) - FX_SMUL(a.y, b.x);
    return fx_norm64(x, y, z, FX_UF2, len);
}

/* fx_renorm is inlined into its callers on 32-bit ARM (the reflected and refracted directions of
 * trace.c): its three 64-bit arguments would otherwise go through the stack, and the inlined
 * copies measured fewer instructions a frame on the board, for a larger image.
 * Elsewhere the compiler decides (the x86 players stay small). */
#if defined(__arm__)
#define FX_RENORM_INLINE __attribute__((always_inline))
#else
#define FX_RENORM_INLINE
#endif

#if FX_UF == 30
/* fx_renorm's second-order correction of (a, b, c), a Q.60 vector rounded to Q2.30, into *out;
 * 0 (and nothing written) when it is further than 2^-12 from unit. */
static inline int fx_renorm_q30(int32_t a, int32_t b, int32_t c, dir3 *out)
{
    int64_t e = FX_SMUL(a, a) + FX_SMUL(b, b) + FX_SMUL(c, c) - ((int64_t)1 << 60);
    if (e > ((int64_t)1 << 48) || e < -((int64_t)1 << 48))
        return 0;
    /* g = e/2 - 3e^2/8 in Q.40: e / 2^20 is below 2^28, its square below 2^56; both e / 2^20
     * and g fit 32 bits, so the products are signed 32x32-bit ones */
    int32_t e40 = (int32_t)(e >> 20);
    int32_t sq = (int32_t)((FX_SMUL(e40, e40)) >> 40); /* below 2^16 */
    int32_t g = (e40 >> 1) - ((3 * sq) >> 3);          /* below 2^27 */
    out->x = a - (int32_t)fx_round_shift(FX_SMUL(a, g), 40);
    out->y = b - (int32_t)fx_round_shift(FX_SMUL(b, g), 40);
    out->z = c - (int32_t)fx_round_shift(FX_SMUL(c, g), 40);
    return 1;
}

/* Unit vector along a Q.60 vector that is already unit to within 2^-12 (reflected and
 * refracted directions, a sphere's p - c times 1/r): rounded to Q2.30 and corrected by
 * v * (1 - e/2 + 3e^2/8), e = |v|^2 - 1, the series of 1/sqrt(1 + e) to second order (what it
 * leaves out is below 5/16 |e|^3 <= 2^-37); anything further from unit goes through fx_norm64. */
static inline FX_RENORM_INLINE dir3 fx_renorm(int64_t x, int64_t y, int64_t z)
{
    const uint64_t two = (uint64_t)1
        << 61; /* 2.0 in Q.60: beyond it the rounding below would not fit */
    if (__builtin_expect((uint64_t)x + two >= 2 * two || (uint64_t)y + two >= 2 * two ||
                             (uint64_t)z + two >= 2 * two,
                         0))
        return fx_norm64(x, y, z, 60, 0);
    int32_t a = (int32_t)fx_round_shift(x, 30), b = (int32_t)fx_round_shift(y, 30),
            c = (int32_t)fx_round_shift(z, 30);
    dir3 d;
    if (__builtin_expect(!fx_renorm_q30(a, b, c, &d), 0))
        return fx_norm64(x, y, z, 60, 0);
    return d;
}
/* fx_renorm of a vector whose length is within 2^-23 of one, without its checks: each |component|
 * < 2^61 and |e| < 2^37, so fx_renorm's range checks pass and fx_renorm_q30's square term (3e^2/8,
 * e / 2^20 below 2^17 squared over 2^40) is 0: g = e / 2^21, the same result. The release builds'
 * form of fx_renorm_unit, compiled in every build so that tests/test_numeric.c checks this very
 * code against fx_renorm. */
static inline FX_RENORM_INLINE dir3 fx_renorm_unit_fast(int64_t x, int64_t y, int64_t z)
{
    int32_t a = (int32_t)fx_round_shift(x, 30), b = (int32_t)fx_round_shift(y, 30),
            c = (int32_t)fx_round_shift(z, 30);
    int64_t e = FX_SMUL(a, a) + FX_SMUL(b, b) + FX_SMUL(c, c) - ((int64_t)1 << 60);
    int32_t g = (int32_t)(e >> 21);
    dir3 d = {a - (int32_t)fx_round_shift(FX_SMUL(a, g), 40),
              b - (int32_t)fx_round_shift(FX_SMUL(b, g), 40),
              c - (int32_t)fx_round_shift(FX_SMUL(c, g), 40)};
    return d;
}

/* fx_renorm of a vector whose length is within 2^-23 of one: fx_renorm_unit_fast. Only for the
 * mirrored direction of unit vectors (d3_reflect_k, docs/numerics.md). The event-counting builds
 * take fx_renorm and count FX_EV_OVERFLOW where the bound fails (see r_mul_in). */
static inline FX_RENORM_INLINE dir3 fx_renorm_unit(int64_t x, int64_t y, int64_t z)
{
#if FX_COUNT_EVENTS
    int32_t a = (int32_t)fx_round_shift(x, 30), b = (int32_t)fx_round_shift(y, 30),
            c = (int32_t)fx_round_shift(z, 30);
    int64_t e = FX_SMUL(a, a) + FX_SMUL(b, b) + FX_SMUL(c, c) - ((int64_t)1 << 60);
    const uint64_t two = (uint64_t)1 << 61;
    if ((uint64_t)x + two >= 2 * two || (uint64_t)y + two >= 2 * two ||
        (uint64_t)z + two >= 2 * two || e >= ((int64_t)1 << 37) || e <= -((int64_t)1 << 37))
        FX_EVENT(FX_EV_OVERFLOW);
    return fx_renorm(x, y, z);
#else
    return fx_renorm_unit_fast(x, y, z);
#endif
}
#else
/* The same for unit in Q16.16: a Q.32 vector unit to within 2^-10, rounded to Q16.16 and
 * corrected to first order, v * (1 - e/2): what that leaves out, 3/8 e^2, is below 2^-21, far
 * under the format's step. 32 x 32-bit products only. */
static inline FX_RENORM_INLINE dir3 fx_renorm(int64_t x, int64_t y, int64_t z)
{
    const uint64_t two = (uint64_t)1 << 33; /* 2.0 in Q.32 */
    if (__builtin_expect((uint64_t)x + two >= 2 * two || (uint64_t)y + two >= 2 * two ||
                             (uint64_t)z + two >= 2 * two,
                         0))
        return fx_norm64(x, y, z, 32, 0);
    int32_t a = (int32_t)fx_round_shift(x, 16), b = (int32_t)fx_round_shift(y, 16),
            c = (int32_t)fx_round_shift(z, 16);
    int64_t e = FX_SMUL(a, a) + FX_SMUL(b, b) + FX_SMUL(c, c) - ((int64_t)1 << 32);
    if (__builtin_expect(e > ((int64_t)1 << 22) || e < -((int64_t)1 << 22), 0))
        return fx_norm64(x, y, z, 32, 0);
    int32_t g = (int32_t)(e >> 1); /* e/2 in Q.32, below 2^21 */
    dir3 d = {a - (int32_t)fx_round_shift(FX_SMUL(a, g), 32),
              b - (int32_t)fx_round_shift(FX_SMUL(b, g), 32),
              c - (int32_t)fx_round_shift(FX_SMUL(c, g), 32)};
    return d;
}

/* With unit in Q16.16 the mirrored direction takes fx_renorm itself. */
static inline FX_RENORM_INLINE dir3 fx_renorm_unit(int64_t x, int64_t y, int64_t z)
{
    return fx_renorm(x, y, z);
}
#endif

/* 1/r prepared for d3_norm_near: m = 2^s / r rounded, s = 30 + bits of r (so m is in
 * (2^30, 2^31]), for r in [1/128, 2048] (the scene limits); m = 0 otherwise. m = 2^31 (r a
 * power of two) is kept as 2^30 with s one less, the same ratio exactly: m then fits a signed
 * word, and each product by it is one signed 32 x 32-bit multiply (smull). Costs a 64-bit
 * division: made once per object and frame. */
static inline rinv r_inv_len(real r)
{
    rinv k = {0, 0, r};
    int bits = r > 0 ? 32 - __builtin_clz((uint32_t)r) : 0;
    if (bits < 10 || bits > 28)
        return k;
    k.s = 30 + bits;
    k.m = (uint32_t)((((uint64_t)1 << k.s) + (uint64_t)r / 2) / (uint64_t)r);
    if (k.m == (uint32_t)1 << 31) {
        k.m >>= 1;
        k.s--;
    }
    return k;
}

/* Unit vector along v whose length is within about 2^-13 of the r that k was made from (a
 * point on a sphere minus its centre): v * (1/r), then fx_renorm's correction, with no square
 * root or division. Any other v gets d3_norm's result. */
static inline dir3 d3_norm_near(vec3 v, rinv k)
{
    if (k.m == 0)
        return FX_NORM_REALS(v.x, v.y, v.z, 0);
    /* r < 2^28 (k.m != 0), so 2 r fits 32 bits: each |v.x| <= 2 r by one unsigned compare */
    uint32_t lim = 2u * (uint32_t)k.r;
    if ((uint32_t)v.x + lim > 2 * lim || (uint32_t)v.y + lim > 2 * lim ||
        (uint32_t)v.z + lim > 2 * lim)
        return FX_NORM_REALS(v.x, v.y, v.z, 0);
#if FX_UF == 30
    /* p = v.x m, |p| <= 2 r m, about 2^(s+1) <= 2^59; x = p 2^(60 - s) is v.x / r in Q.60, which
     * fx_renorm would take: the same steps on p. x is in its range [-2^61, 2^61) exactly when p
     * is in [-2^(sh+31), 2^(sh+31)), sh = s - 30 in [9, 28], i.e. when p's high word is in
     * [-2^(sh-1), 2^(sh-1)); and x rounded to Q2.30, (x + 2^29) / 2^30, is (p + 2^(sh-1)) / 2^sh,
     * whose low word comes from the two words of the sum: no 64-bit shift by a variable. */
    int sh = k.s - 30;
    uint32_t half = 1u << (sh - 1);
    int32_t m = (int32_t)k.m; /* below 2^31 */
    int64_t px = FX_SMUL(v.x, m), py = FX_SMUL(v.y, m), pz = FX_SMUL(v.z, m);
    if ((uint32_t)(px >> 32) + half < 2 * half && (uint32_t)(py >> 32) + half < 2 * half &&
        (uint32_t)(pz >> 32) + half < 2 * half) {
        uint64_t qx = (uint64_t)px + half, qy = (uint64_t)py + half, qz = (uint64_t)pz + half;
        dir3 d;
        if (fx_renorm_q30((int32_t)(((uint32_t)qx >> sh) | ((uint32_t)(qx >> 32) << (32 - sh))),
                          (int32_t)(((uint32_t)qy >> sh) | ((uint32_t)(qy >> 32) << (32 - sh))),
                          (int32_t)(((uint32_t)qz >> sh) | ((uint32_t)(qz >> 32) << (32 - sh))),
                          &d))
            return d;
    }
    int64_t f = (int64_t)1 << (60 - k.s);
    return fx_norm64(px * f, py * f, pz * f, 60, 0);
#else
    /* v.x m / 2^s is v.x / r; s >= 39 (r >= 1/128), so Q.32 is a right shift by s - 32 */
    int sh = k.s - 32;
    return fx_renorm(fx_round_shift(v.x * (int64_t)k.m, sh), fx_round_shift(v.y * (int64_t)k.m, sh),
                     fx_round_shift(v.z * (int64_t)k.m, sh));
#endif
}

/* Mirror direction of d about the normal n: d - 2 (d.n) n, renormalised; dn = d3_dot(d, n)
 * (the tracer has it already). |dn| <= 1 + 2^-28, so dn n.x is one signed 32 x 32-bit product
 * (smull) and 2 dn n.x stays below 2^62. For unit d and n (lengths within 2^-28 of one) the
 * vector's length is within 2^-23 of one (docs/numerics.md): fx_renorm_unit. */
static inline dir3 d3_reflect_k(dir3 d, dir3 n, unit dn)
{
    /* formed as 2 (d.x U_ONE / 2 + (-dn) n.x), the same value: a multiply-accumulate onto
     * d.x U_ONE / 2 (smlal), doubled (-dn is in range by the bound on dn) */
    const int64_t half = (int64_t)1 << (FX_UF - 1);
    const int32_t m = -dn;
    int64_t x = 2 * ((int64_t)d.x * half + FX_SMUL(m, n.x));
    int64_t y = 2 * ((int64_t)d.y * half + FX_SMUL(m, n.y));
    int64_t z = 2 * ((int64_t)d.z * half + FX_SMUL(m, n.z));
    return fx_renorm_unit(x, y, z);
}

static inline dir3 d3_reflect(dir3 d, dir3 n) { return d3_reflect_k(d, n, d3_dot(d, n)); }

/* Refraction of d through a surface with normal n facing the incoming ray (d.n <= 0), with
 * eta = n1 / n2 in (0, 3] and dn = d3_dot(d, n). Returns 0 on total internal reflection, else
 * 1 and *out. Formats for unit in Q2.30 (Q.F below: Q.30; with unit in Q16.16, Q.16 and
 * products in Q.32). cosi, eta and the components are 32-bit values, so their products are
 * signed 32 x 32-bit ones (smull); eta d.x is formed in Q.46 (below 3 * 2^46) and scaled. */
static inline int d3_refract_k(dir3 d, dir3 n, unit dn, real eta, dir3 *out)
{
    int32_t cosi = -dn;                                               /* Q.F, |cosi| <= 1 + 2^-28 */
    int64_t eta2 = (FX_SMUL(eta, eta)) >> (32 - FX_UF);               /* Q.F, at most 9 * 2^F */
    int32_t sin2 = U_ONE - (int32_t)((FX_SMUL(cosi, cosi)) >> FX_UF); /* Q.F in [0, 1] */
    const int pre = FX_UF == 30 ? 2 : 0; /* keeps the product below 2^62 */
    int64_t k = U_ONE - ((eta2 * (sin2 >> pre)) >> (FX_UF - pre));
    if (k < 0)
        return 0;
    int64_t cost = fx_isqrt64((uint64_t)k << FX_UF); /* Q.F */
    int64_t m = ((FX_SMUL(eta, cosi)) >> 16) - cost; /* Q.F, |m| < 2^(F + 3) */
    const int64_t e = 1 << (FX_UF - 16);             /* eta d.x in Q.2F */
    int64_t x = FX_SMUL(eta, d.x) * e + m * n.x; /* Q.2F: below 3 * 2^2F + 4 * 2^2F for eta <= 3 */
    int64_t y = FX_SMUL(eta, d.y) * e + m * n.y;
    int64_t z = FX_SMUL(eta, d.z) * e + m * n.z;
    *out = fx_renorm(x, y, z);
    return 1;
}

static inline int d3_refract(dir3 d, dir3 n, real eta, dir3 *out)
{
    return d3_refract_k(d, n, d3_dot(d, n), eta, out);
}

/* ---- in-scene variants, for the sphere test: no saturation test. Objects lie within
 * R_SCENE_MAX (4096) and ray origins within R_SCENE_MAX + R_T_MAX (20480) of the origin (the
 * tracer casts secondary rays only from inside the scene cube to keep it so), so a
 * difference of the two is below 24576 (raw < 2^31), a dot product with a unit vector is a sum
 * of three products below 2^61, and w_len2 of such a difference stays below 2^63. Any breach is
 * signed overflow, which the UBSan test builds report. */
static inline vec3 v3_sub_in(vec3 a, vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline real v3_dot_d_in(vec3 v, dir3 d)
{
    int64_t s = FX_SMUL(v.x, d.x) + FX_SMUL(v.y, d.y) + FX_SMUL(v.z, d.z);
    return (real)fx_round_shift(s, FX_UF);
}
static inline vec3 d3_scale_in(dir3 d, real s)
{
    return v3((real)fx_round_shift(FX_SMUL(s, d.x), FX_UF),
              (real)fx_round_shift(FX_SMUL(s, d.y), FX_UF),
              (real)fx_round_shift(FX_SMUL(s, d.z), FX_UF));
}
#endif
