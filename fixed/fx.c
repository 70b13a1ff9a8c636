/* fx.c: the out-of-line parts of the numeric layer: 64-bit square root, wide normalisation, event counters. */
#include "real.h"

#if FX_COUNT_EVENTS
unsigned long fx_event_count[FX_EV_COUNT];

void fx_events_reset(void)
{
    for (int i = 0; i < FX_EV_COUNT; i++)
        fx_event_count[i] = 0;
}
#endif

#if REAL_FIXED

uint32_t fx_isqrt64(uint64_t n)
{
    if (n == 0)
        return 0;
    /* Digit-by-digit square root, starting from the highest power of four not above n. */
    uint64_t rem = n, res = 0;
    uint64_t bit = (uint64_t)1 << ((63 - __builtin_clzll(n)) & ~1);
    while (bit) {
        if (rem >= res + bit) {
            rem -= res + bit;
            res = (res >> 1) + bit;
        } else {
            res >>= 1;
        }
        bit >>= 2;
    }
    /* rem = n - res^2; (res + 1/2)^2 = res^2 + res + 1/4, so round up when rem > res. */
    if (rem > res)
        res++;
    return res > UINT32_MAX ? UINT32_MAX : (uint32_t)res;
}

/* Taylor series of sin and cos at x (Q2.30, |x| <= pi/4): errors below 2e-9. */
static void fx_sincos_series(unit x, unit *s, unit *c)
{
    unit x2 = u_mul(x, x);
    /* Horner: sin = x (1 - x2/6 (1 - x2/20 (1 - x2/42 (1 - x2/72 (1 - x2/110))))) */
    unit t = U_ONE;
    static const int32_t sin_div[] = {110, 72, 42, 20, 6};
    for (int i = 0; i < 5; i++)
        t = U_ONE - u_divi(u_mul(x2, t), sin_div[i]);
    *s = u_mul(x, t);
    /* cos = 1 - x2/2 (1 - x2/12 (1 - x2/30 (1 - x2/56 (1 - x2/90 (1 - x2/132))))) */
    static const int32_t cos_div[] = {132, 90, 56, 30, 12, 2};
    t = U_ONE;
    for (int i = 0; i < 6; i++)
        t = U_ONE - u_divi(u_mul(x2, t), cos_div[i]);
    *c = t;
}

void u_sincos_deg(real deg, unit *s, unit *c)
{
    /* Fold the angle exactly, in degrees: into [0, 360), then into the first octant. */
    int32_t a = r_mod(deg, R(360.0));
    int quadrant = (int)(a / R(90.0));
    a -= quadrant * R(90.0); /* [0, 90) */
    int swap = a > R(45.0);
    if (swap)
        a = R(90.0) - a; /* [0, 45] */
    /* a degrees in radians as Q2.30: a_raw * (pi / 180) * 2^14, K = pi / 180 * 2^44. */
    const int64_t k = 307041569098LL;
    unit x = (unit)fx_round_shift((int64_t)a * k, 30);
    unit sn, cs;
    fx_sincos_series(x, &sn, &cs);
    if (swap) {
        unit tmp = sn;
        sn = cs;
        cs = tmp;
    }
    switch (quadrant) {
    case 0: *s = sn; *c = cs; break;
    case 1: *s = cs; *c = -sn; break;
    case 2: *s = -sn; *c = -cs; break;
    default: *s = -cs; *c = sn; break;
    }
}

static uint64_t fx_abs64(int64_t v)
{
    return v < 0 ? 0 - (uint64_t)v : (uint64_t)v;
}

/* Scale v by 2^s (s may be negative; a left shift never overflows here, see below). */
static int64_t fx_scale2(int64_t v, int s)
{
    return s >= 0 ? v * ((int64_t)1 << s) : v >> -s;
}

dir3 fx_norm64(int64_t x, int64_t y, int64_t z, int frac, real *len)
{
    dir3 d = {0, 0, 0};
    uint64_t m = fx_abs64(x);
    uint64_t t = fx_abs64(y);
    if (t > m)
        m = t;
    t = fx_abs64(z);
    if (t > m)
        m = t;
    if (m == 0) {
        FX_EVENT(FX_EV_DOMAIN);
        if (len)
            *len = 0;
        return d;
    }
    /* Bring the largest component into [2^29, 2^30): tiny vectors keep all their bits, large
     * ones lose only bits far below the result's precision, and the sum of squares stays
     * below 3 * 2^60. */
    int s = __builtin_clzll(m) - 34;
    int64_t sx = fx_scale2(x, s), sy = fx_scale2(y, s), sz = fx_scale2(z, s);
    uint64_t sum = (uint64_t)(sx * sx) + (uint64_t)(sy * sy) + (uint64_t)(sz * sz);
    uint32_t l = fx_isqrt64(sum); /* in [2^29, 2^31) */
    /* One division: inv = 2^61 / l, at most 2^32; each sx * inv is below 2^62. */
    int64_t inv = (int64_t)((((uint64_t)1 << 61) + l / 2) / l);
    d.x = (unit)fx_round_shift(sx * inv, 31);
    d.y = (unit)fx_round_shift(sy * inv, 31);
    d.z = (unit)fx_round_shift(sz * inv, 31);
    if (len) {
        /* |v| = l * 2^-s in units of 2^-frac; as Q16.16 that is l * 2^(16 - frac - s). */
        int sh = 16 - frac - s;
        if (sh >= 32)
            *len = fx_sat(INT64_MAX);
        else if (sh >= 0)
            *len = fx_sat((int64_t)l << sh);
        else if (sh > -62)
            *len = fx_sat(fx_round_shift(l, -sh));
        else
            *len = 0;
    }
    return d;
}

#endif
