/* probe.c: probe mode: a point that splitting a square adds is probed (nearest hits, light states, no shading) and shaded in full only where its neighbours cannot give its colour. */
#include "rt.h"

/* Do the samples k[i] with bit i set in `set` (all of one record) have contributions within
 * thr8 of each other at every stored node? */
static int probe_agree(int n, const rt_sample *const k[], unsigned set, int thr8)
{
    const rt_sample *g[4];
    int m = 0;
    for (int i = 0; i < n; i++)
        if (set & (1u << i))
            g[m++] = k[i];
    if (m == 2) { /* the common case: one difference per channel */
        const rt_sample *a = g[0], *b = g[1];
        int nodes = a->nhits < RT_SAMPLE_MAX_HITS ? a->nhits : RT_SAMPLE_MAX_HITS;
        for (int j = 0; j < nodes; j++)
            for (int ch = 0; ch < 3; ch++) {
                int d = a->hits[j].contrib[ch] - b->hits[j].contrib[ch];
                if (d > thr8 || d < -thr8)
                    return 0;
            }
        return 1;
    }
    int nodes = g[0]->nhits < RT_SAMPLE_MAX_HITS ? g[0]->nhits : RT_SAMPLE_MAX_HITS;
    for (int j = 0; j < nodes; j++)
        for (int ch = 0; ch < 3; ch++) {
            int lo = g[0]->hits[j].contrib[ch], hi = lo;
            for (int i = 1; i < m; i++) {
                int v = g[i]->hits[j].contrib[ch];
                lo = v < lo ? v : lo;
                hi = v > hi ? v : hi;
            }
            if (hi - lo > thr8)
                return 0;
        }
    return 1;
}

/* r_lerp out of line: the colour mixing below calls it rather than repeating it (code size). */
static __attribute__((noinline)) real probe_lerp(real a, real b, real t) { return r_lerp(a, b, t); }

/* The colour at fraction t from a to b, from those of them in `m` alone (bit 0: a, bit 1: b). */
static __attribute__((noinline)) rt_color probe_mix(rt_color a, rt_color b, unsigned m, real t)
{
    if (m == 1)
        return a;
    if (m == 2)
        return b;
    return v3(probe_lerp(a.x, b.x, t), probe_lerp(a.y, b.y, t), probe_lerp(a.z, b.z, t));
}

/* Do a and b have the same ray tree below the primary hit (count, objects and levels)? */
static int probe_same_tree(const rt_sample *a, const rt_sample *b)
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

/* Is the primary hit of r on a noise texture (which varies between any two points)? */
static int probe_noise(const rt_scene *s, const rt_sample *r)
{
    int id = r->hits[0].object;
    return id != RT_NO_OBJECT && rt_scene_has(s, RT_FX_NOISE) &&
        s->materials[s->objects[id].material].tex.kind > RT_TEX_CHECKER;
}

/* Bits of rt_sample.lights set where a light's state is 2 (highlight). */
#define PROBE_HIGHLIGHTS 0xAAu

unsigned rt_probe_opaque(const rt_scene *s, const rt_sample *r)
{
    /* A noise texture at the primary hit, nodes beyond those stored, a highlight (its peak
     * lies anywhere between samples), or a texture at a secondary hit (a checkerboard through
     * glass or in a mirror): the colour depends on what no record holds. */
    if (probe_noise(s, r) || r->nhits > RT_SAMPLE_MAX_HITS || (r->lights & PROBE_HIGHLIGHTS))
        return RT_SAMPLE_OPAQUE;
    for (int j = 1; j < r->nhits; j++) {
        int o = r->hits[j].object;
        if (o != RT_NO_OBJECT && s->materials[s->objects[o].material].tex.kind != RT_TEX_NONE)
            return RT_SAMPLE_OPAQUE;
    }
    return 0;
}

/* Bit i set for each context sample k[i] of the set `in` whose record is r's (their primary
 * object and cell are r's already). */
static unsigned probe_matches(int n, const rt_sample *const k[], unsigned in, const rt_sample *r)
{
    unsigned m = 0;
    for (int i = 0; i < n; i++)
        if ((in & (1u << i)) && k[i]->lights == r->lights && probe_same_tree(r, k[i]))
            m |= 1u << i;
    return m;
}

/* The lowest bit set in a non-empty set. */
static int probe_first(unsigned set)
{
    int i = 0;
    while (!(set & (1u << i)))
        i++;
    return i;
}

int rt_probe_point(const rt_scene *s, const rt_view *v, const rt_params *p, rt_stats *st, int thr8,
                   int x, int y, int n, const rt_sample *const k[], enum rt_split_reason why,
                   real tx, real ty, int span, rt_primary *pri, rt_sample *out)
{
    pri->id = RT_PRIMARY_UNKNOWN;
    /* 0. No probe where its answer cannot matter: a point whose record is a context sample's
     * gets that sample's verdict, one with a new record is shaded. So when every context sample
     * is opaque (rt_probe_opaque), or all have one record whose contributions disagree, shade.
     * The four corners of a square have that when it was split for its contributions alone. */
    unsigned opaque = k[0]->flags & k[1]->flags;
    if (n == 4)
        opaque &= k[2]->flags & k[3]->flags;
    if ((opaque & RT_SAMPLE_OPAQUE) ||
        (n == 4 ? why == RT_SPLIT_CONTRIB
                : rt_probe_same(k[0], k[1]) && !probe_agree(2, k, 3u, thr8)))
        return 0;
    /* Nor on an edge longer than RT_PROBE_ONE_SPAN whose ends differ in primary object, cell or
     * light states: the point's record could then be one end's at most, and one is not enough
     * there. */
    if (n == 2 && span > RT_PROBE_ONE_SPAN &&
        (k[0]->hits[0].object != k[1]->hits[0].object || k[0]->cell != k[1]->cell ||
         k[0]->lights != k[1]->lights))
        return 0;

    /* 1. The primary hit and its checker cell (into out, scratch until the end); a noise
     * texture there ends the probe. Its primary ray is kept in *pri for what follows. */
    st->probes++;
    rt_probe_pixel(s, v, p, x, y, 0, pri, st, out);
    if (probe_noise(s, out))
        return 0;
    int id = out->hits[0].object;
    uint8_t cell = out->cell;
    unsigned m = 0;
    for (int i = n - 1; i >= 0; i--)
        m = m << 1 | (k[i]->hits[0].object == id && k[i]->cell == cell ? 1u : 0);
    if (!m)
        return 0; /* something new */

    /* 2. The light states where the context disagrees on a light (a shadow or highlight edge
     * crosses it), the ray tree where the surface casts secondary rays (what they meet can
     * change anywhere) unless the context is an edge whose ends have one record; elsewhere the
     * matching sample's record is the point's. */
    const rt_sample *f = k[probe_first(m)];
    int lights = 0;
    for (int i = 0; i < n; i++)
        lights |= k[i]->lights != f->lights;
    int deep = lights || (f->nhits > 1 && !(n == 2 && m == 3u && probe_same_tree(k[0], k[1])));
    if (deep) {
        /* Its rays beyond the primary one are the probe's: moved to probe_shadow and
         * probe_secondary (their object tests stay in shadow_tests). */
        uint32_t sh = st->rays_shadow, rl = st->rays_reflect, rr = st->rays_refract;
        rt_probe_pixel(s, v, p, x, y, lights ? RT_PROBE_WHOLE : RT_PROBE_TREE, pri, st, out);
        if (!lights)
            out->lights = f->lights;
        st->probe_shadow += st->rays_shadow - sh;
        st->probe_secondary += (st->rays_reflect - rl) + (st->rays_refract - rr);
        st->rays_shadow = sh;
        st->rays_reflect = rl;
        st->rays_refract = rr;
        out->cell = cell;
        m = probe_matches(n, k, m, out);
        if (!m)
            return 0;
        f = k[probe_first(m)];
    } else {
        *out = *f;
    }

    /* 3. Interpolation stands in where two samples or more have the point's record, or one
     * next to it (at most RT_PROBE_ONE_SPAN pixels across the context); where the colour
     * depends on nothing the record misses (f is not opaque: f's record is the point's, and f
     * is on no noise texture, having its primary object); and where those samples'
     * contributions agree. */
    int single = !(m & (m - 1));
    if ((single && span > RT_PROBE_ONE_SPAN) || (f->flags & RT_SAMPLE_OPAQUE) ||
        (!single && !probe_agree(n, k, m, thr8)))
        return 0;

    /* The colour: along x within each row of the context, then between the rows. */
    unsigned top = m & 3, bot = m >> 2 & 3;
    rt_color col = probe_mix(k[0]->color, k[1]->color, top, tx);
    if (n == 4)
        col = probe_mix(col, probe_mix(k[2]->color, k[3]->color, bot, tx),
                        (top ? 1u : 0) | (bot ? 2u : 0), ty);
    if (deep) {
        int nodes = out->nhits < RT_SAMPLE_MAX_HITS ? out->nhits : RT_SAMPLE_MAX_HITS;
        for (int j = 0; j < nodes; j++)
            for (int ch = 0; ch < 3; ch++)
                out->hits[j].contrib[ch] = f->hits[j].contrib[ch];
    }
    out->color = col;
    out->flags = RT_SAMPLE_PROBED;
    out->alt_known = 0; /* its other tone is not known: no corner of a texture square */
    return 1;
}
