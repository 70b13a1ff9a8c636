/* probe.c: probe mode: a point that splitting a square adds is probed (nearest hits and light states, no shading) and shaded in full only where its neighbours cannot give its colour. */
#include <string.h>

#include "rt.h"

int rt_probe_same(const rt_sample *a, const rt_sample *b)
{
    if (a->hits[0].object != b->hits[0].object || a->cell != b->cell || a->nhits != b->nhits ||
        memcmp(a->light_state, b->light_state, sizeof a->light_state) != 0)
        return 0;
    int n = a->nhits < RT_SAMPLE_MAX_HITS ? a->nhits : RT_SAMPLE_MAX_HITS;
    for (int j = 1; j < n; j++)
        if (a->hits[j].object != b->hits[j].object || a->hits[j].level != b->hits[j].level)
            return 0;
    return 1;
}

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
static rt_color probe_mix(rt_color a, rt_color b, unsigned m, real t)
{
    if (m == 1)
        return a;
    if (m == 2)
        return b;
    return v3(probe_lerp(a.x, b.x, t), probe_lerp(a.y, b.y, t), probe_lerp(a.z, b.z, t));
}

int rt_probe_point(const rt_scene *s, const rt_view *v, const rt_params *p, rt_stats *st, int thr8,
                   int x, int y, int n, const rt_sample *const k[], real tx, real ty,
                   rt_sample *out)
{
    unsigned all = (1u << n) - 1, same = 1;
    for (int i = 1; i < n; i++)
        same |= rt_probe_same(k[0], k[i]) ? 1u << i : 0;
    if (same == all && !probe_agree(n, k, all, thr8))
        return 0; /* whatever the probe finds, the point is shaded */

    rt_stats ps = {0};
    rt_probe_pixel(s, v, p, x, y, &ps, out);
    st->probes++;
    st->probe_shadow += ps.rays_shadow;
    st->probe_secondary += ps.rays_reflect + ps.rays_refract;
    st->shadow_tests += ps.shadow_tests;

    /* The context samples on the probe's side of every edge. */
    unsigned m = 0;
    for (int i = n - 1; i >= 0; i--)
        m = m << 1 | (rt_probe_same(out, k[i]) ? 1u : 0);
    if (!m || !probe_agree(n, k, m, thr8))
        return 0; /* something new, or a change interpolation cannot follow */

    /* Along x in each row of the context, then between the rows that have a match. */
    unsigned top = m & 3, bot = m >> 2 & 3;
    rt_color col = probe_mix(k[0]->color, k[1]->color, top, tx);
    if (n == 4)
        col = probe_mix(col, probe_mix(k[2]->color, k[3]->color, bot, tx),
                        (top ? 1u : 0) | (bot ? 2u : 0), ty);
    out->color = col;
    int first = 0;
    while (!(m & (1u << first)))
        first++;
    for (int j = 0; j < RT_SAMPLE_MAX_HITS; j++)
        memcpy(out->hits[j].contrib, k[first]->hits[j].contrib, sizeof out->hits[j].contrib);
    out->probed = 1;
    return 1;
}
