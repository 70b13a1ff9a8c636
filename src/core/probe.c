/* probe.c: probe mode: a point that splitting a square adds is probed (its primary hit and checker cell, no shading) and shaded in full only where its neighbours cannot give its colour. */
#include "rt_local.h"

/* Do samples a and b (of one record) have contributions within thr8 of each other at every
 * stored node? */
static int probe_agree(const rt_sample *a, const rt_sample *b, int thr8)
{
    int nodes = a->nhits < RT_SAMPLE_MAX_HITS ? a->nhits : RT_SAMPLE_MAX_HITS;
    for (int j = 0; j < nodes; j++)
        for (int ch = 0; ch < 3; ch++) {
            int d = a->hits[j].contrib[ch] - b->hits[j].contrib[ch];
            if (d > thr8 || d < -thr8)
                return 0;
        }
    return 1;
}

/* The colour at fraction t from *a to *b: r_lerp of each channel, in its in-range form (the
 * same values: colours and t lie in [0, 1]). */
static rt_color probe_lerp(const rt_color *a, const rt_color *b, real t)
{
    return v3(r_add_in(a->x, r_mul_in(r_add_in(b->x, r_neg_in(a->x)), t)),
              r_add_in(a->y, r_mul_in(r_add_in(b->y, r_neg_in(a->y)), t)),
              r_add_in(a->z, r_mul_in(r_add_in(b->z, r_neg_in(a->z)), t)));
}

/* Do a and b have the same ray tree below the primary hit (count, objects and levels)? */
static inline __attribute__((always_inline)) int probe_same_tree(const rt_sample *a,
                                                                 const rt_sample *b)
{
    if (a->nhits != b->nhits)
        return 0;
    int n = a->nhits < RT_SAMPLE_MAX_HITS ? a->nhits : RT_SAMPLE_MAX_HITS;
    for (int j = 1; j < n; j++)
        if (a->hits[j].object != b->hits[j].object || a->hits[j].level != b->hits[j].level)
            return 0;
    return 1;
}

int rt_probe_same(const rt_sample *a, const rt_sample *b)
{
    return a->hits[0].object == b->hits[0].object && a->cell == b->cell && a->lights == b->lights &&
        probe_same_tree(a, b);
}

/* Is a primary hit on object id (RT_NO_OBJECT: none) on a noise texture (which varies between
 * any two points)? */
static int probe_noise(const rt_scene *s, int id)
{
    return id != RT_NO_OBJECT && rt_scene_has(s, RT_FX_NOISE) &&
        s->materials[s->objects[id].material].tex.kind > RT_TEX_CHECKER;
}

FX_BOARD_THUMB rt_probe_masks rt_probe_masks_of(const rt_scene *s)
{
    rt_probe_masks mk = {0, 0};
    for (int i = 0; i < s->nobjects; i++) {
        const rt_texture *tx = &s->materials[s->objects[i].material].tex;
        if (probe_noise(s, i))
            mk.primary |= (uint32_t)1 << i;
        if (tx->kind != RT_TEX_NONE)
            mk.beyond |= (uint32_t)1 << i;
    }
    return mk;
}

/* Is object `id` (RT_NO_OBJECT: none) in the set? */
static int probe_in(uint32_t set, unsigned id) { return id < RT_MAX_OBJECTS && (set >> id & 1); }

unsigned rt_probe_opaque(const rt_probe_masks *mk, const rt_sample *r)
{
    /* A noise texture at the primary hit, nodes beyond those stored, a highlight (its peak
     * lies anywhere between samples), or a texture at a secondary hit (a checkerboard through
     * glass or in a mirror): the colour depends on what no record holds. */
    if (probe_in(mk->primary, r->hits[0].object) || r->nhits > RT_SAMPLE_MAX_HITS ||
        (r->lights & RT_LIGHTS_HIGHLIGHT))
        return RT_SAMPLE_OPAQUE;
    for (int j = 1; j < r->nhits; j++)
        if (probe_in(mk->beyond, r->hits[j].object))
            return RT_SAMPLE_OPAQUE;
    return 0;
}

/* The primary hit of pixel (x, y) as its full shade finds it (the same ray and nearest-hit test
 * as trace_first) into *pri, and the checker cell there into *cell (0: none). Returns the object
 * as a record holds it (RT_NO_OBJECT: none). */
static int probe_primary(const rt_scene *s, const rt_view *v, int x, int y, rt_stats *st,
                         rt_primary *pri, uint8_t *cell)
{
    const dir3 d = pri->d = rt_view_ray(v, x, y);
    const vec3 eye = v->eye;
    pri->t = 0;
    int id = rt_scene_at_eye(s, eye)
        ? rt_nearest_primary(s, d, rt_view_candidates(v, x, y), &pri->t)
        : rt_nearest_but(s, eye, d, R_T_MAX, -1, &pri->t);
    pri->id = id;
    *cell = 0;
    if (id < 0)
        return RT_NO_OBJECT;
    const rt_material *m = &s->materials[s->objects[id].material];
    if (rt_scene_has(s, RT_FX_TEXTURE) && m->tex.active && m->tex.kind == RT_TEX_CHECKER)
        rt_texture_color(m, v3_along_in(eye, d, pri->t), 0, 0, st, cell);
    return id;
}

int rt_probe_point(const rt_scene *s, const rt_view *v, rt_stats *st, int thr8, int x, int y,
                   const rt_sample *a, const rt_sample *b, real t, int span, rt_primary *pri,
                   rt_sample *out)
{
    pri->id = RT_PRIMARY_UNKNOWN;
    /* Only the middle of an edge of 2 pixels whose ends have one record (primary object,
     * cell and light states), with no secondary ray and no highlight or noise texture (not
     * opaque), and contributions within the threshold. Anything more and the point's colour
     * can hold what neither end shows: the limb of a sphere darkening towards its outline next
     * to an end on the background, a shadow's edge reaching an outline between an end on the
     * floor and one on a sphere, a reflection's or a refraction's own edges and shadows between
     * two ends that see the same objects, the curve of a sphere's shading over 4 or 8 pixels.
     * Adaptive mode traces such a point; so does this mode (-1: shaded where the squares
     * below need it). */
    if (span > 2 || a->nhits != 1 || (a->flags & RT_SAMPLE_OPAQUE) || !rt_probe_same(a, b) ||
        !probe_agree(a, b, thr8))
        return -1;

    /* The primary hit and its checker cell: the ends' object and cell, or shaded in full from
     * the primary hit the probe found (kept in *pri). */
    st->probes++;
    uint8_t cell;
    if (probe_primary(s, v, x, y, st, pri, &cell) != a->hits[0].object || cell != a->cell)
        return 0;

    /* The ends' record, the colour interpolated between them. a's other tone's colour of a
     * two-tone checker (rt_sample.alt), where it has one, stands for the point's: the point
     * can then be a corner of a texture square (ss_cells) as a can. */
    *out = *a;
    out->color = probe_lerp(&a->color, &b->color, t);
    out->flags = RT_SAMPLE_PROBED;
    return 1;
}
