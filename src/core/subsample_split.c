/* subsample_split.c: whether a square's corners disagree (rt_corners_differ, ss_noise_seen, ss_small_missed) and the centre test of a square split for its contributions (rt_centre_smooth). */
#include "subsample.h"

/* The contribution bytes of node j of a sample (rt_hit_rec.contrib). */
#define SS_CONTRIB(sm, j) ((sm)->hits[j].contrib)

/* Do the corners' ray trees differ only in faint nodes? Every node below the primary hit that
 * is not the same (object and level) at the same place in corner 0's tree and in another
 * corner's has contributions of at most lim in every channel, and every tree is stored whole. */
static __attribute__((noinline)) int ss_faint_tree(const rt_sample *const k[4], int lim)
{
    const rt_sample *a = k[0];
    for (int i = 0; i < 4; i++)
        if (k[i]->nhits > RT_SAMPLE_MAX_HITS)
            return 0;
    for (int i = 1; i < 4; i++) {
        const rt_sample *b = k[i];
        const int na = a->nhits, nb = b->nhits, n = na > nb ? na : nb;
        for (int j = 1; j < n; j++) {
            if (j < na && j < nb && a->hits[j].object == b->hits[j].object &&
                a->hits[j].level == b->hits[j].level)
                continue;
            for (int ch = 0; ch < 3; ch++)
                if ((j < na && a->hits[j].contrib[ch] > lim) ||
                    (j < nb && b->hits[j].contrib[ch] > lim))
                    return 0;
        }
    }
    return 1;
}

/* Differences of structure rt_corners_differ lets through to the contributions' test at half
 * the threshold (bits): lit and unlit corners, faint differences of the ray trees. */
enum ss_weak { SS_WEAK_LIGHT = 1, SS_WEAK_TREE = 2 };

enum rt_split_reason rt_corners_differ(const rt_sample *const k[4], int thr8)
{
    const rt_sample *a = k[0], *b = k[1], *c = k[2], *d = k[3];
    /* The corners' counts, light states, cells and flags as one word each (offsets 12..15):
     * where all four agree (the usual case), only the primary objects are left to compare
     * before the ray trees; else the bytes themselves, in the order of the reasons. */
    const uint32_t wa = a->head, wb = b->head, wc = c->head, wd = d->head;
    const unsigned o = a->hits[0].object;
    if (b->hits[0].object != o || c->hits[0].object != o || d->hits[0].object != o)
        return RT_SPLIT_OBJECT;
    /* the bytes in which some corner differs from corner 0 */
    const union {
        uint32_t w;
        struct {
            uint8_t nhits, lights, cell, flags; /* rt_sample's, in its order */
        } b;
    } diff = {.w = (wa ^ wb) | (wa ^ wc) | (wa ^ wd)};
    /* A difference of structure that need not show in the colours, a light lit at some corners
     * and not at others or a ray tree with other objects, splits only where it does: where the
     * contributions differ by more than half the threshold. A faint shadow (a fill light's,
     * or the sun's at a grazing angle) or a faint reflection edge is interpolated like any
     * gradient. A highlight at some corner always splits (its peak can lie between them). */
    int weak = 0; /* enum ss_weak bits; SS_WEAK_TREE decides the reason */
    int n = a->nhits < RT_SAMPLE_MAX_HITS ? a->nhits : RT_SAMPLE_MAX_HITS;
    if (diff.w) {
        if (diff.b.cell)
            return RT_SPLIT_OBJECT;
        if (diff.b.lights & RT_LIGHTS_HIGHLIGHT)
            return RT_SPLIT_LIGHT;
        weak = diff.b.lights ? SS_WEAK_LIGHT : 0;
        if (diff.b.nhits) {
            if (!ss_faint_tree(k, thr8 / 2))
                return RT_SPLIT_SECONDARY;
            weak |= SS_WEAK_TREE;
        }
    }
    if (!(weak & SS_WEAK_TREE))
        for (int j = 1; j < n; j++) {
            const unsigned ob = a->hits[j].object, lv = a->hits[j].level;
            if (b->hits[j].object != ob || c->hits[j].object != ob || d->hits[j].object != ob ||
                b->hits[j].level != lv || c->hits[j].level != lv || d->hits[j].level != lv) {
                if (!ss_faint_tree(k, thr8 / 2))
                    return RT_SPLIT_SECONDARY;
                weak |= SS_WEAK_TREE;
                break;
            }
        }
    if (weak & SS_WEAK_TREE) /* the nodes every corner has (the others are faint) */
        for (int i = 1; i < 4; i++)
            n = k[i]->nhits < n ? k[i]->nhits : n;
    const int lim = weak ? thr8 / 2 : thr8;
    for (int j = 0; j < n; j++) {
        const uint8_t *pa = SS_CONTRIB(a, j), *pb = SS_CONTRIB(b, j), *pc = SS_CONTRIB(c, j),
                      *pd = SS_CONTRIB(d, j);
        for (int ch = 0; ch < 3; ch++) {
            int lo = pa[ch], hi = lo, v = pb[ch];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
            v = pc[ch];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
            v = pd[ch];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
            if (hi - lo > lim)
                return weak & SS_WEAK_TREE ? RT_SPLIT_SECONDARY
                    : weak                 ? RT_SPLIT_LIGHT
                                           : RT_SPLIT_CONTRIB;
        }
    }
    return RT_SPLIT_NONE;
}

__attribute__((cold)) int rt_centre_smooth(const rt_sample *const k[4], const rt_sample *mid,
                                           int tol)
{
    const rt_sample *a = k[0];
    if (!rt_probe_same(a, mid)) /* its shape: the corners' (rt_corners_differ found them alike) */
        return 0;
    const int n = a->nhits < RT_SAMPLE_MAX_HITS ? a->nhits : RT_SAMPLE_MAX_HITS;
    for (int j = 0; j < n; j++)
        for (int ch = 0; ch < 3; ch++) {
            /* 2 (mid - the mean of each diagonal's ends): no rounding enters */
            const int m = 2 * mid->hits[j].contrib[ch];
            const int d0 = m - a->hits[j].contrib[ch] - k[3]->hits[j].contrib[ch],
                      d1 = m - k[1]->hits[j].contrib[ch] - k[2]->hits[j].contrib[ch];
            if ((unsigned)(d0 + 2 * tol) > (unsigned)(4 * tol) ||
                (unsigned)(d1 + 2 * tol) > (unsigned)(4 * tol)) /* |d| > 2 tol */
                return 0;
        }
    return 1;
}

int ss_small_missed(const rt_view *v, const rt_sample *const k[4], int x0, int y0, int w, int h)
{
    for (uint32_t m = v->small; m; m &= m - 1) {
        const unsigned i = (unsigned)__builtin_ctz(m);
        const int16_t *b = v->box[i];
        /* a box of side s + 1 (the cone's box, a pixel wider than the outline either side)
         * holds a sphere about s - 3 across; one wider than the square's diagonal, 1.41 w,
         * always has a corner of the square's lattice on it (within a pixel): left out */
        if (2 * (b[2] - b[0]) > 3 * w + 6 || 2 * (b[3] - b[1]) > 3 * h + 6 || b[2] < x0 ||
            b[0] > x0 + w || b[3] < y0 || b[1] > y0 + h)
            continue;
        if (k[0]->hits[0].object != i && k[1]->hits[0].object != i && k[2]->hits[0].object != i &&
            k[3]->hits[0].object != i)
            return 1;
    }
    return 0;
}

/* ss_noise_seen for node j of corner 0's tree, on a noise texture: its parent flat and its
 * contribution over twice the threshold at some corner that has the node. Out of line and cold:
 * the usual node is on another object. */
static __attribute__((cold, noinline)) int ss_noise_node(const ss_ctx *c,
                                                         const rt_sample *const k[4], int j)
{
    const rt_sample *a = k[0];
    const unsigned lv = a->hits[j].level & 15u;
    int up = j - 1; /* its parent: the last node before it a level up (depth first) */
    while (up > 0 && (a->hits[up].level & 15u) != lv - 1)
        up--;
    if (!(c->flat_view >> a->hits[up].object & 1))
        return 0;
    for (int i = 0; i < 4; i++) /* the corners share the node (RT_SPLIT_NONE) or it is faint */
        for (int ch = 0; ch < 3 && j < k[i]->nhits; ch++)
            if (k[i]->hits[j].contrib[ch] > 2 * c->thr8)
                return 1;
    return 0;
}

int ss_noise_seen(const ss_ctx *c, const rt_sample *const k[4])
{
    const rt_sample *a = k[0];
    const uint32_t noise = c->noise_beyond;
    const int n = a->nhits < RT_SAMPLE_MAX_HITS ? a->nhits : RT_SAMPLE_MAX_HITS;
    for (int j = 1; j < n; j++) {
        const unsigned id = a->hits[j].object;
        if (id < RT_MAX_OBJECTS && (noise >> id & 1) && ss_noise_node(c, k, j))
            return 1;
    }
    return 0;
}

int ss_pool_over(const rt_view *v, const rt_sample *const k[4], int x0, int y0, int w, int h)
{
    for (uint32_t m = v->pool; m; m &= m - 1) {
        const unsigned i = (unsigned)__builtin_ctz(m), j = v->pool_plane[i];
        const int16_t *b = v->pool_box[i];
        if (b[2] < x0 || b[0] > x0 + w || b[3] < y0 || b[1] > y0 + h)
            continue;
        if (k[0]->hits[0].object == j || k[1]->hits[0].object == j || k[2]->hits[0].object == j ||
            k[3]->hits[0].object == j)
            return 1;
    }
    return 0;
}
