/* texture.c: procedural textures: the diffuse colour of a material at a point in space. */
#include "noise.h"
#include "rt_local.h"

rt_color rt_texture_color(const rt_material *m, vec3 p, int max_octaves, real footprint,
                          rt_stats *st, uint8_t *cell)
{
    const rt_texture *tx = &m->tex;
    *cell = 0;
    if (!tx->active)
        return m->diffuse; /* no texture, or a checker of one colour (rt_scene_prepare) */

    /* q = p * scale has |q| <= 20000 for noise textures and 32000 for the checker (the parser
     * bounds the texture scale by the farthest point the material can be seen at): the products
     * need no range check (docs/numerics.md) */
    if (tx->kind == RT_TEX_CHECKER) {
        /* Cells are centred on lattice points, so the faces of cells lie at half-integers and
         * a plane through the origin never sits on a boundary: the cell is floor(q + 1/2). */
        int32_t i = r_mul_round_in(p.x, tx->scale), j = r_mul_round_in(p.y, tx->scale),
                k = r_mul_round_in(p.z, tx->scale);
        /* Which cell, up to three cells away: two corners on cells of the same colour but
         * different cells have a cell of the other colour between them. */
        *cell = (uint8_t)(1 + ((i & 3) | (j & 3) << 2 | (k & 3) << 4));
        return ((i + j + k) & 1) ? tx->color2 : m->diffuse;
    }
    vec3 q = v3(r_mul_in(p.x, tx->scale), r_mul_in(p.y, tx->scale), r_mul_in(p.z, tx->scale));
    if ((RT_COMPILED_EFFECTS & RT_FX_NOISE) == 0)
        return m->diffuse; /* a compiled-in scene without noise textures links no noise code */
    int octaves = max_octaves > 0 && max_octaves < tx->octaves ? max_octaves : tx->octaves;
    /* the octaves a pixel resolves: its footprint in noise units (a footprint of 256 or more
     * resolves none at the smallest scale, 1/256: no product that could saturate) */
    real fp = footprint < R(256.0) ? r_mul(footprint, tx->scale) : R(256.0);
    rt_noise_detail detail = rt_noise_detail_for(fp, octaves);
    st->noise_octaves += (uint32_t)detail.octaves;
    switch (tx->kind) {
    case RT_TEX_MARBLE: {
        /* Veins: a sine across x and y whose phase is pushed around by turbulence. The sine
         * repeats every 2 in x and 4 in y, so the point can be wrapped into the noise period
         * first: the phase then stays small wherever the point lies. */
        vec3 w = rt_noise_wrap(q);
        real phase = r_add(r_add(w.x, r_shr(w.y, 1)),
                           r_mul(tx->turbulence, rt_turbulence_detail(q, detail)));
        real s = r_sin(r_mul(phase, R_PI));
        return rt_palette(tx->palette, r_add(R(0.5), r_shr(s, 1)));
    }
    case RT_TEX_WOOD: {
        /* Rings around the y axis, made irregular by noise. */
        real ring = r_add(r_hypot(q.x, q.z), r_mul(tx->turbulence, rt_fbm_detail(q, detail)));
        return rt_palette(tx->palette, r_mod_pow2(ring, R_ONE));
    }
    case RT_TEX_NOISE:
    default: {
        real n = rt_fbm_detail(q, detail);
        return rt_palette(tx->palette, r_add(R(0.5), r_shr(n, 1)));
    }
    }
}
