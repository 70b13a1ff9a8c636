/* shapes.c: the per-type interface (ray intersection, surface normal) and the tracer's loops over objects. */
#include "rt_local.h"

/* Always inlined into the loops over objects below (rt_intersect gets an out-of-line copy). */
#define SHAPES_INLINE static inline __attribute__((always_inline))

/* Sphere: the perpendicular from the centre to the ray is formed explicitly, which keeps the
 * discriminant r^2 - |perp|^2 accurate in Q32.32 even far from the origin (where
 * |L|^2 - tca^2 would cancel). Given l = centre - origin and tca = l . d. */
SHAPES_INLINE int sphere_hit(const rt_object *o, vec3 l, real tca, dir3 d, real tmax, int quick,
                             real *t)
{
    /* Cheap miss test: the sphere lies behind an origin that is outside it. tca below
     * o->behind = -(r + 2^-10 + r 2^-13) says so without |l|^2: tca is l . d within
     * |l| 2^-U_LEN_ERR_SHIFT + 2 LSB (|d| = 1 within 2^-28 fixed, 2^-21 float, 2^-14
     * rt-fixed16: docs/numerics.md), so an origin with |l| <= r (1 + 2^-15) has
     * |tca| <= r (1 + 2^-15)(1 + 2^-14) + 2 LSB < r (1 + 2^-13) + 2^-10 = -behind (r_shr's
     * rounding is a step, within 2^-10). Below it, |l| > r (1 + 2^-15): w_len2(l) > radius2
     * (exact in fixed, within 2^-22 relative in float) and the test after it rejects too. */
    if (tca < o->behind || (tca < 0 && w_len2(l) > o->radius2))
        return 0;
    /* every hit lies at t >= tca - radius; tmax is at most a shadow segment's length (30573,
     * R_T_MAX for rays: rt_shape_ops) and radius <= 2048, so the sum is in range (below 32622),
     * as are tca -+ thc (|tca| <= 30572, thc <= radius): the unchecked forms, the same values
     * (docs/numerics.md, The sphere test) */
    if (tca > r_add_in(tmax, o->radius))
        return 0;
    /* |l - d tca|^2, where it is not above r^2; `quick` (rt_nearest_set's secondary rays, which
     * mostly miss by far) tests each component against r as it is formed (r_perp_within: the
     * same answer) */
    wide d2;
    if (quick) {
        if (!r_perp_within(l, d, tca, o->radius, o->radius2, &d2))
            return 0;
    } else {
        d2 = w_len2(v3_sub_in(l, d3_scale_in(d, tca)));
        if (d2 > o->radius2)
            return 0;
    }
    real thc = r_sqrt_w_in(w_sub(o->radius2, d2));
    real hit = r_add_in(tca, r_neg_in(thc));
    if (hit <= 0) {
        hit = r_add_in(tca, thc); /* the origin is inside: take the far side */
        if (hit <= 0)
            return 0;
    }
    if (hit >= tmax)
        return 0;
    *t = hit;
    return 1;
}

SHAPES_INLINE int sphere_intersect(const rt_object *o, vec3 org, dir3 d, real tmax, real *t)
{
    vec3 l = v3_sub_in(o->center, org);
    return sphere_hit(o, l, v3_dot_d_in(l, d), d, tmax, 0, t);
}

__attribute__((noinline)) dir3 rt_sphere_normal(const rt_object *o, const vec3 *p)
{
    return d3_norm_near(v3_sub_in(*p, o->center), o->inv_radius); /* |p - c| is about r */
}

static dir3 sphere_normal(const rt_object *o, vec3 p) { return rt_sphere_normal(o, &p); }

/* The plane test up to its division, given num = offset - org . normal, the origin's signed
 * distance to the plane: 1 when the ray meets the plane at t = num / den in (0, tmax), with num
 * and den turned positive in *pn and *pd. `near`: tmax <= R_T_MAX, so that tmax * |den|
 * (|den| <= 1 + 2^-28) stays in range and is formed without the range check (r_mul_u_in), and
 * num and den (a saturated difference and a dot product of unit vectors, never -2^31) are negated
 * without it (r_neg_in, u_neg_in): the same values. */
SHAPES_INLINE int plane_meets(const rt_object *o, real num, dir3 d, real tmax, int near, real *pn,
                              unit *pd)
{
    unit den = d3_dot(d, o->normal);
    if (den > -U_EPS_PARALLEL && den < U_EPS_PARALLEL)
        return 0; /* parallel, or so nearly that the hit lies beyond any scene */
    if (num == 0 || (num < 0) != (den < 0))
        return 0; /* behind the origin (den is not 0: the signs differ exactly then) */
    if (den < 0) {
        den = near ? u_neg_in(den) : u_neg(den);
        num = near ? r_neg_in(num) : r_neg(num);
    }
    /* t = num / den < tmax exactly when num < tmax * den: test before dividing, so the
     * quotient never overflows. */
    if (num >= (near ? r_mul_u_in(tmax, den) : r_mul_u(tmax, den)))
        return 0;
    *pn = num;
    *pd = den;
    return 1;
}

/* The plane test given num (plane_meets), with the hit's distance in *t. */
SHAPES_INLINE int plane_hit(const rt_object *o, real num, dir3 d, real tmax, int near, real *t)
{
    unit den;
    if (!plane_meets(o, num, d, tmax, near, &num, &den))
        return 0;
    *t = r_div_u_pos(num, den);
    return 1;
}

SHAPES_INLINE int plane_intersect(const rt_object *o, vec3 org, dir3 d, real tmax, real *t)
{
    return plane_hit(o, r_sub(o->offset, v3_dot_d(org, o->normal)), d, tmax, 0, t);
}

static dir3 plane_normal(const rt_object *o, vec3 p)
{
    (void)p;
    return o->normal;
}

const rt_shape_ops rt_shapes[RT_SHAPE_COUNT] = {
    [RT_SPHERE] = {sphere_normal},
    [RT_PLANE] = {plane_normal},
};

int rt_intersect(const rt_object *o, vec3 org, dir3 d, real tmax, real *t)
{
    return o->kind == RT_SPHERE ? sphere_intersect(o, org, d, tmax, t)
                                : plane_intersect(o, org, d, tmax, t);
}

/* The loops below call the shape tests directly: the compiler then inlines them, which saves
 * the call and the passing of the ray per object. */

/* The plane test of rt_nearest_set, inlined there (on ARM too: once the tracer's other changes
 * were in, the inlined test measured 0.1% fewer instructions a frame than the out-of-line one,
 * and a smaller image): plane_intersect's result for rt_nearest_set's rays, whose origins are
 * in the scene as the sphere test takes them (|org| <= 23478, docs/numerics.md) and whose tmax
 * is at most R_T_MAX. So |org . n| <= 23478 and, with |offset| <= 4096, |offset - org . n| is
 * below 27575: the numerator is formed without the range checks (v3_dot_d_in, r_add_in, the
 * same values), and plane_hit takes its in-range path (near). */
static inline int shapes_plane(const rt_object *o, const vec3 *org, const dir3 *d, real tmax,
                               real *t)
{
    return plane_hit(o, r_add_in(o->offset, r_neg_in(v3_dot_d_in(*org, o->normal))), *d, tmax, 1,
                     t);
}

/* The loop of rt_nearest_set: the nearest object of cand (within the scene's objects). */
SHAPES_INLINE int shapes_nearest(const rt_scene *s, vec3 org, dir3 d, real tmax, uint32_t cand,
                                 real *t)
{
    int best = -1;
    /* a sphere's tca = (c - org) . d as c . d against the ray's part (v3_dot_part): l = c - org
     * is formed only for the spheres sphere_hit's first test does not reject */
    const dotpart od = v3_dot_part(org, d);
    /* The objects' order (so the same tmax at every test), up to the last candidate: a bit
     * shifted out per object (its test skipped when clear) */
    for (int i = 0; cand; cand >>= 1, i++) {
        const rt_object *o = &s->objects[i];
        real hit;
        if (!(cand & 1))
            continue;
        if (o->kind == RT_SPHERE) {
            real tca = v3_dot_d_from(o->center, d, od);
            if (tca < o->behind || !sphere_hit(o, v3_sub_in(o->center, org), tca, d, tmax, 1, &hit))
                continue;
        } else if (!shapes_plane(o, &org, &d, tmax, &hit)) {
            continue;
        }
        tmax = hit;
        best = i;
    }
    *t = tmax;
    return best;
}

/* cand without the bits of objects the scene does not have. */
static inline uint32_t shapes_in_scene(const rt_scene *s, uint32_t cand)
{
    return s->nobjects < 32 ? cand & (((uint32_t)1 << s->nobjects) - 1) : cand;
}

int rt_nearest_set(const rt_scene *s, vec3 org, dir3 d, real tmax, uint32_t cand, real *t)
{
    return shapes_nearest(s, org, d, tmax, shapes_in_scene(s, cand), t);
}

/* rt_nearest_from_in's search with one copy of rt_nearest_set's loop for both of its searches
 * (the second, of every candidate, only where the first, of ray_in's, did not find `need`):
 * fewer instructions on x86-64 than calling rt_nearest_from_in (callgrind, 13 intro frames:
 * rt-float 593.5 M against 597.0 M, rt-fixed 776.4 M against 778.8 M). */
int rt_nearest_from(const rt_scene *s, vec3 org, dir3 d, real tmax, int from, uint32_t cand,
                    real *t)
{
    int need;
    uint32_t all = rt_ray_cand(s, from, d, shapes_in_scene(s, cand), &need);
    cand = need >= 0 ? all & s->cull.ray_in[need] : all;
    for (;;) {
        int id = shapes_nearest(s, org, d, tmax, cand, t);
        if (id == need || cand == all)
            return id;
        cand = all;
    }
}

int rt_nearest_primary(const rt_scene *s, dir3 d, uint32_t cand, real *t)
{
    real tmax = R_T_MAX;
    int best = -1;
    cand = shapes_in_scene(s, cand);
    /* A plane ahead of every other candidate and the only one among them (the usual floor) is
     * tested last: whether it meets the ray within R_T_MAX does not depend on the others, and a
     * sphere after it wins exactly when its hit is nearer than the plane's t, which
     * r_div_u_above tells without the division; the division is made only when the plane wins.
     * Any other mix of planes keeps the objects' order (a plane's test against a tmax from an
     * earlier object is no comparison of distances). */
    uint32_t first = cand & (0 - cand);
    int last = -1;
    if ((first & s->cull.plane_set) && !(cand & s->cull.plane_set & ~first)) {
        last = __builtin_ctz(first);
        cand &= ~first;
    }
    /* Set bits in increasing order: the objects' order, as rt_nearest tests them. */
    for (; cand; cand &= cand - 1) {
        int i = __builtin_ctz(cand);
        const rt_object *o = &s->objects[i];
        real hit;
        int h;
        if (o->kind == RT_SPHERE) {
            /* l = centre - eye is the frame's; a ray that passes clearly wide of the sphere
             * is rejected from tca alone (rt_scene.cull.eye_cull), before the perpendicular. */
            vec3 l = s->cull.eye_l[i];
            real tca = v3_dot_d_in(l, d);
            wide k = s->cull.eye_cull[i];
            if (k > 0 && (tca <= 0 || w_sq(tca) < k))
                continue;
            h = sphere_hit(o, l, tca, d, tmax, 0, &hit);
        } else {
            h = plane_hit(o, s->cull.eye_num[i], d, tmax, 1, &hit); /* tmax <= R_T_MAX */
        }
        if (h) {
            tmax = hit;
            best = i;
        }
    }
    real num;
    unit den;
    if (last >= 0 &&
        plane_meets(&s->objects[last], s->cull.eye_num[last], d, R_T_MAX, 1, &num, &den) &&
        (best < 0 || !r_div_u_above(num, den, tmax))) {
        tmax = r_div_u_pos(num, den);
        best = last;
    }
    *t = tmax;
    return best;
}

#if RT_COMPILED_PROBE
int rt_plane_primary(const rt_scene *s, int id, dir3 d, real *t)
{
    real num;
    unit den;
    if (!plane_meets(&s->objects[id], s->cull.eye_num[id], d, R_T_MAX, 1, &num, &den))
        return 0;
    *t = r_div_u_pos(num, den);
    return 1;
}
#endif

/* sphere_intersect's answer for a shadow segment, whose hit point is not needed: the same
 * steps up to the discriminant, then r_sphere_span decides where the hit would lie (the fixed
 * build without the square root). */
SHAPES_INLINE int sphere_blocks(const rt_object *o, vec3 org, dir3 d, real tmax)
{
    vec3 l = v3_sub_in(o->center, org);
    real tca = v3_dot_d_in(l, d);
    if (tca < 0 && w_len2(l) > o->radius2)
        return 0;
    if (tca > r_add(tmax, o->radius))
        return 0;
    wide d2 = w_len2(v3_sub_in(l, d3_scale_in(d, tca)));
    if (d2 > o->radius2)
        return 0;
    return r_sphere_span(w_sub(o->radius2, d2), tca, tmax);
}

/* The full test of a shadow-ray candidate, kept out of line: the loop below then holds the ray
 * and the light in registers instead of sharing them with the intersection code (RT_OUT_OF_LINE). */
static RT_OUT_OF_LINE int shapes_blocks(const rt_object *o, const vec3 *org, const dir3 *d,
                                        real dist)
{
    real hit;
    return o->kind == RT_SPHERE ? sphere_blocks(o, *org, *d, dist)
                                : plane_intersect(o, *org, *d, dist, &hit);
}

int rt_occluded(const rt_scene *s, rt_stats *st, int light, uint32_t occ, const vec3 *org,
                const dir3 *d, real dist)
{
    const dir3 dd = *d;
    const dotpart lpd = v3_dot_part(s->lights[light].pos, dd);
    const rcull *cull = s->cull.shadow_cull[light];
    uint32_t tested = 0;
    int blocked = 0;
    /* A segment the bounding sphere's rejection covers misses every sphere inside it. */
    rcull kb = s->cull.bound_shadow_cull[light];
    if (kb != 0 && (occ & s->cull.bound_set) &&
        r_cull_rejects(v3_dot_d_from(s->cull.bound_center, dd, lpd), kb))
        occ &= ~s->cull.bound_set;
    if (!occ)
        return 0;
    /* Only the objects that can block a ray of its quadrant (rt_scene_prepare). */
    if (RT_SHADOW_SETS) {
        const dir3 *pl = s->cull.shadow_plane[light];
        occ &= s->cull.shadow_quad[light][d3_below(dd, pl[0]) | d3_below(dd, pl[1]) << 1];
    }
    /* Set bits in increasing order (the objects' order); counted once, after the loop. The
     * lowest bit's clz j gives object 31 - j. */
    for (; occ; occ &= occ - 1) {
        int j = __builtin_clz(occ & (0 - occ));
        const rt_object *o = &s->objects[31 - j];
        rcull k = cull[31 - j];
        tested++;
        /* The ray from the light back along -d passes too far from the sphere for this
         * segment to reach it (rt_scene_prepare): the full test would miss. A plane's entry
         * is 0. */
        if ((k == 0 ||
             !r_cull_rejects(v3_dot_d_from(o->center, dd, lpd), k)) && /* (c - light) . d */
            shapes_blocks(o, org, d, dist)) {
            blocked = 1;
            break;
        }
    }
    st->shadow_tests += tested;
    return blocked;
}
