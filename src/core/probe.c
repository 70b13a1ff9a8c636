/* probe.c: probe mode: a point that splitting a square adds is probed (nearest hits, light states, no shading) and shaded in full only where its neighbours cannot give its colour. */
#include <string.h>

#include "rt.h"

/* Do the samples k[i] with bit i set in `set` (all of one shape) have contributions within thr8
 * of each other at every stored node? */
static int probe_agree(int n, const rt_sample *const k[], unsigned set, int thr8)
{
    int first = 0;
    while (!(set & (1u << first)))
        first++;
    int nodes = k[first]->nhits < RT_SAMPLE_MAX_HITS ? k[first]->nhits : RT_SAMPLE_MAX_HITS;
    for (int j = 0; j < nodes; j++)
        for (int ch = 0; ch < 3; ch++) {
            int lo = 255, hi = 0;
            for (int i = first; i < n; i++) {
                if (!(set & (1u << i)))
                    continue;
                int v = k[i]->hits[j].contrib[ch];
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
    return a->hits[0].object == b->hits[0].object && a->cell == b->cell &&
        memcmp(a->light_state, b->light_state, sizeof a->light_state) == 0 && probe_same_tree(a, b);
}

/* Does the colour at r depend on what no record holds, so that neighbours cannot give it: a
 * texture at a secondary hit (a checkerboard through glass or in a mirror), nodes beyond those
 * stored, or a highlight (its peak lies anywhere between samples)? */
static int probe_unseen(const rt_scene *s, const rt_sample *r)
{
    if (r->nhits > RT_SAMPLE_MAX_HITS)
        return 1;
    for (int j = 1; j < r->nhits; j++) {
        int o = r->hits[j].object;
        if (o != RT_NO_OBJECT && s->materials[s->objects[o].material].tex.kind != RT_TEX_NONE)
            return 1;
    }
    for (int l = 0; l < RT_MAX_LIGHTS; l++)
        if (r->light_state[l] == 2)
            return 1;
    return 0;
}

/* Bit i set for each context sample k[i] of the set `in` whose record is r's. */
static unsigned probe_matches(int n, const rt_sample *const k[], unsigned in, const rt_sample *r)
{
    unsigned m = 0;
    for (int i = 0; i < n; i++)
        if ((in & (1u << i)) && rt_probe_same(r, k[i]))
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

/* Is the primary hit of r on a noise texture (which varies between any two points)? */
static int probe_noise(const rt_scene *s, const rt_sample *r)
{
    int id = r->hits[0].object;
    return id != RT_NO_OBJECT && rt_scene_has(s, RT_FX_NOISE) &&
        s->materials[s->objects[id].material].tex.kind > RT_TEX_CHECKER;
}

/* Adds a probe's rays to st. */
static void probe_count(rt_stats *st, const rt_stats *ps)
{
    st->probe_shadow += ps->rays_shadow;
    st->probe_secondary += ps->rays_reflect + ps->rays_refract;
    st->shadow_tests += ps->shadow_tests;
}

int rt_probe_point(const rt_scene *s, const rt_view *v, const rt_params *p, rt_stats *st, int thr8,
                   int x, int y, int n, const rt_sample *const k[], real tx, real ty, int span,
                   rt_sample *out)
{
    /* 0. No probe where its answer cannot matter: a point whose record is a context sample's
     * gets that sample's verdict, one with a new record is shaded. So when every context sample
     * is on noise or probe_unseen, or all have one record whose contributions disagree, shade. */
    unsigned never = 0, same = 0;
    for (int i = 0; i < n; i++) {
        never += probe_noise(s, k[i]) || probe_unseen(s, k[i]);
        same += rt_probe_same(k[0], k[i]);
    }
    if (never == (unsigned)n || (same == (unsigned)n && !probe_agree(n, k, (1u << n) - 1, thr8)))
        return 0;

    /* 1. The primary hit and its checker cell; a noise texture there ends the probe. */
    rt_sample pr;
    rt_stats ps = {0};
    st->probes++;
    rt_probe_pixel(s, v, p, x, y, 0, &ps, &pr);
    probe_count(st, &ps);
    if (probe_noise(s, &pr))
        return 0;
    int id = pr.hits[0].object;
    unsigned m = 0;
    for (int i = n - 1; i >= 0; i--)
        m = m << 1 | (k[i]->hits[0].object == id && k[i]->cell == pr.cell ? 1u : 0);
    if (!m)
        return 0; /* something new */

    /* 2. The whole record (every light's state, the ray tree) where the context disagrees on
     * a light (a shadow or highlight edge crosses it) or the surface casts secondary rays (what
     * they meet can change anywhere); elsewhere the matching sample's record is the point's. */
    const rt_sample *f = k[probe_first(m)];
    int deep = f->nhits > 1;
    for (int i = 0; i < n; i++)
        deep |= memcmp(k[i]->light_state, f->light_state, sizeof f->light_state) != 0;
    *out = *f;
    if (deep) {
        rt_stats ps2 = {0};
        rt_probe_pixel(s, v, p, x, y, 1, &ps2, out);
        probe_count(st, &ps2);
        out->cell = pr.cell;
        m = probe_matches(n, k, m, out);
    }

    /* 3. Interpolation stands in where two samples or more have the point's record, or one
     * next to it (at most RT_PROBE_ONE_SPAN pixels across the context); where the colour
     * depends on nothing the record misses (probe_unseen); and where those samples'
     * contributions agree. */
    if (!m || (!(m & (m - 1)) && span > RT_PROBE_ONE_SPAN) || probe_unseen(s, out) ||
        !probe_agree(n, k, m, thr8))
        return 0;

    /* The colour: along x within each row of the context, then between the rows. */
    unsigned top = m & 3, bot = m >> 2 & 3;
    rt_color col = probe_mix(k[0]->color, k[1]->color, top, tx);
    if (n == 4)
        col = probe_mix(col, probe_mix(k[2]->color, k[3]->color, bot, tx),
                        (top ? 1u : 0) | (bot ? 2u : 0), ty);
    f = k[probe_first(m)];
    for (int j = 0; j < RT_SAMPLE_MAX_HITS; j++)
        memcpy(out->hits[j].contrib, f->hits[j].contrib, sizeof out->hits[j].contrib);
    out->color = col;
    out->probed = 1;
    return 1;
}
