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

/* Does a light that sample f has unlit (state 0) light the primary hit *pri (on object pri->id,
 * seen from the prepared eye) after all? The test trace_light makes for it (facing, n . l, one
 * shadow ray), without the shading: a lit wedge between shadows that the context's samples do
 * not see. */
static int probe_lit(const rt_scene *s, const rt_view *v, rt_stats *st, const rt_primary *pri,
                     const rt_sample *f)
{
    if (pri->id < 0)
        return 0; /* the background: no surface, no light */
    const rt_object *o = &s->objects[pri->id];
    const vec3 p = v3_along_in(v->eye, pri->d, pri->t);
    dir3 n = rt_shapes[o->kind].normal(o, p);
    int inside = 0;
    if (d3_dot(pri->d, n) > 0) {
        n = d3_neg(n);
        inside = 1;
    }
    const vec3 p_out = v3_along_in(p, n, R_EPS_OFFSET);
    for (int i = 0; i < s->nlights; i++) {
        dir3 l;
        if (!rt_light_state(f, i) && rt_light_reach(s, st, i, pri->id, inside, &p, &p_out, n, &l))
            return 1;
    }
    return 0;
}

int rt_probe_point(const rt_scene *s, const rt_view *v, rt_stats *st, int thr8, int x, int y,
                   const rt_sample *a, const rt_sample *b, real t, int span, rt_primary *pri,
                   rt_sample *out)
{
    pri->id = RT_PRIMARY_UNKNOWN;
    /* 0. No probe where it cannot pay. Where the ends have one record whose contributions
     * disagree, a point with their record gets their verdict and one with a new record is
     * shaded. Where both ends cast secondary rays (and differ in them), the point's ray tree
     * would take those rays again: its full shade but for the colour (a tree probe measured
     * dearer than the shades it saved, docs/probe.md). On an edge longer than
     * RT_PROBE_ONE_SPAN whose ends differ in primary object or cell, the point's record could
     * be one end's at most, not enough there. (The caller has left out the edges whose ends
     * are both opaque or disagree on a light: ss_probe_edge.) */
    const int agreed = rt_probe_same(a, b); /* a point matching both needs no more test */
    if (agreed ? !probe_agree(a, b, thr8)
               : (a->nhits != 1 && b->nhits != 1) ||
                (span > RT_PROBE_ONE_SPAN &&
                 (a->hits[0].object != b->hits[0].object || a->cell != b->cell)))
        return -1;

    /* 1. The primary hit and its checker cell; a noise texture there ends the probe. The
     * primary ray and hit stay in *pri for the full shade. */
    st->probes++;
    uint8_t cell;
    int id = probe_primary(s, v, x, y, st, pri, &cell);
    if (probe_noise(s, id))
        return 0;
    const unsigned m = (a->hits[0].object == id && a->cell == cell ? 1u : 0) |
        (b->hits[0].object == id && b->cell == cell ? 2u : 0);
    if (!m)
        return 0; /* something new */

    /* 2. The ends agree on every light: the matching end's light states are the point's, once
     * a light it has unlit is found unlit at the point too (probe_lit, below: else a lit wedge
     * between shadows lies there, and the point is shaded).
     * Its ray tree is the matching end's where that casts no secondary ray, or where the two
     * ends have one record; elsewhere it would take a probe of its own: shaded. */
    const rt_sample *f = m & 1 ? a : b;
    if (f->nhits > 1 && !agreed)
        return 0;

    /* 3. Interpolation stands in where both ends have the point's record, or one next to it
     * (an edge of at most RT_PROBE_ONE_SPAN pixels); where the colour depends on nothing the
     * record misses (f is not opaque: f's record is the point's, and f is on no noise texture,
     * having its primary object); and where the ends' contributions agree. A light f has unlit
     * is tested at the point (probe_lit), but on an edge of 2 pixels whose ends both match: the
     * point's neighbours a pixel away on either side, on its object and cell and unlit, are
     * what the test would look between. (Where one end is another object, a shadow's edge can
     * meet the outline between them: tested.) */
    if ((m != 3u && span > RT_PROBE_ONE_SPAN) || (f->flags & RT_SAMPLE_OPAQUE) ||
        (m == 3u && !agreed && !probe_agree(a, b, thr8)) ||
        ((m != 3u || span > 2) && probe_lit(s, v, st, pri, f)))
        return 0;

    /* The record is f's, the colour interpolated from the matching ends'. f's other tone's
     * colour of a two-tone checker (rt_sample.alt), where it has one, stands for the point's:
     * the point can then be a corner of a texture square (ss_cells) as f can. */
    *out = *f;
    if (m == 3u)
        out->color = probe_lerp(&a->color, &b->color, t);
    out->flags = RT_SAMPLE_PROBED;
    return 1;
}
