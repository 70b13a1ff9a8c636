/* noise.c: 3D Perlin gradient noise, fBm and turbulence, and the colour palettes of the textures. */
#include "noise.h"

#include "rt_local.h"

/* Lattice coordinates are Q16.16 integers modulo the period: 24 bits. */
#define NOISE_FRAC 16
#define NOISE_ONE (1 << NOISE_FRAC)
#define NOISE_COORD_MASK ((uint32_t)RT_NOISE_PERIOD * NOISE_ONE - 1)

/* NOISE_OPAQUE(x): the value of x is unknown to the optimiser from here on (no instruction).
 * Speed only: GCC for ARM then keeps a mask as a mask, so that the shift after it goes into
 * the load's address (an and and a shifted-register load, not a shift, an and and a load). */
#if defined(__arm__)
#define NOISE_OPAQUE(x) __asm__("" : "+r"(x))
#else
#define NOISE_OPAQUE(x) (void)(x) /* x86-64: the barrier costs more than it saves */
#endif

/* The hash is a product per axis, the three XORed, then mixed: the per-axis products of a
 * cell's two corners along each axis are shared by its eight corners. */
#define NOISE_HX 0x8DA6B343u
#define NOISE_HY 0xD8163841u
#define NOISE_HZ 0xCB1AB31Fu

/* The mixer's first step, h ^ (h >> 15), is linear over XOR: applied to each per-axis term it
 * gives the same as applied to their XOR, so the eight corners share it. */
static inline uint32_t noise_spread(uint32_t h) { return h ^ h >> 15; }

/* The rest of the mixer, on a spread value. */
static inline uint32_t noise_mix_spread(uint32_t h)
{
    h *= 0x2C1B3C6Du;
    return h ^ h >> 12;
}

static inline uint32_t noise_mix(uint32_t h) { return noise_mix_spread(noise_spread(h)); }

uint32_t rt_noise_hash(int32_t i, int32_t j, int32_t k)
{
    const uint32_t mask = RT_NOISE_PERIOD - 1;
    return noise_mix(((uint32_t)i & mask) * NOISE_HX ^ ((uint32_t)j & mask) * NOISE_HY ^
                     ((uint32_t)k & mask) * NOISE_HZ);
}

/* The gradients: the twelve edges of the cube, four repeated to make sixteen, one per value of
 * a hash's bits 8..11: (1, 1, 0), (-1, 1, 0), (1, -1, 0), (-1, -1, 0), (1, 0, 1), (-1, 0, 1),
 * (1, 0, -1), (-1, 0, -1), (0, 1, 1), (0, -1, 1), (0, 1, -1), (0, -1, -1), then (1, 1, 0),
 * (0, -1, 1), (-1, 1, 0), (0, -1, -1). The offset from corner c = (cx, cy, cz) of the cell
 * (cx, cy, cz in {0, 1}) to the point is (x, y, z) - c, (x, y, z) the offset from corner 0, so
 * a gradient's dot product with it is g . (x, y, z) - g . c: the first part is the same for
 * every corner (noise_eval tabulates it once per point from six sums and differences), the
 * second is this table: noise_corner[cx + 2 cy + 4 cz - 1][g] = -g . c. */
static const int32_t noise_corner[7][16] = {
    {-1, 1, -1, 1, -1, 1, -1, 1, 0, 0, 0, 0, -1, 0, 1, 0},   /* c = (1, 0, 0) */
    {-1, -1, 1, 1, 0, 0, 0, 0, -1, 1, -1, 1, -1, 1, -1, 1},  /* c = (0, 1, 0) */
    {-2, 0, 0, 2, -1, 1, -1, 1, -1, 1, -1, 1, -2, 1, 0, 1},  /* c = (1, 1, 0) */
    {0, 0, 0, 0, -1, -1, 1, 1, -1, -1, 1, 1, 0, -1, 0, 1},   /* c = (0, 0, 1) */
    {-1, 1, -1, 1, -2, 0, 0, 2, -1, -1, 1, 1, -1, -1, 1, 1}, /* c = (1, 0, 1) */
    {-1, -1, 1, 1, -1, -1, 1, 1, -2, 0, 0, 2, -1, 0, -1, 2}, /* c = (0, 1, 1) */
    {-2, 0, 0, 2, -2, 0, 0, 2, -2, 0, 0, 2, -2, 0, 0, 2},    /* c = (1, 1, 1) */
};

/* Dot product of the gradient picked by bits 8..11 of the hash h with the offset from corner c
 * (0..7): dots[g] = g . (x, y, z), the Q16.16 offset from corner 0 (in [0, 1): within +-2),
 * plus -g . c. */
static inline int32_t noise_dot(uint32_t h, const int32_t dots[16], int c)
{
    uint32_t g = h & 0xF00; /* g 2^8: the byte offset of column g in a row of 16 words is g >> 6 */
    NOISE_OPAQUE(g);
    int32_t d = *(const int32_t *)((const char *)dots + (g >> 6));
    return c == 0
        ? d
        : d + *(const int32_t *)((const char *)noise_corner[c - 1] + (g >> 6)) * NOISE_ONE;
}

/* Quintic fade 6t^5 - 15t^4 + 10t^3 of t in [0, 1) (Q16.16): zero first and second
 * derivatives at 0 and 1. t^3 is kept in Q.32 and the factor 10 - t (15 - 6t) in Q16.16, each
 * rounded once: within 2 LSB of the exact value. The last rounding adds the product's bit 31
 * to its high word (the carry of adding 2^31). */
static inline int32_t noise_fade(uint32_t t)
{
    uint32_t t3 =
        (uint32_t)((((uint64_t)(t * t) * t + (NOISE_ONE >> 1)) << (32 - NOISE_FRAC)) >> 32);
    uint32_t inner = 10 * NOISE_ONE -
        (uint32_t)(((uint64_t)t * (15 * NOISE_ONE - 6 * t) + (NOISE_ONE >> 1)) >> NOISE_FRAC);
    uint64_t p = (uint64_t)t3 * inner;
    return (int32_t)((uint32_t)(p >> 32) + ((uint32_t)p >> 31));
}

/* A fade value t in [0, 1] (Q16.16), and split into its high and low bytes, t = 256 hi + lo, for
 * interpolations in 32 bits. */
typedef struct noise_weight {
    int32_t t, hi, lo;
} noise_weight;

static inline noise_weight noise_weight_of(int32_t t) { return (noise_weight){t, t >> 8, t & 255}; }

/* a + (b - a) t rounded half up, t = 256 t.hi + t.lo in [0, 1] (Q16.16), |a|, |b| <= 2 (2^17):
 * floor(((b - a) t + 2^15) / 2^16) = floor((P + floor(Q / 2^8)) / 2^8) with
 * P = (b - a) t.hi + 2^7 and Q = (b - a) t.lo, both below 2^27 in magnitude: the same value as
 * the 64-bit product, in 32-bit arithmetic. On 64-bit machines, the 64-bit product itself (fewer
 * instructions there). */
static inline int32_t noise_lerp(int32_t a, int32_t b, noise_weight t)
{
    int32_t d = b - a;
#if UINTPTR_MAX > 0xFFFFFFFFu
    return a + (int32_t)(((int64_t)d * t.t + (1 << 15)) >> 16);
#else
    int32_t p = d * t.hi + (1 << 7);
    p += (d * t.lo) >> 8;
    return a + (p >> 8);
#endif
}

/* The corners c = (0, cy, cz) and c + (1, 0, 0) of a cell edge along x, sx0 and sx1 their x hash
 * terms, syz the other two XORed: their gradients' dot products with the offsets from them,
 * interpolated by u. */
static inline int32_t noise_edge(uint32_t sx0, uint32_t sx1, uint32_t syz, const int32_t dots[16],
                                 int c, noise_weight u)
{
    return noise_lerp(noise_dot(noise_mix_spread(sx0 ^ syz), dots, c),
                      noise_dot(noise_mix_spread(sx1 ^ syz), dots, c + 1), u);
}

/* Noise at the lattice coordinates (cx, cy, cz) (Q16.16 modulo the period), in Q16.16. dots is
 * the caller's room for 16 words: passed in, its address is a register, so each look-up is one
 * load (GCC for ARM builds a local array's indexed address in three instructions). */
static int32_t noise_eval(uint32_t cx, uint32_t cy, uint32_t cz, int32_t dots[16])
{
    const uint32_t mask = RT_NOISE_PERIOD - 1;
    uint32_t i = cx >> NOISE_FRAC, j = cy >> NOISE_FRAC, k = cz >> NOISE_FRAC;
    int32_t x = (int32_t)(cx & (NOISE_ONE - 1)), y = (int32_t)(cy & (NOISE_ONE - 1)),
            z = (int32_t)(cz & (NOISE_ONE - 1));
    /* the hash's per-axis terms, each already XORed with itself shifted (see noise_spread) */
    uint32_t sx0 = noise_spread((i & mask) * NOISE_HX),
             sx1 = noise_spread(((i + 1) & mask) * NOISE_HX);
    uint32_t sy0 = noise_spread((j & mask) * NOISE_HY),
             sy1 = noise_spread(((j + 1) & mask) * NOISE_HY);
    uint32_t sz0 = noise_spread((k & mask) * NOISE_HZ),
             sz1 = noise_spread(((k + 1) & mask) * NOISE_HZ);
    /* g . (x, y, z) for each gradient g, in the order of noise_corner's columns */
    int32_t pxy = x + y, mxy = x - y, pxz = x + z, mxz = x - z, pyz = y + z, myz = y - z;
    dots[0] = dots[12] = pxy, dots[1] = dots[14] = -mxy, dots[2] = mxy, dots[3] = -pxy;
    dots[4] = pxz, dots[5] = -mxz, dots[6] = mxz, dots[7] = -pxz;
    dots[8] = pyz, dots[9] = dots[13] = -myz, dots[10] = myz, dots[11] = dots[15] = -pyz;
    noise_weight u = noise_weight_of(noise_fade((uint32_t)x));
    noise_weight v = noise_weight_of(noise_fade((uint32_t)y));
    noise_weight w = noise_weight_of(noise_fade((uint32_t)z));

    int32_t a = noise_edge(sx0, sx1, sy0 ^ sz0, dots, 0, u);
    int32_t b = noise_edge(sx0, sx1, sy1 ^ sz0, dots, 2, u);
    int32_t ab = noise_lerp(a, b, v);
    int32_t c = noise_edge(sx0, sx1, sy0 ^ sz1, dots, 4, u);
    int32_t d = noise_edge(sx0, sx1, sy1 ^ sz1, dots, 6, u);
    return noise_lerp(ab, noise_lerp(c, d, v), w);
}

vec3 rt_noise_wrap(vec3 p)
{
    const real period = R(256.0);
    return v3(r_mod_pow2(p.x, period), r_mod_pow2(p.y, period), r_mod_pow2(p.z, period));
}

/* floor(w * 2^16) modulo 2^32 for |w| < 32768: w's Q16.16 integer, rounded down (exact in the
 * fixed build; in float each step, a floor and a product by 2^15, is exact too). For lattice
 * coordinates the caller masks it to the period: this is the wrap. */
static uint32_t noise_q16(real w)
{
    int32_t i, hi;
    real f = r_floor_split(w, &i);
    real g = r_floor_split(r_muli(f, 32768), &hi); /* f * 2^15 < 32768: no saturation */
    return ((uint32_t)i << NOISE_FRAC) + ((uint32_t)hi << 1) + (g >= R(0.5));
}

real rt_noise(vec3 p)
{
    int32_t dots[16];
    return r_from_q16(noise_eval(noise_q16(p.x) & NOISE_COORD_MASK,
                                 noise_q16(p.y) & NOISE_COORD_MASK,
                                 noise_q16(p.z) & NOISE_COORD_MASK, dots));
}

/* E|noise| over the lattice, Q16.16 (0.2203, measured over 2 million points). */
#define NOISE_ABS_MEAN 14434

/* Sum over the octaves of d of amp * f(noise), f the identity or the absolute value. Each
 * octave doubles the lattice coordinates modulo the period, in integers. */
static real noise_octaves(vec3 p, rt_noise_detail d, int absolute)
{
    /* the 24-bit lattice coordinates in the top bits of a word: doubling one modulo the period
     * is a shift that drops the bit going out */
    uint32_t cx = noise_q16(p.x) << 8, cy = noise_q16(p.y) << 8, cz = noise_q16(p.z) << 8;
    int32_t sum = 0, dots[16];
    for (int o = 0; o < d.octaves; o++) {
        int32_t n = noise_eval(cx >> 8, cy >> 8, cz >> 8, dots);
        if (absolute && n < 0)
            n = -n;
        if (o == d.octaves - 1 && d.last < RT_NOISE_WEIGHT_ONE) /* the fading octave */
            n = (n * d.last + (absolute ? NOISE_ABS_MEAN : 0) * (RT_NOISE_WEIGHT_ONE - d.last) +
                 RT_NOISE_WEIGHT_ONE / 2) >>
                8;
        sum += (n + ((1 << o) >> 1)) >> o; /* amplitude 2^-o, rounded half up */
        cx <<= 1, cy <<= 1, cz <<= 1;
    }
    if (absolute) /* the octaves left out, at their mean */
        for (int o = d.octaves; o < d.total; o++)
            sum += (NOISE_ABS_MEAN + ((1 << o) >> 1)) >> o;
    return r_from_q16(sum);
}

real rt_fbm_detail(vec3 p, rt_noise_detail d) { return noise_octaves(p, d, 0); }

real rt_turbulence_detail(vec3 p, rt_noise_detail d) { return noise_octaves(p, d, 1); }

real rt_fbm(vec3 p, int octaves)
{
    return noise_octaves(p, (rt_noise_detail){octaves, octaves, RT_NOISE_WEIGHT_ONE}, 0);
}

real rt_turbulence(vec3 p, int octaves)
{
    return noise_octaves(p, (rt_noise_detail){octaves, octaves, RT_NOISE_WEIGHT_ONE}, 1);
}

/* Octaves resolved below this footprint bias, in 1/256 octave: shifts the whole fade band. */
#define NOISE_DETAIL_BIAS 0

rt_noise_detail rt_noise_detail_for(real footprint, int octaves)
{
    rt_noise_detail d = {octaves, octaves, RT_NOISE_WEIGHT_ONE};
    if (footprint <= 0)
        return d;
    /* the footprint in Q16.16, at most 2^8 (no octave is resolved beyond 1) */
    uint32_t f = footprint >= R(256.0) ? (uint32_t)256 << NOISE_FRAC : noise_q16(footprint);
    if (f == 0)
        return d;
    /* log2(f) in 1/256 octave: the top bit's position plus the bits below it read linearly
     * (continuous and increasing, within 0.09 octave of the logarithm) */
    int top = 31 - __builtin_clz(f);
    int32_t log2f = top * 256 + (int32_t)(((f - ((uint32_t)1 << top)) << 8) >> top);
    /* octaves resolved: log2(1 / footprint) = NOISE_FRAC - log2(f) */
    int32_t resolved = NOISE_FRAC * 256 - log2f + NOISE_DETAIL_BIAS;
    if (resolved >= octaves * 256)
        return d;
    if (resolved <= 0)
        return (rt_noise_detail){0, octaves, RT_NOISE_WEIGHT_ONE};
    d.octaves = (resolved + 255) >> 8;
    d.last = resolved - (d.octaves - 1) * 256;
    return d;
}

/* Each palette: five colour stops evenly spread over [0, 1]. */
#define NOISE_STOPS 5
#define C(r, g, b) \
    { \
        R(r), R(g), R(b) \
    }
static const vec3 noise_palettes[RT_PAL_COUNT][NOISE_STOPS] = {
    [RT_PAL_MARBLE] = {C(0.92, 0.91, 0.88), C(0.85, 0.84, 0.82), C(0.62, 0.64, 0.70),
                       C(0.30, 0.33, 0.42), C(0.10, 0.11, 0.16)},
    [RT_PAL_WOOD] = {C(0.80, 0.56, 0.30), C(0.72, 0.47, 0.24), C(0.58, 0.35, 0.16),
                     C(0.45, 0.26, 0.11), C(0.78, 0.54, 0.28)},
    [RT_PAL_LAVA] = {C(0.10, 0.02, 0.02), C(0.55, 0.06, 0.02), C(0.95, 0.35, 0.05),
                     C(1.00, 0.75, 0.20), C(1.00, 0.95, 0.70)},
    [RT_PAL_SKY] = {C(0.16, 0.30, 0.60), C(0.30, 0.46, 0.75), C(0.55, 0.68, 0.88),
                    C(0.85, 0.90, 0.97), C(1.00, 1.00, 1.00)},
};
#undef C

vec3 rt_palette(int id, real t)
{
    const vec3 *pal = noise_palettes[id];
    t = r_clamp(t, 0, R_ONE);
    /* position among the stops: t * (stops - 1) = integer segment + fraction */
    int32_t seg;
    real f = r_floor_split(r_muli(t, NOISE_STOPS - 1), &seg);
    if (seg >= NOISE_STOPS - 1)
        return pal[NOISE_STOPS - 1];
    /* a + (b - a) f: a and f in [0, 1], b - a in [-1, 1]; in range, so formed without range
     * checks */
    vec3 a = pal[seg];
    return c3_madd(a, v3_sub(pal[seg + 1], a), f);
}
