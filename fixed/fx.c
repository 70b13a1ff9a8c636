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

/* Starting values for 1/sqrt: entry i = round(2^31 / sqrt((i + 32.5) / 32)), i.e. 1/sqrt of the
 * middle of each of 96 intervals of [1, 4) in Q1.31. */
static const uint32_t fx_rsqrt_tab[96] = {
    2130900515u, 2098855072u, 2068213208u, 2038875364u, 2010751598u, 1983760420u,
    1957827796u, 1932886296u, 1908874354u, 1885735628u, 1863418444u, 1841875310u,
    1821062491u, 1800939636u, 1781469447u, 1762617387u, 1744351429u, 1726641819u,
    1709460876u, 1692782810u, 1676583559u, 1660840642u, 1645533028u, 1630641020u,
    1616146146u, 1602031062u, 1588279468u, 1574876026u, 1561806289u, 1549056637u,
    1536614214u, 1524466875u, 1512603139u, 1501012140u, 1489683584u, 1478607716u,
    1467775280u, 1457177486u, 1446805984u, 1436652834u, 1426710480u, 1416971728u,
    1407429723u, 1398077927u, 1388910104u, 1379920300u, 1371102827u, 1362452250u,
    1353963368u, 1345631207u, 1337451002u, 1329418191u, 1321528399u, 1313777432u,
    1306161267u, 1298676040u, 1291318043u, 1284083712u, 1276969620u, 1269972473u,
    1263089103u, 1256316458u, 1249651603u, 1243091706u, 1236634043u, 1230275986u,
    1224014999u, 1217848637u, 1211774541u, 1205790433u, 1199894112u, 1194083452u,
    1188356400u, 1182710970u, 1177145240u, 1171657354u, 1166245512u, 1160907976u,
    1155643060u, 1150449133u, 1145324612u, 1140267967u, 1135277711u, 1130352405u,
    1125490652u, 1120691096u, 1115952423u, 1111273357u, 1106652658u, 1102089122u,
    1097581581u, 1093128899u, 1088729972u, 1084383727u, 1080089122u, 1075845140u,
};

uint32_t fx_isqrt64(uint64_t n)
{
    if (n == 0)
        return 0;
    /* Division-free: normalise n to [2^62, 2^64), refine 1/sqrt by two Newton steps from the
     * table (8 -> 16 -> 30 bits), multiply back, correct once by the residual, then fix the
     * last unit exactly. A digit-by-digit loop gives the same results but mispredicts a
     * branch on each of its ~30 steps. */
    int k = __builtin_clzll(n) & ~1;
    uint64_t x = n << k;
    uint32_t X = (uint32_t)(x >> 32);
    uint64_t y = fx_rsqrt_tab[(x >> 57) - 32];
    for (int i = 0; i < 2; i++) {
        uint64_t y2 = (y * y) >> 30;
        uint64_t xy2 = ((uint64_t)X * y2) >> 32;
        y = (y * ((3u << 30) - xy2)) >> 31;
    }
    uint64_t s = ((uint64_t)X * y) >> 30;
    if (s > UINT32_MAX)
        s = UINT32_MAX;
    int64_t r = (int64_t)(x - s * s);
    s = (uint64_t)((int64_t)s + (((r >> 8) * (int64_t)y) >> 55));
    uint64_t rr = s >> (k >> 1);
    if (rr > UINT32_MAX)
        rr = UINT32_MAX;
    uint64_t sq = rr * rr;
    rr -= sq > n;
    sq = rr * rr;
    rr += (n - sq) > 2 * rr;
    sq = rr * rr;
    rr += (n - sq) > rr; /* round to nearest: n - rr^2 > rr means sqrt(n) > rr + 1/2 */
    return rr > UINT32_MAX ? UINT32_MAX : (uint32_t)rr;
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

/* z ~ 2^63 / m for m in [2^31, 2^32), within a few units: from the 1/sqrt table (x = m / 2^30
 * in [2, 4), entry y = 2^31 / sqrt(x), so y^2 / 2^29 = 2^63 / m to about 2^-8), then three
 * Newton steps z += z (2^63 - m z) / 2^63, each correction formed from e / 2^31 so that the
 * product fits. */
static inline uint64_t fx_recip63(uint64_t m)
{
    uint64_t y = fx_rsqrt_tab[(m >> 25) - 32];
    uint64_t z = (y * y) >> 29;
    for (int i = 0; i < 3; i++) {
        int64_t e = (int64_t)(((uint64_t)1 << 63) - m * z); /* |e| < 2^56: no wrap */
        z = (uint64_t)((int64_t)z + (((e >> 31) * (int64_t)z) >> 32));
    }
    return z;
}

uint64_t fx_udiv64(uint64_t n, uint32_t m)
{
    /* q ~ n z / 2^(63-k) with z ~ 2^63 / (m 2^k), the 94-bit product formed from n's halves
     * (z is capped at 2^32 so that the low half's product fits); then the exact quotient by
     * the remainder, or the library's division when the estimate is off by more than a few
     * units (large quotients, where z's relative error of 2^-30 shows). */
    int k = __builtin_clz(m);
    uint64_t z = fx_recip63((uint64_t)m << k);
    if (z > ((uint64_t)1 << 32))
        z = (uint64_t)1 << 32;
    uint64_t nh = n >> 32, nl = n & 0xFFFFFFFFu;
    uint64_t q = ((nh * z) + ((nl * z) >> 32)) >> (31 - k);
    int64_t r = (int64_t)(n - q * m);
    if (r < -4 * (int64_t)m || r >= 4 * (int64_t)m)
        return n / m;
    while (r < 0) {
        q--;
        r += m;
    }
    while (r >= (int64_t)m) {
        q++;
        r -= m;
    }
    return q;
}

uint64_t fx_recip61(uint32_t l)
{
    /* z ~ 2^63 / M for M = l normalised to [2^31, 2^32) */
    int k = __builtin_clz(l); /* 1 or 2 */
    uint64_t z = fx_recip63((uint64_t)l << k);
    /* (2^61 + h) / l = (2^61 + h) 2^k / M ~ z 2^(k-2) + h z / 2^(63-k), h = l/2; then the
     * exact quotient by the remainder (a few steps at most). */
    uint64_t h = l >> 1, n = ((uint64_t)1 << 61) + h;
    uint64_t q = (z >> (2 - k)) + ((h * z) >> (63 - k));
    int64_t r = (int64_t)(n - q * l);
    while (r < 0) {
        q--;
        r += l;
    }
    while (r >= (int64_t)l) {
        q++;
        r -= l;
    }
    return q;
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
    /* inv = 2^61 / l rounded, at most 2^32; each sx * inv is below 2^62. */
#if FX_SOFT_DIVIDE
    int64_t inv = (int64_t)fx_recip61(l);
#else
    int64_t inv = (int64_t)((((uint64_t)1 << 61) + l / 2) / l);
#endif
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
