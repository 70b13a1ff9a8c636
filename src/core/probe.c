/* probe.c: probe mode: a point that splitting a square adds is probed (nearest hits and light states, no shading) and shaded in full only where its neighbours cannot give its colour. */
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

/* Bit i set for each context sample k[i] of the set `in` whose record is out's. */
static unsigned probe_matches(int n, const rt_sample *const k[], unsigned in, const rt_sample *out)
{
    unsigned m = 0;
    for (int i = 0; i < n; i++)
        if ((in & (1u << i)) && rt_probe_same(out, k[i]))
            m |= 1u << i;
    return m;
}

static int probe_first(unsigned set)
{
    int i = 0;
    while (!(set & (1u << i)))
        i++;
    return i;
}

int rt_probe_point(const rt_scene *s, const rt_view *v, const rt_params *p, rt_stats *st, int thr8,
                   int x, int y, int n, const rt_sample *const k[], real tx, real ty,
                   rt_sample *out)
{
    /* 1. The primary hit and its checker cell. A surface with a noise texture varies between
     * any two points: interpolation cannot stand in. */
    rt_sample pr;
    rt_stats ps = {0};
    st->probes++;
    rt_probe_pixel(s, v, p, x, y, 0, 0, &ps, &pr);
    int id = pr.hits[0].object;
    if (id != RT_NO_OBJECT && rt_scene_has(s, RT_FX_TEXTURE)) {
        int kind = s->materials[s->objects[id].material].tex.kind;
        if (kind != RT_TEX_NONE && kind != RT_TEX_CHECKER)
            return 0;
    }
    unsigned m = 0;
    for (int i = 0; i < n; i++)
        if (k[i]->hits[0].object == id && k[i]->cell == pr.cell)
            m |= 1u << i;
    if (!m)
        return 0; /* something new */

    /* 2. What the samples on that surface disagree on: only those lights' states, and the ray
     * tree only if theirs differ. What they agree on is taken as the point's. */
    const rt_sample *f = k[probe_first(m)];
    unsigned lights = 0;
    int deep = 0;
    for (int i = 0; i < n; i++) {
        if (!(m & (1u << i)))
            continue;
        for (int l = 0; l < RT_MAX_LIGHTS; l++)
            if (k[i]->light_state[l] != f->light_state[l])
                lights |= 1u << l;
        deep |= !probe_same_tree(k[i], f);
    }
    *out = *f;
    if (lights || deep) {
        rt_probe_pixel(s, v, p, x, y, lights, deep, &ps, &pr);
        st->probe_shadow += ps.rays_shadow;
        st->probe_secondary += ps.rays_reflect + ps.rays_refract;
        st->shadow_tests += ps.shadow_tests;
        for (int l = 0; l < RT_MAX_LIGHTS; l++)
            if (lights & (1u << l))
                out->light_state[l] = pr.light_state[l];
        if (deep) {
            out->nhits = pr.nhits;
            for (int j = 1; j < RT_SAMPLE_MAX_HITS; j++) {
                out->hits[j].object = pr.hits[j].object;
                out->hits[j].level = pr.hits[j].level;
            }
        }
        m = probe_matches(n, k, m, out);
        if (!m)
            return 0; /* a light state or a ray tree none of them has */
    }
    /* Interpolation stands in only with two samples or more to go by, on a surface that
     * reflects and refracts nothing (what its secondary rays see, a checkerboard through glass,
     * is in no record), and where their contributions agree. */
    if (!(m & (m - 1)) || out->nhits > 1 || !probe_agree(n, k, m, thr8))
        return 0;

    /* 3. The colour: along x within each row of the context, then between the rows. */
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
