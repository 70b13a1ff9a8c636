/* prepare.c: derived scene data: per-frame constants, culling, and the effects a scene needs. */
#include "rt_local.h"

/* The absolute slack terms of the proven margins below (each proof says which it takes and
 * why): powers of two, exact in both builds and far above half a Q16.16 step (2^-17). */
#define PREP_SLACK_10 R(0.0009765625) /* 2^-10 */
#define PREP_SLACK_8 R(0.00390625)    /* 2^-8 */
#define PREP_SLACK_7 R(0.0078125)     /* 2^-7 */
#define PREP_SLACK_6 R(0.015625)      /* 2^-6 */

/* delta of the occluder and candidate sets' proofs (scene_shadow_pairs, scene_ray_sets): how far
 * a point the tracer takes to lie on a sphere of the scene may be off it, the unit vectors'
 * length error at the scene's size and two R_EPS_OFFSET included. A constant in range. */
static real scene_delta(void)
{
    return r_add_in(r_add_in(PREP_SLACK_8, r_shr(R_SCENE_MAX, U_LEN_ERR_SHIFT - 3)),
                    r_muli(R_EPS_OFFSET, 2));
}

/* Signed distance of p from the plane o (positive on the side its normal points to). */
static real scene_side(const rt_object *plane, vec3 p)
{
    return r_sub(v3_dot_d(p, plane->normal), plane->offset);
}

/* Can the plane `pl` come between light position `lp` and a point of another object? Only if
 * some other object reaches the far side of the plane from the light: the segment from a
 * surface point to the light crosses the plane only then. */
static int scene_plane_occludes(const rt_scene *s, int pl, vec3 lp)
{
    const rt_object *p = &s->objects[pl];
    real sl = scene_side(p, lp);
    if (sl == 0) /* a light in the plane: any other object's shadow ray may graze it */
        return s->nobjects > 1;
    for (int j = 0; j < s->nobjects; j++) {
        const rt_object *o = &s->objects[j];
        if (j == pl)
            continue;
        real lo, hi;
        if (o->kind == RT_SPHERE) {
            real c = scene_side(p, o->center);
            lo = r_sub(c, o->radius);
            hi = r_add(c, o->radius);
        } else {
            /* Planes that are not exactly parallel cross somewhere, however far out. */
            int same = o->normal.x == p->normal.x && o->normal.y == p->normal.y &&
                o->normal.z == p->normal.z;
            dir3 neg = d3_neg(o->normal);
            int opposite = neg.x == p->normal.x && neg.y == p->normal.y && neg.z == p->normal.z;
            if (!same && !opposite)
                return 1;
            /* points x of o have x . n_o = offset_o, so x . n_p = +-offset_o */
            lo = hi = r_sub(same ? o->offset : r_neg(o->offset), p->offset);
        }
        if (sl > 0 ? lo < 0 : hi > 0)
            return 1;
    }
    return 0;
}

/* Effects on demand: what the materials in use, the lights and the geometry call for. */
static void scene_derive_effects(rt_scene *s)
{
    unsigned fx = 0;
    int secondary = 0, self_loop = 0;
    uint32_t self_shadow = 0; /* spheres whose inside some ray can reach */
    for (int i = 0; i < s->nobjects; i++) {
        const rt_object *o = &s->objects[i];
        const rt_material *m = &s->materials[o->material];
        /* Rays get inside a sphere by refraction, or by starting there: the camera inside. */
        if (o->kind == RT_SPHERE &&
            (m->transmit > 0 ||
             w_len2(v3_sub(s->camera.eye, o->center)) <= w_sq(r_add(o->radius, R_EPS_OFFSET))))
            self_shadow |= (uint32_t)1 << i;
        if (m->specular > 0 && s->nlights > 0)
            fx |= RT_FX_SPECULAR;
        if (m->transmit > 0)
            fx |= RT_FX_REFRACT | RT_FX_REFLECT; /* total internal reflection */
        if (m->reflect > 0)
            fx |= RT_FX_REFLECT;
        if (m->tex.active)
            fx |= RT_FX_TEXTURE;
        if (m->tex.kind == RT_TEX_MARBLE || m->tex.kind == RT_TEX_WOOD ||
            m->tex.kind == RT_TEX_NOISE)
            fx |= RT_FX_NOISE;
        if (m->reflect > 0 || m->transmit > 0) {
            secondary++;
            /* a ray inside a sphere meets the sphere again */
            if (self_shadow & ((uint32_t)1 << i))
                self_loop = 1;
        }
    }
    /* A convex object's mirror ray never meets the object again from outside, so one such
     * object alone is a ray tree of depth 1; two can mirror each other without end. */
    s->reach_depth = secondary == 0 ? 0 : (secondary == 1 && !self_loop ? 1 : RT_MAX_DEPTH);

    for (int l = 0; l < RT_MAX_LIGHTS; l++) {
        uint32_t occ = 0;
        for (int i = 0; i < s->nobjects && l < s->nlights; i++) {
            /* A sphere can shadow any other object, and its own inside when a ray can get
             * there; a plane only what lies beyond it. */
            const rt_object *o = &s->objects[i];
            if (o->kind == RT_SPHERE ? s->nobjects > 1 || (self_shadow & ((uint32_t)1 << i))
                                     : scene_plane_occludes(s, i, s->lights[l].pos))
                occ |= (uint32_t)1 << i;
        }
        s->occluders[l] = occ;
        if (occ)
            fx |= RT_FX_SHADOW;
    }
    s->effects = fx;
    s->cull.forced = 0;
}

void rt_scene_force_effects(rt_scene *s)
{
    s->effects = RT_FX_ALL;
    s->reach_depth = RT_MAX_DEPTH;
    s->cull.forced = 1;
    for (int l = 0; l < RT_MAX_LIGHTS; l++) {
        s->occluders[l] = s->nobjects >= 32 ? 0xFFFFFFFFu : ((uint32_t)1 << s->nobjects) - 1;
        for (int j = 0; RT_SHADOW_SETS && j < RT_MAX_OBJECTS; j++)
            s->cull.occ_of[l][j] = s->occluders[l];
    }
    for (int j = 0; j < RT_MAX_OBJECTS; j++) { /* every secondary ray tests every object */
        for (int q = 0; q < 8; q++)
            s->cull.ray_oct[j][q] = 0xFFFFFFFFu;
        s->cull.ray_in[j] = 0xFFFFFFFFu;
    }
    for (int l = 0; l < RT_MAX_LIGHTS; l++) /* and every shadow ray is tested */
        s->cull.dark_inside[l] = 0;
}

/* Does the surface of object o pass within RT_NEAR_LIGHT of the point q? */
static int scene_light_near(const rt_object *o, vec3 q)
{
    real gap;
    if (o->kind == RT_SPHERE) {
        real dist = 0;
        vec3 v = v3_sub(q, o->center);
        if (!v3_is_zero(v))
            d3_norm(v, &dist);
        gap = r_abs(r_sub(dist, o->radius));
    } else {
        gap = r_abs(r_sub(v3_dot_d(q, o->normal), o->offset));
    }
    return gap < RT_NEAR_LIGHT;
}

/* The cone of directions from lp that scene_cull's rejection (K = k > 0) lets through, for the
 * sphere whose centre is at squared distance d2 (d = r_sqrt_w(d2)) from lp, e its E: the sine
 * of its half-angle around the direction to the centre, or 0 when there is no such cone under
 * 1. A ray along d with s = c . d as computed passes the rejection only if s >= sqrt(K), so
 * the exact c . d is at least sqrt(K) - E and the line of d passes within
 * sqrt(D^2 - (sqrt(K) - E)^2) of the centre: that over D, rounded up in both builds (sqrt(K)
 * taken a step and 2^-20 low, the result raised by 2^-10 D and two steps, D taken a step and
 * 2^-20 low).
 * A direction further off the centre's than the asin of this is rejected by the test. */
static real scene_cone(wide d2, real d, wide k, real e)
{
    real kr = r_sqrt_w(k);
    kr = r_sub(r_sub(r_sub(kr, e), r_shr(kr, 20)), R_LSB);
    real dl = r_sub(r_sub(d, r_shr(d, 20)), R_LSB);
    if (kr <= 0 || dl <= 0 || kr >= d)
        return 0;
    real far = r_add(r_add(r_sqrt_w(w_sub(d2, w_sq(kr))), r_shr(d, 10)), r_muli(R_LSB, 2));
    if (far >= dl)
        return 0;
    real sn = r_add(r_div(far, dl), r_muli(R_LSB, 2));
    return sn < R_ONE ? sn : 0;
}

/* The rejection of sphere o for rays from or toward the point lp (rt_scene.cull.shadow_cull: a light,
 * reach 2 R_EPS_OFFSET; rt_scene.cull.eye_cull: the eye, reach 0, where the ray starts at lp
 * itself and s = tca, pointing away when s <= 0).
 *
 * A shadow ray is the segment from p_out (the hit point lifted R_EPS_OFFSET off the surface)
 * along d toward the light, stopped R_EPS_OFFSET short of it; d is aimed from the hit point
 * or from p_out (near lights). Every point of it lies within mu = 2 R_EPS_OFFSET (plus
 * rounding) of the ray from the light back along -d. If the sphere test reports a hit, a
 * point of the segment is within the radius r (plus the test's rounding) of the centre, so
 * that ray comes within R = r + mu + margin of the centre. With c = centre - light, D = |c|
 * and s = c . d as computed (|s - exact| <= E, the rounding of the dot product and of d's
 * length), the ray passes farther than R from the centre when s >= 0 (it points away; the
 * nearest point is the light, D > R) or when D^2 - s^2 > R^2 + E (2D + E), i.e.
 * s^2 < K = D^2 - R^2 - E (2D + E). K <= 0 (light inside or near the sphere): no rejection.
 * The margins are generous for both builds: 2^-10 + (D + r) 2^-14 on the radius covers the
 * sphere test's rounding in either (a few Q16.16 steps, or float's relative 2^-24 of the
 * coordinates) and the rounding of K itself; E = D 2^-18 + 2 LSB bounds the dot product's
 * error (the unit vector's length is exact to 2^-28 fixed, 2^-21 float; with unit in Q16.16,
 * 1.3 * 2^-16, E = D 2^-14 + 2 LSB: U_LEN_ERR_SHIFT). */
static wide scene_cull(const rt_object *o, vec3 lp, real reach, real *cone)
{
    vec3 c = v3_sub(o->center, lp);
    wide d2 = w_len2(c);
    real d = r_sqrt_w(d2);
    real margin = r_add(PREP_SLACK_10, r_shr(r_add(d, o->radius), 14));
    real big_r = r_add(r_add(o->radius, reach), margin);
    real e = r_add(r_shr(d, U_LEN_ERR_SHIFT), r_muli(R_LSB, 2));
    /* D < 14190 and R, E small against it inside the scene cube: no term saturates */
    wide k = w_sub(w_sub(d2, w_sq(big_r)), w_add(w_mul(r_muli(d, 2), e), w_sq(e)));
    if (cone)
        *cone = k > 0 ? scene_cone(d2, d, k, e) : 0;
    return k > 0 ? k : 0;
}

int rt_scene_mirror(const rt_scene *s)
{
    if (!rt_scene_has(s, RT_FX_REFLECT) || s->cull.forced)
        return -1; /* no reflected ray, or trace_secondary tests every object */
    for (int i = 0; i < s->nobjects; i++) {
        const rt_object *o = &s->objects[i];
        const rt_material *m = &s->materials[o->material];
        /* eye_num < 0: the eye on the side the normal points to, which every ray from it meets */
        if (o->kind == RT_PLANE && (m->reflect > 0 || m->transmit > 0) && s->cull.eye_num[i] < 0)
            return i;
    }
    return -1;
}

/* The mirror cone of sphere i (radius r, centre c) in plane pl (unit normal n as prepared, n^ its
 * exact unit vector, M the mirror in the plane {x : x . n^ = offset}), for the rays traced as
 * follows: a primary ray from the eye e along d (rt_view_ray) whose nearest hit is at t0 > 0 on
 * the plane's front; p = e + t0 d as trace_ray forms it, p_out = p + R_EPS_OFFSET n, and the
 * reflected ray from p_out along d' = d3_reflect_k(d, n, d . n), tested against the sphere with
 * sphere_intersect.
 *
 * If that test reports a hit at t > 0, the point p_out + t d' lies within r + rho of c (rho the
 * test's rounding, which scene_cull's margin covers). M is an isometry, so M(p_out) + t M(d')
 * lies within r + rho of M(c), and the computed mirror centre c' = c - 2 side n (side = c . n -
 * offset as scene_side forms it) is within rho_c of M(c). Now M(d') = d + e_d, |e_d| <= delta
 * (d' is d mirrored in n, rounded and renormalised, and n is unit to 2^-U_LEN_ERR_SHIFT / 4);
 * M(p_out) = p + f with |f| <= R_EPS_OFFSET (1 + 2^-14) + 2 dist(p, plane) + rounding (M(p) is
 * p moved twice its distance from the plane); p = e + t0 d + g, g v3_along_in's rounding. So
 * the point e + (t0 + t) d of the primary ray's line, ahead of the eye, lies within
 * R = r + rho + rho_c + |f| + |g| + t delta of c', and t0 + t <= D' + R (D' = |c' - e|: both
 * legs point the same way to within delta), so t0 + t <= (D' + r)(1 + 2^-9) + 1 with the bounds
 * below. They hold in every build (fixed with Q2.30 units, float, rt-fixed16's Q16.16 units):
 * delta <= 2^-13 (2^-28 fixed, 2^-21 float; rt-fixed16's rounded d . n and renormalisation
 * 2^-15); dist(p, plane) <= t0 2^-14 + a few steps (t0 times the rounding of d . n and of n's
 * length, plus eye_num's and the division's rounding); rho_c <= 2 |side| 2^-14 + a few steps;
 * and the roundings of coordinates (a Q16.16 step, or float's half ulp, at most 2^-12 inside
 * the scene cube), a dozen at most. So rho_c + |f| + |g| + t delta <= R_EPS_OFFSET +
 * (D' + r + 1)(1 + 2^-9) 2^-12 + |side| 2^-13 + 2^-8, well within reach =
 * 2 R_EPS_OFFSET + 2^-7 + (D' + r + 2 |side|) 2^-10, and rho within scene_cull's margin
 * (2^-10 + (D' + r) 2^-14: the test runs from p_out, within D' + r of c). The direction d then
 * lies in the cone scene_cull derives for a sphere at c' of radius r + reach seen from the eye
 * (its `cone` holds every ray from the eye whose line passes within that radius plus margin of
 * c' ahead of the eye). No bound when c' leaves the scene cube (scene_cull's range), or the
 * eye is within that radius of c' (cone 0). */
real rt_scene_mirror_cone(const rt_scene *s, int pl, int i, vec3 *l)
{
    const rt_object *p = &s->objects[pl], *o = &s->objects[i];
    *l = v3(0, 0, 0);
    if (o->kind != RT_SPHERE)
        return 0;
    real side = scene_side(p, o->center);
    if (r_abs(side) >= r_muli(R_SCENE_MAX, 2))
        return 0; /* the mirror image lies outside the scene cube */
    rt_object m = *o;
    m.center = v3_along(o->center, p->normal, r_neg(r_muli(side, 2)));
    if (!v3_within(m.center, R_SCENE_MAX))
        return 0;
    vec3 lc = v3_sub(m.center, s->cull.eye_at);
    real dist = r_sqrt_w(w_len2(lc));
    real reach = r_add(r_add(r_muli(R_EPS_OFFSET, 2), PREP_SLACK_7),
                       r_shr(r_add(r_add(dist, o->radius), r_muli(r_abs(side), 2)), 10));
    real cone = 0;
    if (scene_cull(&m, s->cull.eye_at, reach, &cone) <= 0 || cone <= 0)
        return 0;
    *l = lc;
    return cone;
}

/* The bounding sphere of the scene's spheres (rt_scene.bound_*), centred in the box of their
 * extents, its radius the largest |c_i - centre| + r_i rounded up. Any sphere test that could
 * report a hit on a sphere inside reports a point within r_i + rho_i of c_i, rho_i its
 * rounding (scene_cull: at most 2^-10 + (D_i + r_i) 2^-14), so within R + rho_i of the centre,
 * and rho_i is within the bound's own margin, as D_i + r_i <= D + R: a ray or segment that
 * scene_cull's test for the bound rejects misses each sphere inside. */
static void scene_bound(rt_scene *s)
{
    uint32_t set = 0;
    vec3 lo = {0, 0, 0}, hi = {0, 0, 0};
    for (int i = 0; i < s->nobjects; i++) {
        const rt_object *o = &s->objects[i];
        if (o->kind != RT_SPHERE)
            continue;
        vec3 a = v3_sub(o->center, v3(o->radius, o->radius, o->radius));
        vec3 b = v3_add(o->center, v3(o->radius, o->radius, o->radius));
        if (!set) {
            lo = a;
            hi = b;
        }
        lo = v3(r_min(lo.x, a.x), r_min(lo.y, a.y), r_min(lo.z, a.z));
        hi = v3(r_max(hi.x, b.x), r_max(hi.y, b.y), r_max(hi.z, b.z));
        set |= (uint32_t)1 << i;
    }
    s->cull.bound_set = 0;
    if ((set & (set - 1)) == 0) /* fewer than two spheres: nothing to gain */
        return;
    vec3 c = v3_add(
        lo,
        v3(r_shr(r_sub(hi.x, lo.x), 1), r_shr(r_sub(hi.y, lo.y), 1), r_shr(r_sub(hi.z, lo.z), 1)));
    real radius = 0;
    for (int i = 0; i < s->nobjects; i++) {
        const rt_object *o = &s->objects[i];
        if (set & ((uint32_t)1 << i))
            radius = r_max(radius, r_add(r_sqrt_w(w_len2(v3_sub(o->center, c))), o->radius));
    }
    /* rounded up: the square root's rounding (half a step fixed, 2^-24 relative float) */
    radius = r_add(r_add(radius, PREP_SLACK_10), r_shr(radius, 14));
    rt_object b = {.kind = RT_SPHERE, .center = c, .radius = radius};
    s->cull.bound_set = set;
    s->cull.bound_center = c;
    s->cull.bound_radius = radius;
    for (int l = 0; l < RT_MAX_LIGHTS; l++)
        s->cull.bound_shadow_cull[l] = l < s->nlights
            ? r_cull(scene_cull(&b, s->lights[l].pos, r_muli(R_EPS_OFFSET, 2), 0))
            : 0;
}

/* The quadrants of light l's shadow rays (rt_scene.cull.shadow_plane, shadow_quad), given each
 * object's cone[] for the light (scene_cull: the sine sn of the half-angle around the direction
 * u_c from the light to the centre outside which its rejection refuses a ray, 0 for none).
 *
 * A ray toward the light along d leaves it backwards along u = -d. Its cone's directions lie on
 * the side u . n > 0 of a plane through the light when u_c . n > sn (the farthest of them is
 * asin(sn) further off u_c, and u_c is less than 90 degrees minus that off n), and then
 * u . n >= sin(u_c . n - sn): with u_c . n > sn + 2^-10 as computed, above 2^-11, far beyond the
 * error of d . n's sign (d3_below: the exact sum in fixed) and of d's and n's lengths (2^-26
 * fixed, 2^-14 rt-fixed16, 2^-20 float). A ray with d . n >= 0 (not d3_below) has u . n below
 * that, so the sphere's rejection refuses it: the sphere is left out of the quadrants on that
 * side (and the same with the signs swapped).
 *
 * The planes contain the direction a from the light to the spheres' bound, at right angles to
 * each other and 45 degrees either side of the plane through a and the vertical (or x, when a
 * is within 26 degrees of the vertical): a cluster seen from a light high above or level with
 * it is cut about evenly (measured: better than the vertical and horizontal planes, no worse
 * than the best of four turns). Once per frame: compiled for size. */
static __attribute__((cold, noinline)) void scene_shadow_quads(rt_scene *s, int l,
                                                               const real cone[])
{
    const dir3 zero = {0, 0, 0};
    dir3 *plane = s->cull.shadow_plane[l];
    uint32_t *quad = s->cull.shadow_quad[l];
    for (int j = 0; j < 2; j++)
        plane[j] = zero;
    for (int q = 0; q < 4; q++)
        quad[q] = 0xFFFFFFFFu;
    vec3 lp = s->lights[l].pos;
    vec3 w = v3_sub(s->cull.bound_center, lp);
    if (!s->cull.bound_set || v3_is_zero(w))
        return;
    dir3 a = d3_norm(w, 0), across = {0, U_ONE, 0};
    unit ay = d3_dot(a, across);
    if (ay > U(0.9) || ay < U(-0.9))
        across = (dir3){U_ONE, 0, 0};
    dir3 p0 = d3_cross(a, across, 0), p1 = d3_cross(a, p0, 0), n[2];
    for (int j = 0; j < 2; j++) {
        dir3 p1s = j ? d3_neg(p1) : p1;
        n[j] = d3_norm(v3_add(v3(u_to_real(p0.x), u_to_real(p0.y), u_to_real(p0.z)),
                              v3(u_to_real(p1s.x), u_to_real(p1s.y), u_to_real(p1s.z))),
                       0);
        plane[j] = n[j];
    }
    for (int i = 0; i < s->nobjects; i++) {
        const rt_object *o = &s->objects[i];
        vec3 c = v3_sub(o->center, lp);
        if (o->kind != RT_SPHERE || cone[i] <= 0 || v3_is_zero(c))
            continue;
        dir3 uc = d3_norm(c, 0);
        real lim = r_add(cone[i], PREP_SLACK_10);
        for (int j = 0; j < 2; j++) {
            real un = u_to_real(d3_dot(uc, n[j]));
            /* u . n > 0 throughout: left out where d . n >= 0 (bit j clear), and conversely */
            int off = un > lim ? 0 : un < r_neg(lim) ? 1 : -1;
            for (int q = 0; q < 4 && off >= 0; q++)
                if (((q >> j) & 1) == off)
                    quad[q] &= ~((uint32_t)1 << i);
        }
    }
}

/* cos(asin(sn)) for a sine sn in [0, 1], rounded down (by 2 steps: the square root's rounding,
 * 1 - sn^2 exact as a wide). */
static real scene_cos_of(real sn)
{
    return r_sub(r_sqrt_w(w_sub(w_sq(R_ONE), w_sq(sn))), r_muli(R_LSB, 2));
}

/* Light l's occluders per object (rt_scene.cull.occ_of), given each object's cone[] for the light
 * (scene_cull: the sine sn of the half-angle around the direction u_c from the light to the
 * centre outside which its shadow-ray rejection refuses a ray, 0 for none).
 *
 * A shadow ray from a point of sphere A (centre c_A, radius r, C_A = c_A - light, D_A = |C_A|)
 * leaves its hit point p or the offset point p_out, within rho = r + delta + 2 R_EPS_OFFSET of
 * c_A: delta bounds a hit point's distance from its surface (docs/numerics.md: 1e-4 fixed, 6e-7
 * times the coordinates float; the sphere test's rounding grows as 2^-14 of the distances in
 * rt-fixed16), taken as 2^-8 + 4096 * 2^(3 - U_LEN_ERR_SHIFT) (1/8 in fixed and float, 2 in
 * rt-fixed16). Its direction u = -d (from the light toward the point, as rt_light_reach forms d)
 * is then within asin(rho / D_A) of C_A's, plus the rounding of d (2^-26 fixed, 2^-20 float,
 * 2^-13 rt-fixed16). Another sphere B whose cone (sine sB around C_B) is further off C_A than
 * that, angle(C_A, C_B) > asin(rho / D_A) + asin(sB) + 2^-9, rejects every such ray: by the
 * triangle inequality of angles, u is then further than asin(sB) off C_B. As cosines (both
 * angles at most pi / 2, their sum at most pi; cos is 1-Lipschitz), times D_A D_B: C_A . C_B <
 * D_B (sqrt(D_A^2 - rho^2) cB - rho sB - D_A 2^-9 - 4 LSB), cB = cos(asin(sB)); the dot product
 * and the squares exact (wide), the square roots rounded down, the 4 LSB holding the rounding of
 * the products and of D_B: no division, no normalisation. And a sphere B wholly farther from
 * the light than the segment reaches, D_B - r_B - m > D_A + rho, m = 2^-10 + (D_B + r_B) 2^-12
 * (the sphere test's rounding, scene_cull's margin four times over), has no point the test could
 * find within the segment, which runs from p_out (within D_A + rho of the light: its distance
 * from the light only falls along it) toward the light. Either way B is left out of
 * occ_of[l][A], the same answers (test_shapes: test_shadow_pairs). Every object's own bit is
 * left out of its set (a convex surface never shadows its lit side; rt_light_reach adds it back
 * for a point seen from inside); a plane's own set is the light's occluders but itself.
 *
 * A plane P (stored unit normal N) is left out of sphere A's set (RT_PLANE_CULL) when the
 * light is above A's centre, w = -(C_A . N) >= 0, D_A < 128 and H_u (r + R_EPS_OFFSET) <
 * (h - 2 delta) D_A: h is the centre's height above P, H_u >= H = sqrt(D_A^2 - w^2) the
 * light's distance from the normal through c_A (2 LSB added to the rounded root). Then h >
 * 2 delta, and the light is over 2 delta above P. If r <= delta, A clears P by more than
 * delta: every p_out of A lies above P. Otherwise a point lit from outside (outward normal n,
 * n . l > 0 as rt_light_reach casts) has n . (L - c_A) > r - delta > 0 (p within delta of
 * the surface, d's rounding times D_A far below delta). With a = n . N, n . (L - c_A) <= a w +
 * sqrt(1 - a^2) H, increasing in a for a < 0 (w >= 0), and <= 0 at a = -a0, a0 = (h - delta) /
 * (r + R_EPS_OFFSET), since H <= a0 D_A gives sqrt(1 - a0^2) H <= a0 w. So every lit point has
 * a > -a0, and p_out = p + R_EPS_OFFSET n is above P by more than h - a0 (r + R_EPS_OFFSET)
 * - (its error) > 0; the segment's end, within 2 R_EPS_OFFSET plus d's rounding of the light
 * (from p_out, or aimed from it for near lights), is above P too: the segment never reaches P,
 * and the plane test (num < 0, and -num < tmax |den| to within a few LSB) misses. The second
 * delta leaves delta D_A of slack in the comparison, above the products' rounding and H's
 * error from w's (at most sqrt(2 D_A dw), dw a few LSB plus D_A times the normal's length
 * error: below delta for D_A < 128 in each build). A point seen from inside (p_out inside A,
 * which may touch P) gets the planes back from rt_light_reach. test_shapes: test_plane_pairs.
 * Distances within the scene (below 30000) and sines: the sums are in range (r_add_in). Once per
 * frame: compiled for size. */
static __attribute__((cold, noinline)) void scene_shadow_pairs(rt_scene *s, int l,
                                                               const real cone[])
{
    const real delta = scene_delta();
    const vec3 lp = s->lights[l].pos;
    for (int a = 0; a < s->nobjects; a++) {
        const rt_object *oa = &s->objects[a];
        uint32_t occ = s->occluders[l] & ~((uint32_t)1 << a);
        vec3 va = v3_sub_in(oa->center, lp); /* positions in the scene cube */
        wide da2 = w_len2(va);
        real da = r_sqrt_w(da2), rho = r_add_in(oa->radius, delta);
        /* (D_A - rho above D_A 2^-8: D_A^2 - rho^2 clearly positive in either build) */
        if (oa->kind == RT_SPHERE && r_add_in(rho, r_shr(da, 8)) < da) {
            /* D_A cos(asin(rho / D_A)), rounded down; the segment's reach from the light */
            real dca = r_add_in(r_sqrt_w(w_sub(da2, w_sq(rho))), r_neg_in(r_muli(R_LSB, 2)));
            real reach = r_add_in(da, rho), margin = r_add_in(r_shr(da, 9), r_muli(R_LSB, 4));
            for (int b = 0; b < s->nobjects; b++) {
                const rt_object *ob = &s->objects[b];
                vec3 vb = v3_sub_in(ob->center, lp);
                if (b == a || ob->kind != RT_SPHERE) {
#if RT_PLANE_CULL
                    /* a plane below A, the light above both (see above) */
                    real wn = r_neg_in(v3_dot_d_in(va, ob->normal));
                    real k = r_add_in(scene_side(ob, oa->center), r_neg_in(r_muli(delta, 2)));
                    real hu = r_add_in(r_sqrt_w(w_sub(da2, w_sq(wn))), r_muli(R_LSB, 2));
                    if (b != a && wn >= 0 && da < R(128.0) &&
                        r_mul_in(hu, r_add_in(oa->radius, R_EPS_OFFSET)) < r_mul_in(k, da))
                        occ &= ~((uint32_t)1 << b);
#endif
                    continue;
                }
                real db = r_sqrt_w(w_len2(vb)), sb = cone[b];
                real m = r_add_in(PREP_SLACK_10, r_shr(r_add_in(db, ob->radius), 12));
                wide dot = w_add(w_add(w_mul(va.x, vb.x), w_mul(va.y, vb.y)), w_mul(va.z, vb.z));
                /* beyond the segment's reach, or its cone apart from the receiver's */
                if (r_add_in(db, r_neg_in(r_add_in(ob->radius, m))) > reach ||
                    (sb > 0 &&
                     dot < w_mul(r_add_in(r_add_in(r_mul_in(dca, scene_cos_of(sb)),
                                                   r_neg_in(r_mul_in(rho, sb))),
                                          r_neg_in(margin)),
                                 db)))
                    occ &= ~((uint32_t)1 << b);
            }
        }
        s->cull.occ_of[l][a] = occ;
    }
}

/* The secondary rays' candidate sets (rt_scene.cull.ray_oct, ray_in), for rays from hit points of
 * each sphere A (centre c_A, radius r_A).
 *
 * trace_secondary casts them from p_out = p + R_EPS_OFFSET n or p_in = p - R_EPS_OFFSET n, p a
 * hit point on A: within rho = r_A + delta of c_A, delta as scene_shadow_pairs takes it (a hit
 * point's distance from its surface, 1/8 in fixed and float, 2 in rt-fixed16, plus 2
 * R_EPS_OFFSET). If sphere B's test (as rt_nearest_set forms it) reports a hit at t > 0 for
 * such a ray (origin o, direction d as stored), the point h = o + t d lies within r_B + m of
 * c_B, m = 2^-10 + (D + r_B) 2^-12 with D >= |c_B - o| (scene_cull's margin four times over, as
 * scene_shadow_pairs takes it), D taken as |V|_1 + rho, V = c_B - c_A (the sum of the
 * magnitudes is at least the length: no square root). So with R = rho + r_B + m + 2^-8 (the
 * last term for the rounding of V and R themselves in float; fixed forms V exactly; every sum is
 * of in-scene distances, below 30000: r_add_in):
 *
 * ray_oct: t d_k = h_k - o_k >= V_k - (r_B + m) - rho, so V_k > R gives d_k > 0 (t > 0): a ray
 * whose component k is negative (octant bit k set, rt_octant) never gets a hit on B, and B is
 * left out of those octants; V_k < -R likewise for the octants with d_k >= 0 (bit k clear). Only
 * spheres are left out, only where their test cannot report a hit: the same results for any ray
 * from A. (Planes stay: the intro's spheres rest on the floor, so p_out can lie beneath it.)
 *
 * ray_in: if A's own test reports a hit at t_A (its point within r_A + m_A of c_A, m_A =
 * 2^-10 + (rho + r_A) 2^-12), the ray's points for t in [0, t_A] lie within rho + m_A of c_A
 * (o and that point do: the ball is convex). With |V| > R + m_A (as squares, wide), no point of
 * B's within r_B + m of c_B is among them: B's test, if it reports a hit, reports one beyond t_A.
 * B is left out only when it comes after every plane in the objects' order: the objects before
 * the last plane are then all tested, with the same tmax at each, and after it rt_nearest_set
 * keeps the strictly nearest sphere hit (ties to the first), so where the search without B
 * finds A it is the search's answer with B (trace_ray searches again otherwise).
 *
 * dark_inside, dark_r (rt_light_reach's shortcut): a point p of A seen from inside (its normal
 * n turned inward) with p_out = p + R_EPS_OFFSET n, |p_out - c_A| < r - mi exactly (dark_r = r -
 * mi, mi = 2^-10 + r 2^-(U_LEN_ERR_SHIFT - 4): r 2^-14 fixed and float, r 2^-10 rt-fixed16),
 * under a light L at D = |L - c_A| > r + ml + 2 LSB (ml = 2 R_EPS_OFFSET + 2^-6 + (D + r)
 * 2^-(U_LEN_ERR_SHIFT - 8)), A among its occluders: rt_light_reach returns 0 whenever it gets
 * as far as the shadow ray (or earlier, n . l <= 0). The ray's occluders hold A (seen from
 * inside, rt_light_reach adds A back); the bound's, the quadrants' and A's own rejections
 * refuse only segments A's test would miss, so the ray is blocked if A's test (sphere_blocks)
 * reports the segment from p_out along d (unit to 2^-U_LEN_ERR_SHIFT / 4, toward L from p, or
 * from p_out for a near light) of length dist - R_EPS_OFFSET (dist within a step of |L - p|, or
 * |L - p_out|, above R_EPS_OFFSET as L is far outside). With l = c - p_out, |l| < r - mi: tca <=
 * |l| < r passes both first rejections; |perp|^2 = |l|^2 - tca^2 within a few steps times r
 * (d's length error times r, and each component's rounding), so a = r^2 - |perp|^2 exceeds
 * tca^2 by at least 2 r mi - mi^2 less that, and thc - |tca| >= mi / 2 - a few steps: the near
 * hit is negative, the far one tca + thc positive. The segment's end lies within 2 R_EPS_OFFSET
 * plus d's error times dist ((D + r) 2^-(U_LEN_ERR_SHIFT - 2)) of L, so outside A by more than
 * 2^-6 + (D + r) 2^-(U_LEN_ERR_SHIFT - 4): the exit point comes that far before it, and the far
 * hit as formed is off the exit by thc's error, a's error over 2 thc with thc >= sqrt(r mi),
 * plus tca's: within ml's 2^-6 + (D + r) 2^-(U_LEN_ERR_SHIFT - 8) in every build (fixed: a
 * few steps times r over sqrt(r^2 2^-14), below 2^-8; float: r^2 2^-22 over the same, below
 * 2^-8 + r 2^-12; rt-fixed16: r^2 2^-14 over sqrt(r^2 2^-10), r 2^-9): so within the segment,
 * and A blocks it. test_shapes: test_dark_inside.
 * Once per frame: compiled for size. */
#if defined(__arm__) && !defined(__thumb2__)
__attribute__((target("thumb"))) /* the ARM926 image: Thumb, as ARM_COLD_SRCS (Makefile) */
#endif
static __attribute__((cold, noinline)) void
scene_ray_sets(rt_scene *s)
{
    const real delta = scene_delta();
    int last_plane = -1;
    for (int l = 0; l < RT_MAX_LIGHTS; l++)
        s->cull.dark_inside[l] = 0;
    for (int i = 0; i < RT_MAX_OBJECTS; i++) {
        s->cull.dark_r[i] = 0;
        /* a plane's rays mirrored off its front: every object but itself (trace_secondary) */
        int plane = i < s->nobjects && s->objects[i].kind == RT_PLANE;
        for (int q = 0; q < 8; q++)
            s->cull.ray_oct[i][q] = plane ? ~((uint32_t)1 << i) : 0xFFFFFFFFu;
        s->cull.ray_in[i] = 0xFFFFFFFFu;
        if (plane)
            last_plane = i;
    }
    for (int a = 0; a < s->nobjects; a++) {
        const rt_object *oa = &s->objects[a];
        if (oa->kind != RT_SPHERE)
            continue;
        real rho = r_add_in(oa->radius, delta);
        real ma = r_add_in(PREP_SLACK_10, r_shr(r_add_in(rho, oa->radius), 12));
        /* dark_r, dark_inside (the proof above) */
        real mi = r_add_in(PREP_SLACK_10, r_shr(oa->radius, U_LEN_ERR_SHIFT - 4));
        s->cull.dark_r[a] = oa->radius > mi ? r_add_in(oa->radius, r_neg_in(mi)) : 0;
        for (int l = 0; l < s->nlights; l++) {
            real dl = r_sqrt_w(w_len2(v3_sub_in(s->lights[l].pos, oa->center)));
            real ml = r_add_in(r_add_in(r_muli(R_EPS_OFFSET, 2), PREP_SLACK_6),
                               r_shr(r_add_in(dl, oa->radius), U_LEN_ERR_SHIFT - 8));
            if ((s->occluders[l] >> a & 1) && s->cull.dark_r[a] > 0 &&
                dl > r_add_in(r_add_in(oa->radius, ml), r_muli(R_LSB, 2)))
                s->cull.dark_inside[l] |= (uint32_t)1 << a;
        }
        for (int b = 0; b < s->nobjects; b++) {
            const rt_object *ob = &s->objects[b];
            if (b == a || ob->kind != RT_SPHERE)
                continue;
            vec3 v = v3_sub_in(ob->center, oa->center);
            const real vk[3] = {v.x, v.y, v.z};
            real l1 = 0;
            for (int k = 0; k < 3; k++)
                l1 = r_add_in(l1, vk[k] < 0 ? r_neg_in(vk[k]) : vk[k]);
            real m = r_add_in(PREP_SLACK_10, r_shr(r_add_in(r_add_in(l1, rho), ob->radius), 12));
            real reach = r_add_in(r_add_in(r_add_in(rho, ob->radius), m), PREP_SLACK_8);
            /* the octants B stays in: bit q of `keep` (0xAA, 0xCC, 0xF0: those with bit k set) */
            unsigned keep = 0xFF;
            for (int k = 0; k < 3; k++) {
                unsigned with_k = k == 0 ? 0xAAu : k == 1 ? 0xCCu : 0xF0u;
                if (vk[k] > reach)
                    keep &= ~with_k;
                else if (vk[k] < r_neg_in(reach))
                    keep &= with_k;
            }
            uint32_t bit = (uint32_t)1 << b;
            for (int q = 0; q < 8; q++)
                if (!(keep >> q & 1))
                    s->cull.ray_oct[a][q] &= ~bit;
            if (b > last_plane && w_len2(v) > w_sq(r_add_in(reach, ma)))
                s->cull.ray_in[a] &= ~bit;
        }
    }
}

/* The largest v in [0, 1] with u_pow(v, h) == 0, by bisection: u_pow is non-decreasing in v
 * (a product of rounded products of non-negative values), 0 at 0 and 1 at 1, so every v up to
 * the result gives 0 and the highlight term can be skipped there, exactly. */
static unit scene_spec_zero(unsigned h)
{
    unit lo = 0, hi = U_ONE;
    for (;;) {
        unit mid = u_add(lo, u_divi(u_add(hi, u_neg(lo)), 2));
        if (mid == lo || mid == hi)
            return lo;
        if (u_pow(mid, h) == 0)
            lo = mid;
        else
            hi = mid;
    }
}

void rt_scene_prepare(rt_scene *s)
{
    for (int i = 0; i < s->nobjects; i++) {
        rt_object *o = &s->objects[i];
        if (o->kind == RT_SPHERE) {
            o->radius2 = w_sq(o->radius);
            o->behind = rt_sphere_behind(o->radius);
            o->inv_radius = r_inv_len(o->radius);
        } else {
            /* A plane is given by any normal vector and the offset along the unit normal. A
             * normal animated through zero has no direction at that instant: the plane is
             * then no plane at all, and a zero normal makes every ray miss it (parallel). */
            o->normal = (dir3){0, 0, 0};
            if (!v3_is_zero(o->axis))
                o->normal = d3_norm(o->axis, 0);
        }
    }
    for (int i = 0; i < s->nmaterials; i++) {
        rt_material *m = &s->materials[i];
        m->ior_inv = r_div(R_ONE, m->ior);
        m->spec_zero = m->specular > 0 ? scene_spec_zero(m->shininess) : 0;
        m->ambient_term = c3_scale_p(c3_mul_p(m->diffuse, s->ambient), m->ambient);
        /* A checkerboard whose colours are equal (the intro's floor until its second colour is
         * keyed away) is its diffuse colour and has no edges: its cells are not told apart, so
         * subsampling does not split squares along them. */
        m->tex.active = m->tex.kind != RT_TEX_NONE &&
            (m->tex.kind != RT_TEX_CHECKER || m->tex.color2.x != m->diffuse.x ||
             m->tex.color2.y != m->diffuse.y || m->tex.color2.z != m->diffuse.z);
    }
    s->cull.near_lights = 0;
    real cone[RT_MAX_LIGHTS][RT_MAX_OBJECTS];
    for (int l = 0; l < s->nlights; l++)
        for (int i = 0; i < s->nobjects; i++) {
            const rt_object *o = &s->objects[i];
            if (scene_light_near(o, s->lights[l].pos))
                s->cull.near_lights |= 1u << l;
            cone[l][i] = 0;
            s->cull.shadow_cull[l][i] = o->kind == RT_SPHERE
                ? r_cull(scene_cull(o, s->lights[l].pos, r_muli(R_EPS_OFFSET, 2), &cone[l][i]))
                : 0;
        }
    s->cull.eye_at = s->camera.eye;
    s->cull.plane_set = 0;
    for (int i = 0; i < s->nobjects; i++) {
        const rt_object *o = &s->objects[i];
        s->cull.eye_l[i] = v3_sub_in(o->center, s->cull.eye_at); /* as the sphere test forms it */
        s->cull.eye_cone[i] = 0;
        s->cull.eye_cull[i] =
            o->kind == RT_SPHERE ? scene_cull(o, s->cull.eye_at, 0, &s->cull.eye_cone[i]) : 0;
        /* a plane's signed distance from the eye, as plane_intersect forms it */
        if (o->kind == RT_PLANE)
            s->cull.plane_set |= (uint32_t)1 << i;
        s->cull.eye_num[i] =
            o->kind == RT_PLANE ? r_sub(o->offset, v3_dot_d(s->cull.eye_at, o->normal)) : 0;
    }
    scene_bound(s);
    for (int l = 0; RT_SHADOW_SETS && l < s->nlights; l++)
        scene_shadow_quads(s, l, cone[l]);
    scene_derive_effects(s);
    for (int l = 0; RT_SHADOW_SETS && l < s->nlights; l++)
        scene_shadow_pairs(s, l, cone[l]);
    if (RT_RAY_SETS)
        scene_ray_sets(s);
}
