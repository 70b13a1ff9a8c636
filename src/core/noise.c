/* noise.c: 3D Perlin gradient noise, fBm and turbulence, and the colour palettes of the textures. */
#include "noise.h"

#include "rt.h"

/* Twelve gradients along the cube's edges, four repeated to make sixteen (one per 4-bit hash):
 * each is (gx, gy, gz) with components in {-1, 0, 1}. */
static const int8_t noise_grad[16][3] = {
    {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
    {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}, {1, 1, 0}, {0, -1, 1}, {-1, 1, 0}, {0, -1, -1},
};

/* Lattice coordinates are Q16.16 integers modulo the period: 24 bits. */
#define NOISE_FRAC 16
#define NOISE_ONE (1 << NOISE_FRAC)
#define NOISE_COORD_MASK ((uint32_t)RT_NOISE_PERIOD * NOISE_ONE - 1)

/* The hash is a product per axis, the three XORed, then mixed: the per-axis products of a
 * cell's two corners along each axis are shared by its eight corners. */
#define NOISE_HX 0x8DA6B343u
#define NOISE_HY 0xD8163841u
#define NOISE_HZ 0xCB1AB31Fu

static inline uint32_t noise_mix(uint32_t h)
{
    h ^= h >> 15;
    h *= 0x2C1B3C6Du;
    h ^= h >> 12;
    return h;
}

uint32_t rt_noise_hash(int32_t i, int32_t j, int32_t k)
{
    const uint32_t mask = RT_NOISE_PERIOD - 1;
    return noise_mix(((uint32_t)i & mask) * NOISE_HX ^ ((uint32_t)j & mask) * NOISE_HY ^
                     ((uint32_t)k & mask) * NOISE_HZ);
}

/* Dot product of the gradient of hash h with the offset (x, y, z) from that corner (Q16.16
 * offsets in [-1, 1]: the result is within +-2). */
static inline int32_t noise_dot(uint32_t h, int32_t x, int32_t y, int32_t z)
{
    const int8_t *g = noise_grad[(h >> 8) & 15];
    return g[0] * x + g[1] * y + g[2] * z;
}

/* Quintic fade 6t^5 - 15t^4 + 10t^3 of t in [0, 1) (Q16.16): zero first and second
 * derivatives at 0 and 1. t^3 is kept in Q.32 and the factor 10 - t (15 - 6t) in Q16.16, each
 * rounded once: within 2 LSB of the exact value. */
static inline int32_t noise_fade(uint32_t t)
{
    uint32_t t3 = (uint32_t)(((uint64_t)(t * t) * t + (NOISE_ONE >> 1)) >> NOISE_FRAC);
    uint32_t inner = 10 * NOISE_ONE -
        (uint32_t)(((uint64_t)t * (15 * NOISE_ONE - 6 * t) + (NOISE_ONE >> 1)) >> NOISE_FRAC);
    return (int32_t)(((uint64_t)t3 * inner + 0x80000000u) >> 32);
}

/* a + (b - a) t, t in [0, 1] (Q16.16), rounded half up. */
static inline int32_t noise_lerp(int32_t a, int32_t b, int32_t t)
{
    return a + (int32_t)(((int64_t)(b - a) * t + (NOISE_ONE >> 1)) >> NOISE_FRAC);
}

/* Noise at the lattice coordinates (cx, cy, cz) (Q16.16 modulo the period), in Q16.16. */
static int32_t noise_eval(uint32_t cx, uint32_t cy, uint32_t cz)
{
    const uint32_t mask = RT_NOISE_PERIOD - 1;
    uint32_t i = cx >> NOISE_FRAC, j = cy >> NOISE_FRAC, k = cz >> NOISE_FRAC;
    int32_t x = (int32_t)(cx & (NOISE_ONE - 1)), y = (int32_t)(cy & (NOISE_ONE - 1)),
            z = (int32_t)(cz & (NOISE_ONE - 1));
    int32_t x1 = x - NOISE_ONE, y1 = y - NOISE_ONE, z1 = z - NOISE_ONE;
    uint32_t hx0 = (i & mask) * NOISE_HX, hx1 = ((i + 1) & mask) * NOISE_HX;
    uint32_t hy0 = (j & mask) * NOISE_HY, hy1 = ((j + 1) & mask) * NOISE_HY;
    uint32_t hz0 = (k & mask) * NOISE_HZ, hz1 = ((k + 1) & mask) * NOISE_HZ;
    int32_t u = noise_fade((uint32_t)x), v = noise_fade((uint32_t)y), w = noise_fade((uint32_t)z);

    uint32_t h00 = hy0 ^ hz0, h10 = hy1 ^ hz0, h01 = hy0 ^ hz1, h11 = hy1 ^ hz1;
    int32_t a = noise_lerp(noise_dot(noise_mix(hx0 ^ h00), x, y, z),
                           noise_dot(noise_mix(hx1 ^ h00), x1, y, z), u);
    int32_t b = noise_lerp(noise_dot(noise_mix(hx0 ^ h10), x, y1, z),
                           noise_dot(noise_mix(hx1 ^ h10), x1, y1, z), u);
    int32_t c = noise_lerp(noise_dot(noise_mix(hx0 ^ h01), x, y, z1),
                           noise_dot(noise_mix(hx1 ^ h01), x1, y, z1), u);
    int32_t d = noise_lerp(noise_dot(noise_mix(hx0 ^ h11), x, y1, z1),
                           noise_dot(noise_mix(hx1 ^ h11), x1, y1, z1), u);
    return noise_lerp(noise_lerp(a, b, v), noise_lerp(c, d, v), w);
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
    return r_from_q16(noise_eval(noise_q16(p.x) & NOISE_COORD_MASK,
                                 noise_q16(p.y) & NOISE_COORD_MASK,
                                 noise_q16(p.z) & NOISE_COORD_MASK));
}

/* E|noise| over the lattice, Q16.16 (0.2203, measured over 2 million points). */
#define NOISE_ABS_MEAN 14434

/* Sum over the octaves of d of amp * f(noise), f the identity or the absolute value. Each
 * octave doubles the lattice coordinates modulo the period, in integers. */
static real noise_octaves(vec3 p, rt_noise_detail d, int absolute)
{
    uint32_t cx = noise_q16(p.x) & NOISE_COORD_MASK, cy = noise_q16(p.y) & NOISE_COORD_MASK,
             cz = noise_q16(p.z) & NOISE_COORD_MASK;
    int32_t sum = 0;
    for (int o = 0; o < d.octaves; o++) {
        int32_t n = noise_eval(cx, cy, cz);
        if (absolute && n < 0)
            n = -n;
        if (o == d.octaves - 1 && d.last < RT_NOISE_WEIGHT_ONE) /* the fading octave */
            n = (n * d.last + (absolute ? NOISE_ABS_MEAN : 0) * (RT_NOISE_WEIGHT_ONE - d.last) +
                 RT_NOISE_WEIGHT_ONE / 2) >>
                8;
        sum += (n + ((1 << o) >> 1)) >> o; /* amplitude 2^-o, rounded half up */
        cx = (cx << 1) & NOISE_COORD_MASK;
        cy = (cy << 1) & NOISE_COORD_MASK;
        cz = (cz << 1) & NOISE_COORD_MASK;
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
    vec3 a = pal[seg], b = pal[seg + 1];
    return v3(r_lerp(a.x, b.x, f), r_lerp(a.y, b.y, f), r_lerp(a.z, b.z, f));
}
