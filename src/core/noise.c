/* noise.c: 3D Perlin gradient noise, fBm and turbulence, and the colour palettes of the textures. */
#include "noise.h"

#include "rt.h"

/* Twelve gradients along the cube's edges, four repeated to make sixteen (one per 4-bit hash):
 * each is (gx, gy, gz) with components in {-1, 0, 1}. */
static const int8_t noise_grad[16][3] = {
    {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
    {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}, {1, 1, 0}, {0, -1, 1}, {-1, 1, 0}, {0, -1, -1},
};

uint32_t rt_noise_hash(int32_t i, int32_t j, int32_t k)
{
    const uint32_t mask = RT_NOISE_PERIOD - 1;
    uint32_t h = ((uint32_t)i & mask) * 0x8DA6B343u;
    h ^= ((uint32_t)j & mask) * 0xD8163841u;
    h ^= ((uint32_t)k & mask) * 0xCB1AB31Fu;
    h ^= h >> 15;
    h *= 0x2C1B3C6Du;
    h ^= h >> 12;
    return h;
}

static real noise_term(real v, int g) { return r_mul_sign(v, g); }

/* Dot product of the corner's gradient with the offset (x, y, z) from that corner. */
static inline __attribute__((always_inline)) real noise_dot(uint32_t h, real x, real y, real z)
{
    const int8_t *g = noise_grad[(h >> 8) & 15];
    return r_add(r_add(noise_term(x, g[0]), noise_term(y, g[1])), noise_term(z, g[2]));
}

/* Quintic fade 6t^5 - 15t^4 + 10t^3: zero first and second derivatives at 0 and 1. */
static real noise_fade(real t)
{
    real f = r_add(r_mul(t, r_sub(r_muli(t, 6), R(15.0))), R(10.0));
    return r_mul(r_mul(r_mul(t, t), t), f);
}

real rt_noise(vec3 p)
{
    int32_t i, j, k;
    real x = r_floor_split(p.x, &i);
    real y = r_floor_split(p.y, &j);
    real z = r_floor_split(p.z, &k);
    real x1 = r_sub(x, R_ONE), y1 = r_sub(y, R_ONE), z1 = r_sub(z, R_ONE);
    real u = noise_fade(x), v = noise_fade(y), w = noise_fade(z);

    real a = r_lerp(noise_dot(rt_noise_hash(i, j, k), x, y, z),
                    noise_dot(rt_noise_hash(i + 1, j, k), x1, y, z), u);
    real b = r_lerp(noise_dot(rt_noise_hash(i, j + 1, k), x, y1, z),
                    noise_dot(rt_noise_hash(i + 1, j + 1, k), x1, y1, z), u);
    real c = r_lerp(noise_dot(rt_noise_hash(i, j, k + 1), x, y, z1),
                    noise_dot(rt_noise_hash(i + 1, j, k + 1), x1, y, z1), u);
    real d = r_lerp(noise_dot(rt_noise_hash(i, j + 1, k + 1), x, y1, z1),
                    noise_dot(rt_noise_hash(i + 1, j + 1, k + 1), x1, y1, z1), u);
    return r_lerp(r_lerp(a, b, v), r_lerp(c, d, v), w);
}

vec3 rt_noise_wrap(vec3 p)
{
    const real period = R(256.0);
    return v3(r_mod_pow2(p.x, period), r_mod_pow2(p.y, period), r_mod_pow2(p.z, period));
}

/* Sum over octaves of amp * f(noise), f the identity or the absolute value. */
static real noise_octaves(vec3 p, int octaves, int absolute)
{
    real sum = 0, amp = R_ONE;
    p = rt_noise_wrap(p);
    for (int o = 0; o < octaves; o++) {
        real n = rt_noise(p);
        sum = r_add(sum, r_mul(absolute ? r_abs(n) : n, amp));
        amp = r_shr(amp, 1);
        /* the next octave: twice the wrapped point, wrapped again (rt_noise_wrap's bits) */
        const real period = R(256.0);
        p = v3(r_mod_pow2_twice(p.x, period), r_mod_pow2_twice(p.y, period),
               r_mod_pow2_twice(p.z, period));
    }
    return sum;
}

real rt_fbm(vec3 p, int octaves) { return noise_octaves(p, octaves, 0); }

real rt_turbulence(vec3 p, int octaves) { return noise_octaves(p, octaves, 1); }

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
