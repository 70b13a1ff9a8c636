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

/* Starting values for 1/sqrt: entry i = round(2^15 / sqrt((i + 128.5) / 128)), i.e. 1/sqrt of the
 * middle of each of 384 intervals of [1, 4), in Q1.15: within 2^-9 over each interval. */
static const uint16_t fx_rsqrt_tab[384] = {
    32704u, 32578u, 32453u, 32329u, 32207u, 32086u, 31966u, 31848u, 31731u, 31616u, 31501u, 31388u,
    31276u, 31166u, 31056u, 30948u, 30840u, 30734u, 30629u, 30525u, 30422u, 30320u, 30219u, 30120u,
    30021u, 29923u, 29826u, 29730u, 29635u, 29540u, 29447u, 29354u, 29263u, 29172u, 29082u, 28993u,
    28905u, 28817u, 28731u, 28645u, 28560u, 28475u, 28392u, 28309u, 28227u, 28145u, 28064u, 27984u,
    27905u, 27826u, 27748u, 27671u, 27594u, 27518u, 27442u, 27368u, 27293u, 27220u, 27147u, 27074u,
    27002u, 26931u, 26860u, 26790u, 26720u, 26651u, 26582u, 26514u, 26447u, 26380u, 26313u, 26247u,
    26182u, 26117u, 26052u, 25988u, 25924u, 25861u, 25799u, 25736u, 25674u, 25613u, 25552u, 25492u,
    25432u, 25372u, 25313u, 25254u, 25196u, 25138u, 25080u, 25023u, 24966u, 24910u, 24854u, 24798u,
    24743u, 24688u, 24633u, 24579u, 24525u, 24472u, 24419u, 24366u, 24313u, 24261u, 24209u, 24158u,
    24107u, 24056u, 24005u, 23955u, 23905u, 23856u, 23807u, 23758u, 23709u, 23661u, 23613u, 23565u,
    23518u, 23470u, 23423u, 23377u, 23331u, 23284u, 23239u, 23193u, 23148u, 23103u, 23058u, 23014u,
    22969u, 22926u, 22882u, 22838u, 22795u, 22752u, 22709u, 22667u, 22625u, 22583u, 22541u, 22499u,
    22458u, 22417u, 22376u, 22335u, 22295u, 22255u, 22215u, 22175u, 22135u, 22096u, 22057u, 22018u,
    21979u, 21941u, 21902u, 21864u, 21826u, 21789u, 21751u, 21714u, 21677u, 21640u, 21603u, 21566u,
    21530u, 21494u, 21458u, 21422u, 21386u, 21351u, 21315u, 21280u, 21245u, 21210u, 21176u, 21141u,
    21107u, 21073u, 21039u, 21005u, 20972u, 20938u, 20905u, 20872u, 20839u, 20806u, 20773u, 20741u,
    20708u, 20676u, 20644u, 20612u, 20580u, 20548u, 20517u, 20486u, 20454u, 20423u, 20392u, 20362u,
    20331u, 20301u, 20270u, 20240u, 20210u, 20180u, 20150u, 20120u, 20091u, 20061u, 20032u, 20003u,
    19974u, 19945u, 19916u, 19887u, 19859u, 19830u, 19802u, 19774u, 19746u, 19718u, 19690u, 19662u,
    19635u, 19607u, 19580u, 19553u, 19526u, 19498u, 19472u, 19445u, 19418u, 19391u, 19365u, 19339u,
    19312u, 19286u, 19260u, 19234u, 19208u, 19183u, 19157u, 19132u, 19106u, 19081u, 19056u, 19030u,
    19005u, 18980u, 18956u, 18931u, 18906u, 18882u, 18857u, 18833u, 18809u, 18785u, 18760u, 18737u,
    18713u, 18689u, 18665u, 18642u, 18618u, 18595u, 18571u, 18548u, 18525u, 18502u, 18479u, 18456u,
    18433u, 18410u, 18388u, 18365u, 18343u, 18320u, 18298u, 18276u, 18253u, 18231u, 18209u, 18187u,
    18166u, 18144u, 18122u, 18100u, 18079u, 18057u, 18036u, 18015u, 17994u, 17972u, 17951u, 17930u,
    17909u, 17888u, 17868u, 17847u, 17826u, 17806u, 17785u, 17765u, 17744u, 17724u, 17704u, 17684u,
    17664u, 17644u, 17624u, 17604u, 17584u, 17564u, 17545u, 17525u, 17505u, 17486u, 17467u, 17447u,
    17428u, 17409u, 17390u, 17370u, 17351u, 17332u, 17314u, 17295u, 17276u, 17257u, 17238u, 17220u,
    17201u, 17183u, 17164u, 17146u, 17128u, 17109u, 17091u, 17073u, 17055u, 17037u, 17019u, 17001u,
    16983u, 16966u, 16948u, 16930u, 16913u, 16895u, 16877u, 16860u, 16843u, 16825u, 16808u, 16791u,
    16773u, 16756u, 16739u, 16722u, 16705u, 16688u, 16671u, 16655u, 16638u, 16621u, 16604u, 16588u,
    16571u, 16555u, 16538u, 16522u, 16505u, 16489u, 16473u, 16456u, 16440u, 16424u, 16408u, 16392u,
};

/* 2^62 / sqrt(x) for x in [2^62, 2^64), in (2^30, 2^31]: the table's 1/sqrt of X = x / 2^32
 * (9 bits), refined by one Newton step y += y (1 - X y^2 / 2^92) / 2 to 17 bits. Every operand
 * fits 32 bits and every product 64 (umull on a 32-bit core): y < 2^31, y^2 / 2^30 < 2^32, and
 * X y^2 / 2^62 is within 2^-7 of 2^30, so 3 * 2^30 minus it stays positive. */
static inline uint32_t fx_rsqrt62(uint64_t x)
{
    uint32_t X = (uint32_t)(x >> 32);
    uint32_t y = (uint32_t)fx_rsqrt_tab[(X >> 23) - 128] << 16;
    uint32_t y2 = (uint32_t)((FX_UMUL(y, y)) >> 30);
    uint32_t xy2 = (uint32_t)((FX_UMUL(X, y2)) >> 32);
    return (uint32_t)((FX_UMUL(y, (3u << 30) - xy2)) >> 31);
}

/* 2^64 / sqrt(x) for x in [2^62, 2^64), in (2^32, 2^33], to about 2^-33 relative (within a
 * quarter unit of a Q2.30 result it scales): one Newton step at 32-bit precision, then a
 * second with the residual 1 - x y^2 formed from every bit of x and y^2. */
static inline uint64_t fx_rsqrt64(uint64_t x)
{
    uint32_t y = fx_rsqrt62(x); /* 2^62 / sqrt(x) within 2^-17, at most 2^31 */
    uint64_t q = FX_UMUL(y, y); /* at most 2^62 */
    uint32_t xh = (uint32_t)(x >> 32), xl = (uint32_t)x, qh = (uint32_t)(q >> 32), ql = (uint32_t)q;
    /* x q / 2^64 = 2^60 (1 - e / 2^60), |e| < 2^45; the dropped xl ql / 2^64 is below 1 */
    uint64_t t = FX_UMUL(xh, qh) + ((FX_UMUL(xh, ql)) >> 32) + ((FX_UMUL(xl, qh)) >> 32);
    int64_t e = (int64_t)(((uint64_t)1 << 60) - t);
    /* y (1 + e / 2^61), scaled by 4: y e / 2^59, with e / 2^14 within +-2^31 */
    return ((uint64_t)y << 2) + (uint64_t)(((int64_t)(int32_t)(e >> 14) * (int64_t)y) >> 45);
}

uint32_t fx_isqrt64(uint64_t n)
{
    if (n == 0)
        return 0;
    /* Division-free: normalise n to [2^62, 2^64), 1/sqrt from fx_rsqrt62, multiply back,
     * correct once by the residual, then fix the last unit exactly. A digit-by-digit loop
     * gives the same results but mispredicts a branch on each of its ~30 steps. Every value that
     * fits a word is kept in one (a 32-bit core then forms no 64-bit compare or product it
     * does not need). */
    int k = __builtin_clzll(n) & ~1;
    uint64_t x = n << k;
    uint32_t X = (uint32_t)(x >> 32);
    uint32_t y = fx_rsqrt62(x); /* 17 bits: the residual step below doubles them */
    uint64_t p = FX_UMUL(X, y);
    uint32_t s0 = p >> 62 ? UINT32_MAX : (uint32_t)(p >> 30); /* p / 2^30 capped at 2^32 - 1 */
    /* s += r / (2 s) = r y / 2^63, r = x - s^2 below 2^48 */
    int64_t r = (int64_t)(x - FX_UMUL(s0, s0));
    int64_t s = (int64_t)s0 + (((r >> 16) * (int64_t)y) >> 47);
    /* s is within a unit of sqrt(x); scaled back and rounded it is within one of sqrt(n)
     * rounded, which is the rr with n - rr^2 in (-rr, rr]: one step to it. */
    int h = k >> 1;
    /* s is at most 2^32 (x < 2^64); capping it at 2^32 - 1 changes no result: for h = 0 rr is
     * capped the same, for h >= 1 2^32 + 2^(h-1) is no multiple of 2^h, so the rounded shift
     * is the same. Then the rounded shift in 32 bits: s / 2^h rounded half up is s >> h plus
     * bit h - 1 of s; rr is at least 1 (x >= 2^62, so s >= 2^31 - 1 and h <= 31). */
    uint32_t s32 = s > (int64_t)UINT32_MAX ? UINT32_MAX : (uint32_t)s;
    uint32_t rr = h ? (s32 >> h) + ((s32 >> (h - 1)) & 1) : s32;
    int64_t d = (int64_t)(n - FX_UMUL(rr, rr)); /* |d| < 2^34: wraps back */
    if (d > (int64_t)rr)
        return rr == UINT32_MAX ? rr : rr + 1; /* 2^32 is capped */
    return rr - (d <= -(int64_t)rr);
}

/* Taylor series of sin and cos at x (a unit, |x| <= pi/4): errors below 2e-9 in Q2.30. */
static FX_BOARD_THUMB __attribute__((cold)) void fx_sincos_series(unit x, unit *s, unit *c)
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

/* Once per frame (the camera's field of view): compiled for size (cold). */
FX_BOARD_THUMB __attribute__((cold)) void u_sincos_deg(real deg, unit *s, unit *c)
{
    /* Fold the angle exactly, in degrees: into [0, 360), then into the first octant. */
    int32_t a = r_mod(deg, R(360.0));
    int quadrant = (int)(a / R(90.0));
    a -= quadrant * R(90.0); /* [0, 90) */
    int swap = a > R(45.0);
    if (swap)
        a = R(90.0) - a; /* [0, 45] */
    /* a degrees in radians as a unit: a_raw * (pi / 180) * 2^(FX_UF - 16), K = pi / 180 * 2^44,
     * the product in Q.60 (below 2^60). */
    const int64_t k = 307041569098LL;
    unit x = (unit)fx_round_shift((int64_t)a * k, 60 - FX_UF);
    unit sn, cs;
    fx_sincos_series(x, &sn, &cs);
    if (swap) {
        unit tmp = sn;
        sn = cs;
        cs = tmp;
    }
    switch (quadrant) {
    case 0:
        *s = sn;
        *c = cs;
        break;
    case 1:
        *s = cs;
        *c = -sn;
        break;
    case 2:
        *s = -sn;
        *c = -cs;
        break;
    default:
        *s = -cs;
        *c = sn;
        break;
    }
}

static uint64_t fx_abs64(int64_t v) { return v < 0 ? 0 - (uint64_t)v : (uint64_t)v; }

/* The magnitudes of three 32-bit components (each at most 2^31) ORed: zero exactly when all
 * are, and with the same highest set bit as the largest of them, which is all normalisation
 * scales by (a clz); no compare. */
static inline uint32_t fx_abs32(int32_t v)
{
    uint32_t sg = (uint32_t)(v >> 31); /* all ones for a negative v: (v ^ -1) + 1 = -v */
    return ((uint32_t)v ^ sg) - sg;
}
static inline uint32_t fx_top_abs3_32(int32_t x, int32_t y, int32_t z)
{
    return fx_abs32(x) | fx_abs32(y) | fx_abs32(z);
}

/* The same for three 64-bit components. */
static uint64_t fx_top_abs3(int64_t x, int64_t y, int64_t z)
{
    return fx_abs64(x) | fx_abs64(y) | fx_abs64(z);
}

/* What normalising a zero vector gives: (0, 0, 0), length 0, and a domain event. */
static dir3 fx_norm_zero(real *len)
{
    dir3 d = {0, 0, 0};
    FX_EVENT(FX_EV_DOMAIN);
    if (len)
        *len = 0;
    return d;
}

/* z ~ 2^62 / m for m in [2^31, 2^32), in (2^30, 2^31 + 2^23), within about 2 units, in 32-bit
 * words (an ARM926 has no 64 x 64-bit product: each one below is a single umull/smull): from
 * the 1/sqrt table (x = m / 2^30 in [2, 4), y = entry * 2^16 = 2^31 / sqrt(x), so y^2 / 2^30 =
 * 2^62 / m to about 2^-8), then two Newton steps z += z (2^62 - m z) / 2^62 (2^-16, then the
 * 2^-30 the arithmetic holds), each correction formed from e / 2^30, which fits 32 bits
 * (|e| < 2^55, then 2^47). */
static inline uint32_t fx_recip62(uint32_t m)
{
    uint32_t y = (uint32_t)fx_rsqrt_tab[(m >> 23) - 128] << 16;
    uint32_t z = (uint32_t)((FX_UMUL(y, y)) >> 30);
    for (int i = 0; i < 2; i++) {
        int64_t e = (int64_t)(((uint64_t)1 << 62) - FX_UMUL(m, z)); /* no wrap */
        z = (uint32_t)((int64_t)z + (((int64_t)(int32_t)(e >> 30) * (int64_t)z) >> 32));
    }
    return z;
}

uint64_t fx_udiv64(uint64_t n, uint32_t m)
{
    /* q ~ n z / 2^(62-k) with z ~ 2^62 / (m 2^k), the 94-bit product formed from n's halves,
     * each a 32 x 32-bit one, as (n z) / 2^31 (below 2^63) shifted by 31 - k; then the exact
     * quotient by the remainder, or the library's division when the estimate is off by more
     * than a few units (large quotients, where z's relative error of 2^-30 shows). */
    int k = __builtin_clz(m);
    uint32_t z = fx_recip62(m << k);
    uint32_t nh = (uint32_t)(n >> 32), nl = (uint32_t)n;
    uint64_t q = ((FX_UMUL(nh, z)) * 2 + ((FX_UMUL(nl, z)) >> 31)) >> (31 - k);
    int64_t r = (int64_t)(n - q * m);
    /* r in [-4m, 4m) by one unsigned compare (8m < 2^35) */
    if ((uint64_t)r + 4 * (uint64_t)m >= 8 * (uint64_t)m)
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

#if FX_UF == 30
/* v r rounded and shifted right by 32 + t (t = 0 or 1), for |v| <= 2^30 and r in (2^32, 2^33]
 * given as rl, its low word read as signed, and rh = (r - rl) / 2^32 (1 to 3), with half =
 * 2^(31 + t): v r = v rl + v rh 2^32 is a signed 32x32-bit product and a 32-bit one added to its
 * high word (the sum fits 64 bits, so forming it modulo 2^64 is exact); the rounding half is
 * added, the high word taken and shifted by t. */
static inline unit fx_mul_r(int32_t v, int32_t rl, uint32_t rh, uint64_t half, int t)
{
    uint64_t p = (uint64_t)(FX_SMUL(v, rl)) + ((uint64_t)((uint32_t)v * rh) << 32) + half;
    return (unit)((int32_t)(p >> 32) >> t);
}

/* The unit vector, and the length (len may be NULL), of (sx, sy, sz) 2^-s in units of 2^-frac,
 * where the largest of |sx|, |sy|, |sz| is in [2^29, 2^30]: the sum of squares lies in
 * [2^58, 3 * 2^60). No square root and no division: with sum = xs 2^-k, xs in [2^62, 2^64)
 * (k = 2 or 4), r = fx_rsqrt64(xs) ~ 2^64 / sqrt(xs), so 1 / |v| = r 2^(k/2) / 2^64 and each
 * component of the unit vector, in Q2.30, is sx r / 2^(34 - k/2) (fx_mul_r), below 2^63 before
 * the shift. Inlined into both callers: fx_norm32_to's copy (light directions, the most
 * frequent) then has frac = 16 and the call is saved. */
static inline __attribute__((always_inline)) dir3 fx_norm_scaled(int32_t sx, int32_t sy, int32_t sz,
                                                                 int s, int frac, real *len)
{
    dir3 d;
    uint64_t sum =
        (uint64_t)(FX_SMUL(sx, sx)) + (uint64_t)(FX_SMUL(sy, sy)) + (uint64_t)(FX_SMUL(sz, sz));
    int k = __builtin_clz((uint32_t)(sum >> 32)) & ~1; /* the high word is at least 2^26 */
    uint64_t xs = sum << k;
    uint64_t r = fx_rsqrt64(xs);
    int t = k == 2;
    uint64_t half = (uint64_t)(1 + t) << 31; /* 2^(31 + t): constant shifts */
    int32_t rl = (int32_t)(uint32_t)r;
    uint32_t rh = (uint32_t)(r >> 32) + ((uint32_t)r >> 31);
    d.x = fx_mul_r(sx, rl, rh, half, t);
    d.y = fx_mul_r(sy, rl, rh, half, t);
    d.z = fx_mul_r(sz, rl, rh, half, t);
    if (len) {
        /* sqrt(xs) = xs / sqrt(xs) ~ (xs / 2^32) (r / 2) / 2^31, sqrt(sum) = sqrt(xs) 2^(-k/2):
         * l in [2^29, 2^31], to about a unit: (xs / 2^32) (r / 2) / 2^(30 + k/2), halved and
         * rounded, i.e. (product + 2^(30 + k/2)) / 2^(31 + k/2), taken as the high word shifted
         * by 1 - t. |v| = l * 2^-s in units of 2^-frac; as Q16.16 that is l * 2^(16 - frac - s). */
        uint64_t pl = (xs >> 32) * (r >> 1) + ((uint64_t)(2 - t) << 31); /* below 2^63 */
        uint32_t l = (uint32_t)(pl >> 32) >> (1 - t);
        int sh = 16 - frac - s;
        if (sh >= 32)
            *len = fx_sat(INT64_MAX);
        else if (sh >= 0)
            *len = fx_sat((int64_t)l << sh);
        else if (sh > -32) /* rounded in 32 bits: l + 2^30 does not overflow */
            *len = (real)((l + (1u << (-sh - 1))) >> -sh);
        else
            *len = 0;
    }
    return d;
}

/* Cold: compiled for size. It normalises every primary ray (fx_ray_dir), but on 32-bit ARM it
 * is flattened into fx_ray_dir, and on x86-64 not marking it cold changes no measurable time
 * (docs/probe.md); its other callers are off the usual paths (the camera's frame once per frame,
 * fx_renorm's far-from-unit fallback). */
__attribute__((cold)) dir3 fx_norm64(int64_t x, int64_t y, int64_t z, int frac, real *len)
{
    uint64_t m = fx_top_abs3(x, y, z);
    if (m == 0)
        return fx_norm_zero(len);
    /* Bring the largest component into [2^29, 2^30): tiny vectors keep all their bits, large
     * ones lose only bits far below the result's precision (shifted right, rounded down). */
    int s = __builtin_clzll(m) - 34;
    int32_t sx, sy, sz;
    if (s >= 0) {
        sx = (int32_t)(x * ((int64_t)1 << s));
        sy = (int32_t)(y * ((int64_t)1 << s));
        sz = (int32_t)(z * ((int64_t)1 << s));
    } else if (s > -32) {
        /* each result fits 32 bits, so it is the low word of x >> -s: from x's two words,
         * without a 64-bit shift by a variable (the primary rays' case: s about -29) */
        int sh = -s;
        sx = (int32_t)(((uint32_t)x >> sh) | ((uint32_t)((uint64_t)x >> 32) << (32 - sh)));
        sy = (int32_t)(((uint32_t)y >> sh) | ((uint32_t)((uint64_t)y >> 32) << (32 - sh)));
        sz = (int32_t)(((uint32_t)z >> sh) | ((uint32_t)((uint64_t)z >> 32) << (32 - sh)));
    } else {
        sx = (int32_t)(x >> -s);
        sy = (int32_t)(y >> -s);
        sz = (int32_t)(z >> -s);
    }
    return fx_norm_scaled(sx, sy, sz, s, frac, len); /* one inlined copy */
}

real fx_norm32_to(dir3 *out, int32_t x, int32_t y, int32_t z)
{
    real len;
    uint32_t m = fx_top_abs3_32(x, y, z);
    /* The largest magnitude 2^s in [2^29, 2^30): s >= -2. A component of 2^30 or more (8192
     * units and beyond: rare) goes through fx_norm64, which forms the same s and the same
     * shifted components from the 64-bit ones, hence the same results (test_numeric); the usual
     * case then needs no right shifts. */
    if (m == 0 || m >= (1u << 30)) {
        *out = m == 0 ? fx_norm_zero(&len) : fx_norm64(x, y, z, 16, &len);
        return len;
    }
    int s = __builtin_clz(m) - 2;
    x *= 1 << s;
    y *= 1 << s;
    z *= 1 << s;
    *out = fx_norm_scaled(x, y, z, s, 16, &len); /* one inlined copy */
    return len;
}

#else
/* 2^46 / sqrt(x) for x in [2^30, 2^32), in (2^30, 2^31]: the table's 1/sqrt and one Newton step
 * in 32 x 32-bit products, to about 2^-17 relative: enough for a Q16.16 result. */
static inline uint32_t fx_rsqrt32(uint32_t x)
{
    uint32_t y = fx_rsqrt_tab[(x >> 23) - 128];           /* 2^30 / sqrt(x) within 2^-9 */
    uint32_t t = (uint32_t)((FX_UMUL(x, (y * y))) >> 30); /* x y^2 / 2^30, about 2^30 */
    uint64_t r = ((uint64_t)y * ((3u << 30) - t)) >> 15;
    return r > INT32_MAX ? INT32_MAX : (uint32_t)r;
}

/* The unit vector, and the length (len may be NULL), of (x, y, z) 2^-s in units of 2^-frac,
 * where the largest of |x|, |y|, |z| is in [2^15, 2^16]: the squares and their sum from 32-bit
 * values, 1/sqrt by fx_rsqrt32, no 64 x 64-bit product. */
static inline dir3 fx_norm_scaled(int32_t sx, int32_t sy, int32_t sz, int s, int frac, real *len)
{
    dir3 d;
    /* sum in [2^30, 3 * 2^32]: xs = sum / 4^j in [2^30, 2^32) */
    uint64_t sum = (uint64_t)(FX_SMUL(sx, sx) + FX_SMUL(sy, sy) + FX_SMUL(sz, sz));
    int j = sum >> 32 != 0;
    uint32_t xs = j ? (uint32_t)(sum >> 2) : (uint32_t)sum;
    uint32_t r = fx_rsqrt32(xs) >> j; /* 2^46 / sqrt(sum), in (2^29, 2^31) */
    /* component / sqrt(sum) in Q16.16 = sx 2^16 r / 2^46 = (4 sx) r / 2^32: the high word */
    d.x = (unit)(((int64_t)(sx * 4) * (int32_t)r + ((int64_t)1 << 31)) >> 32);
    d.y = (unit)(((int64_t)(sy * 4) * (int32_t)r + ((int64_t)1 << 31)) >> 32);
    d.z = (unit)(((int64_t)(sz * 4) * (int32_t)r + ((int64_t)1 << 31)) >> 32);
    if (len) {
        /* sqrt(sum) 2^16 = sum r 2^16 / 2^46 = xs r / 2^(30 - 2j) (below 2^63 before the
         * shift); |v| = sqrt(sum) 2^-s in units of 2^-frac: as Q16.16, xs r 2^sh */
        int64_t l = (int64_t)(FX_UMUL(xs, r));
        int sh = 2 * j - 30 - frac - s;
        if (sh >= 32)
            *len = fx_sat(INT64_MAX);
        else if (sh >= 0)
            *len = fx_sat(l << sh);
        else if (sh > -63)
            *len = fx_sat(fx_round_shift(l, -sh));
        else
            *len = 0;
    }
    return d;
}

/* Unit in Q16.16, any 64-bit vector: the largest component is brought into [2^15, 2^16]
 * (rounded) and fx_norm_scaled does the rest. */
/* Cold: compiled for size. It normalises every primary ray (fx_ray_dir), but on 32-bit ARM it
 * is flattened into fx_ray_dir, and on x86-64 not marking it cold changes no measurable time
 * (docs/probe.md); its other callers are off the usual paths (the camera's frame once per frame,
 * fx_renorm's far-from-unit fallback). */
__attribute__((cold)) dir3 fx_norm64(int64_t x, int64_t y, int64_t z, int frac, real *len)
{
    uint64_t m = fx_top_abs3(x, y, z);
    if (m == 0)
        return fx_norm_zero(len);
    int s = __builtin_clzll(m) - 48; /* the largest magnitude 2^s in [2^15, 2^16) */
    if (s >= 0)
        return fx_norm_scaled((int32_t)(x * ((int64_t)1 << s)), (int32_t)(y * ((int64_t)1 << s)),
                              (int32_t)(z * ((int64_t)1 << s)), s, frac, len);
    return fx_norm_scaled((int32_t)fx_round_shift(x, -s), (int32_t)fx_round_shift(y, -s),
                          (int32_t)fx_round_shift(z, -s), s, frac, len);
}

real fx_norm32_to(dir3 *out, int32_t x, int32_t y, int32_t z)
{
    real len;
    uint32_t m = fx_top_abs3_32(x, y, z);
    if (m == 0) {
        *out = fx_norm_zero(&len);
        return len;
    }
    int s = __builtin_clz(m) - 16; /* the largest magnitude 2^s in [2^15, 2^16) */
    if (s >= 0)
        *out = fx_norm_scaled(x * (1 << s), y * (1 << s), z * (1 << s), s, 16, &len);
    else
        *out = fx_norm_scaled(fx_round_shift32(x, -s), fx_round_shift32(y, -s),
                              fx_round_shift32(z, -s), s, 16, &len);
    return len;
}
#endif

/* fx_norm64's results for 32-bit components (the same s, shifted components and results as
 * fx_norm32_to's, test_numeric), the length formed only where it is asked for, so one beyond
 * real's range counts no event the caller did not ask for. Off the tracer's usual paths (once a
 * frame, or fallbacks): the light direction has fx_norm32_to. */
FX_BOARD_THUMB
dir3 fx_norm32(int32_t x, int32_t y, int32_t z, real *len) { return fx_norm64(x, y, z, 16, len); }

/* The primary ray through a pixel (d3_ray): f + r*(step*ia) + u*(step*ib), ia and ib the
 * pixel's offsets from the image centre in half pixels, normalised. Formed in Q.58 when
 * step*|ia| and step*|ib| are below 8 (any field of view on frames up to 4:1); a wider image
 * plane (a 4096x2 frame reaches 7000) is formed with as many more bits of shift as it needs,
 * so that every term stays below 2^61 and the sums below 2^63. With unit in Q16.16 the offsets
 * are rounded to Q.16 (below 2^29 on any frame) and the sums are Q.32 (below 2^47). On 32-bit
 * ARM with fx_norm64 inlined into it (flatten: fewer instructions a primary ray on the board, for
 * a larger image); elsewhere a plain call, which keeps the desktop player small. */
#if defined(__arm__)
__attribute__((flatten))
#endif
dir3 fx_ray_dir(const dir3 *f, const dir3 *r, const dir3 *u, ustep step, int32_t ia, int32_t ib)
{
    int64_t x, y, z;
#if FX_UF == 30
    /* The usual frame (step * |ia| and step * |ib| within 2^31: any frame up to 1280 pixels
     * wide at a 90-degree field of view): both offsets fit a word, so sh below is 2 and the
     * shifted offsets are the words' own arithmetic shifts, the same values from two 32-bit
     * products and their overflow tests (on 32-bit cores). */
    int32_t as, bs, a32, b32;
    int sh = 2;
    if (!FX_WORD64 && /* a 64-bit core forms the products below as cheaply */
        __builtin_expect(!__builtin_mul_overflow(step, ia, &a32) &&
                             !__builtin_mul_overflow(step, ib, &b32),
                         1)) {
        as = a32 >> 2;
        bs = b32 >> 2;
    } else {
        int64_t a = FX_SMUL(step, ia), b = FX_SMUL(step, ib); /* Q.30, below 2^44 */
        uint64_t big =
            (a < 0 ? 0 - (uint64_t)a : (uint64_t)a) | (b < 0 ? 0 - (uint64_t)b : (uint64_t)b);
        /* the smallest sh >= 2 with both offsets below 2^(31 + sh): then a and b shifted fit
         * 32 bits and every product is a signed 32x32-bit one (smull, smlal) */
        sh = big >> 33 ? 33 - __builtin_clzll(big) : 2;
        as = (int32_t)(a >> sh);
        bs = (int32_t)(b >> sh);
    }
    if (__builtin_expect(sh == 2, 1)) { /* the usual frame: constant shifts */
        x = FX_SMUL(f->x, (1 << 28)) + FX_SMUL(r->x, as) + FX_SMUL(u->x, bs);
        y = FX_SMUL(f->y, (1 << 28)) + FX_SMUL(r->y, as) + FX_SMUL(u->y, bs);
        z = FX_SMUL(f->z, (1 << 28)) + FX_SMUL(r->z, as) + FX_SMUL(u->z, bs);
    } else {
        x = (int64_t)f->x * ((int64_t)1 << (30 - sh)) + FX_SMUL(r->x, as) + FX_SMUL(u->x, bs);
        y = (int64_t)f->y * ((int64_t)1 << (30 - sh)) + FX_SMUL(r->y, as) + FX_SMUL(u->y, bs);
        z = (int64_t)f->z * ((int64_t)1 << (30 - sh)) + FX_SMUL(r->z, as) + FX_SMUL(u->z, bs);
    }
#else
    int32_t a = (int32_t)fx_round_shift(FX_SMUL(step, ia), 14);
    int32_t b = (int32_t)fx_round_shift(FX_SMUL(step, ib), 14);
    x = (int64_t)f->x * 65536 + FX_SMUL(r->x, a) + FX_SMUL(u->x, b);
    y = (int64_t)f->y * 65536 + FX_SMUL(r->y, a) + FX_SMUL(u->y, b);
    z = (int64_t)f->z * 65536 + FX_SMUL(r->z, a) + FX_SMUL(u->z, b);
#endif
    return fx_norm64(x, y, z, 0, 0); /* the direction alone: frac does not matter */
}

#endif
