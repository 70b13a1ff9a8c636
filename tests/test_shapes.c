/* test_shapes.c: ray-sphere and ray-plane hits and misses, and the per-sample record, against double. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>

#include "rt_local.h"

#if REAL_FIXED
static double to_d(real r) { return r / 65536.0; }
static real from_d(double x) { return (real)llround(x * 65536.0); }
/* distances along a ray: a few Q16.16 steps */
#define T_TOL 1e-4
#else
static double to_d(real r) { return r; }
static real from_d(double x) { return (real)x; }
#define T_TOL 1e-4
#endif

static vec3 vd(double x, double y, double z) { return v3(from_d(x), from_d(y), from_d(z)); }

static dir3 dirv(double x, double y, double z) { return d3_norm(vd(x, y, z), 0); }

static rt_object sphere(double x, double y, double z, double r)
{
    rt_object o = {.kind = RT_SPHERE};
    o.center = vd(x, y, z);
    o.radius = from_d(r);
    o.radius2 = w_sq(o.radius);
    o.behind = rt_sphere_behind(o.radius);
    return o;
}

static rt_object plane(double nx, double ny, double nz, double offset)
{
    rt_object o = {.kind = RT_PLANE};
    o.axis = vd(nx, ny, nz);
    o.normal = d3_norm(o.axis, 0);
    o.offset = from_d(offset);
    return o;
}

/* Hit distance in double of the ray (o, d) with a sphere, or -1. */
static double sphere_oracle(double ox, double oy, double oz, double dx, double dy, double dz,
                            double cx, double cy, double cz, double r)
{
    double n = sqrt(dx * dx + dy * dy + dz * dz);
    dx /= n, dy /= n, dz /= n;
    double lx = cx - ox, ly = cy - oy, lz = cz - oz;
    double tca = lx * dx + ly * dy + lz * dz;
    double px = lx - tca * dx, py = ly - tca * dy, pz = lz - tca * dz;
    double d2 = px * px + py * py + pz * pz;
    if (d2 > r * r)
        return -1;
    double thc = sqrt(r * r - d2);
    if (tca - thc > 0)
        return tca - thc;
    if (tca + thc > 0)
        return tca + thc;
    return -1;
}

static int hit(const rt_object *o, vec3 org, dir3 d, real tmax, double *t)
{
    real tr;
    int h = rt_intersect(o, org, d, tmax, &tr);
    *t = h ? to_d(tr) : -1;
    return h;
}

static void test_sphere_cases(void **state)
{
    (void)state;
    rt_object s = sphere(0, 0, -10, 2);
    double t;
    fx_events_reset();
    /* straight on: t = 8 */
    assert_true(hit(&s, vd(0, 0, 0), dirv(0, 0, -1), R_T_MAX, &t));
    assert_true(fabs(t - 8.0) < T_TOL);
    /* passing beside: miss */
    assert_false(hit(&s, vd(2.5, 0, 0), dirv(0, 0, -1), R_T_MAX, &t));
    /* sphere behind the origin: miss (the cheap test) */
    assert_false(hit(&s, vd(0, 0, 0), dirv(0, 0, 1), R_T_MAX, &t));
    /* origin inside: the far side, t = r */
    assert_true(hit(&s, vd(0, 0, -10), dirv(1, 0, 0), R_T_MAX, &t));
    assert_true(fabs(t - 2.0) < T_TOL);
    /* beyond tmax: miss; within: hit */
    assert_false(hit(&s, vd(0, 0, 0), dirv(0, 0, -1), R(7.9), &t));
    assert_true(hit(&s, vd(0, 0, 0), dirv(0, 0, -1), R(8.1), &t));
    /* grazing: 1e-3 inside the silhouette hits, 1e-3 outside misses */
    assert_true(hit(&s, vd(1.999, 0, 0), dirv(0, 0, -1), R_T_MAX, &t));
    assert_true(fabs(t - sphere_oracle(1.999, 0, 0, 0, 0, -1, 0, 0, -10, 2)) < 2e-3);
    assert_false(hit(&s, vd(2.001, 0, 0), dirv(0, 0, -1), R_T_MAX, &t));
    /* far away: a radius-2 sphere 3000 units down a diagonal */
    rt_object far = sphere(1800, 1200, -2000, 2);
    assert_true(hit(&far, vd(0, 0, 0), dirv(1800, 1200, -2000), R_T_MAX, &t));
    double want = sphere_oracle(0, 0, 0, 1800, 1200, -2000, 1800, 1200, -2000, 2);
    assert_true(fabs(t - want) < 1e-3);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW] + fx_event_count[FX_EV_DOMAIN], 0);
}

static void test_plane_cases(void **state)
{
    (void)state;
    rt_object p = plane(0, 1, 0, 0);
    double t;
    fx_events_reset();
    assert_true(hit(&p, vd(0, 5, 0), dirv(0, -1, 0), R_T_MAX, &t));
    assert_true(fabs(t - 5.0) < T_TOL);
    /* oblique: 45 degrees down from height 5 -> t = 5 sqrt 2 */
    assert_true(hit(&p, vd(0, 5, 0), dirv(1, -1, 0), R_T_MAX, &t));
    assert_true(fabs(t - 5.0 * sqrt(2.0)) < T_TOL);
    /* away from the plane, and parallel to it: miss */
    assert_false(hit(&p, vd(0, 5, 0), dirv(0, 1, 0), R_T_MAX, &t));
    assert_false(hit(&p, vd(0, 5, 0), dirv(1, 0, 0), R_T_MAX, &t));
    /* nearly parallel: the hit lies beyond any scene distance, so it is a miss, not an
     * overflow */
    assert_false(hit(&p, vd(0, 5, 0), dirv(1, -0.00005, 0), R_T_MAX, &t));
    /* shallow but within range: t = 5 / sin(angle), from the direction actually used */
    dir3 shallow = dirv(1, -0.01, 0);
#if REAL_FIXED
    double sin_angle = -shallow.y / 1073741824.0;
#else
    double sin_angle = -shallow.y;
#endif
    assert_true(hit(&p, vd(0, 5, 0), shallow, R_T_MAX, &t));
    if (fabs(t - 5.0 / sin_angle) >= 1e-3)
        fail_msg("shallow plane hit at %.6f, want %.6f", t, 5.0 / sin_angle);
    /* tilted plane through (0, 0, -10) facing the origin */
    rt_object q = plane(0, 0, 1, -10);
    assert_true(hit(&q, vd(3, 2, 0), dirv(0, 0, -1), R_T_MAX, &t));
    assert_true(fabs(t - 10.0) < T_TOL);
    /* from behind the plane the hit still counts (planes are two-sided) */
    assert_true(hit(&q, vd(0, 0, -20), dirv(0, 0, 1), R_T_MAX, &t));
    assert_true(fabs(t - 10.0) < T_TOL);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW] + fx_event_count[FX_EV_DOMAIN], 0);
}

/* Deterministic pseudo-random numbers in [lo, hi). */
static uint32_t rng_state = 12345;
static double rnd(double lo, double hi)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return lo + (hi - lo) * ((rng_state >> 8) / 16777216.0);
}

static void test_sphere_random(void **state)
{
    (void)state;
    int disagree = 0, n = 20000;
    double worst_t = 0;
    fx_events_reset();
    for (int i = 0; i < n; i++) {
        double cx = rnd(-100, 100), cy = rnd(-100, 100), cz = rnd(-100, 100), r = rnd(0.05, 20);
        double ox = rnd(-100, 100), oy = rnd(-100, 100), oz = rnd(-100, 100);
        /* aim near the sphere so that about half the rays hit */
        double dx = cx + rnd(-1.5, 1.5) * r - ox, dy = cy + rnd(-1.5, 1.5) * r - oy,
               dz = cz + rnd(-1.5, 1.5) * r - oz;
        rt_object s = sphere(cx, cy, cz, r);
        /* the oracle uses the build's own quantised inputs */
        double qcx = to_d(s.center.x), qcy = to_d(s.center.y), qcz = to_d(s.center.z);
        double qr = to_d(s.radius);
        vec3 org = vd(ox, oy, oz);
        double qox = to_d(org.x), qoy = to_d(org.y), qoz = to_d(org.z);
        double want = sphere_oracle(qox, qoy, qoz, dx, dy, dz, qcx, qcy, qcz, qr);
        double t;
        int h = hit(&s, org, dirv(dx, dy, dz), R_T_MAX, &t);
        if (h != (want > 0)) {
            /* allowed only within a thin band around tangency */
            double n2 = sqrt(dx * dx + dy * dy + dz * dz);
            double lx = qcx - qox, ly = qcy - qoy, lz = qcz - qoz;
            double tca = (lx * dx + ly * dy + lz * dz) / n2;
            double perp = sqrt(fabs(lx * lx + ly * ly + lz * lz - tca * tca));
            if (fabs(perp - qr) > 1e-3)
                fail_msg("hit/miss disagree far from tangency: perp %g r %g", perp, qr);
            disagree++;
            continue;
        }
        if (h) {
            /* distance error grows near tangency (sqrt of a small discriminant) */
            double err = fabs(t - want);
            double allowed = 2e-4 + 4e-3 * sqrt(r);
            if (err > allowed)
                fail_msg("t error %g > %g (t %g, r %g)", err, allowed, want, qr);
            if (err > worst_t)
                worst_t = err;
        }
    }
    print_message("sphere random: %d rays, %d tangent disagreements, worst t error %.3g\n", n,
                  disagree, worst_t);
    assert_true(disagree < n / 1000);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
}

/* A shadow segment as trace.c builds it, passing by the point q at distance rq from c in the
 * direction u (not unit), as seen from the scene's light 0: a surface point p beyond q, a normal
 * facing the light tilted at random, p lifted R_EPS_OFFSET along it (p_out), aimed from p (or,
 * `lifted`, from p_out, as for a light near a surface) and stopped R_EPS_OFFSET short of the
 * light. 0 where there is no such segment (p outside the scene cube or at the light, the normal
 * turned away, the light within R_EPS_OFFSET). */
static int shadow_segment(const rt_scene *s, double cx, double cy, double cz, double ux, double uy,
                          double uz, double rq, int lifted, vec3 *p_out, dir3 *l, real *seg)
{
    const vec3 lp = s->lights[0].pos;
    double lx = to_d(lp.x), ly = to_d(lp.y), lz = to_d(lp.z);
    double un = sqrt(ux * ux + uy * uy + uz * uz) + 1e-9;
    double qx = cx + ux / un * rq, qy = cy + uy / un * rq, qz = cz + uz / un * rq;
    double k = rnd(1.02, 3);
    vec3 p = vd(lx + (qx - lx) * k, ly + (qy - ly) * k, lz + (qz - lz) * k);
    if (!v3_within(p, R_SCENE_MAX))
        return 0;
    vec3 to_light = v3_sub(lp, p);
    if (v3_is_zero(to_light))
        return 0;
    real dist;
    *l = d3_norm(to_light, &dist);
    /* a surface normal facing the light, tilted at random */
    dir3 nrm = d3_norm(
        vd(to_d(l->x) + rnd(-0.9, 0.9), to_d(l->y) + rnd(-0.9, 0.9), to_d(l->z) + rnd(-0.9, 0.9)),
        0);
    if (d3_dot(nrm, *l) <= 0)
        return 0;
    *p_out = v3_along(p, nrm, R_EPS_OFFSET);
    if (lifted) {
        vec3 t2 = v3_sub(lp, *p_out);
        if (v3_is_zero(t2))
            return 0;
        *l = d3_norm(t2, &dist);
    }
    if (dist <= R_EPS_OFFSET)
        return 0;
    *seg = r_sub(dist, R_EPS_OFFSET);
    return 1;
}

/* The shadow rays' quick rejection (rt_scene.cull.shadow_cull) never changes a result: shadow
 * segments built as trace.c builds them (from a surface point lifted R_EPS_OFFSET, aimed from
 * the point or from the lifted point, stopped R_EPS_OFFSET short of the light) that pass within
 * a hair of a sphere give the same answer through rt_occluded as through the sphere test
 * alone, and the rejection does fire on many of them, near misses included. */
static void test_shadow_cull(void **state)
{
    (void)state;
    static rt_scene s;
    int n = 200000, culled = 0, near_culled = 0, hits = 0;
    fx_events_reset();
    for (int i = 0; i < n; i++) {
        double span = i % 10 == 0 ? 2000.0 : 20.0; /* now and then a scene far out */
        double r = i % 10 == 0 ? rnd(0.05, 100) : rnd(0.05, 5);
        s = (rt_scene){0};
        s.nobjects = 1;
        s.objects[0] = sphere(rnd(-span, span), rnd(-span, span), rnd(-span, span), r);
        s.nmaterials = 1;
        s.materials[0].ior = R_ONE;
        s.nlights = 1;
        double lx = rnd(-span, span), ly = rnd(-span, span), lz = rnd(-span, span);
        s.lights[0].pos = vd(lx, ly, lz);
        rt_scene_prepare(&s);
        const rt_object *o = &s.objects[0];
        /* a point q at about the radius from the centre; the surface point p lies beyond q as
         * seen from the light, so that the shadow segment passes by q */
        double cx = to_d(o->center.x), cy = to_d(o->center.y), cz = to_d(o->center.z);
        double ux = rnd(-1, 1), uy = rnd(-1, 1), uz = rnd(-1, 1);
        double rq = r * (1 + rnd(-0.02, 0.05)) + rnd(-0.005, 0.01);
        if (i & 2) {
            /* q off the centre at right angles to the light: the segment grazes the sphere,
             * passing a few thousandths outside or inside it, where the rejection starts */
            double ax = cx - lx, ay = cy - ly, az = cz - lz;
            double a2 = ax * ax + ay * ay + az * az + 1e-30,
                   ua = (ux * ax + uy * ay + uz * az) / a2;
            ux -= ua * ax, uy -= ua * ay, uz -= ua * az;
            rq = r + rnd(-0.002, 0.012) + r * rnd(0, 0.002);
        }
        vec3 p_out;
        dir3 l;
        real seg, t;
        if (!shadow_segment(&s, cx, cy, cz, ux, uy, uz, rq, i & 1, &p_out, &l, &seg))
            continue;
        int want = rt_intersect(o, p_out, l, seg, &t);
        rt_stats st = {0};
        int got = rt_occluded(&s, &st, 0, 1, &p_out, &l, seg);
        if (got != want)
            fail_msg("rt_occluded %d, sphere test %d (case %d, r %g, q at %g of the centre)", got,
                     want, i, r, rq);
        hits += want;
        real cd = v3_dot_d_in(v3_sub_in(o->center, s.lights[0].pos), l);
        rcull kc = s.cull.shadow_cull[0][0];
        if (kc != 0 && r_cull_rejects(cd, kc)) {
            culled++;
            if (rq - r < 0.012 + r * 0.002)
                near_culled++;
        }
    }
    print_message("shadow cull: %d segments, %d blocked, %d rejected early (%d of them passing "
                  "within 0.012 + 0.2%% of the radius)\n",
                  n, hits, culled, near_culled);
    assert_true(hits > n / 10);
    assert_true(culled > n / 20);
    assert_true(near_culled > n / 100);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
}

/* The sphere test's cut for spheres behind the ray (rt_object.behind) never changes a hit:
 * secondary rays from points near a sphere's surface, inside and outside it (within 0.002 +
 * 0.1% of the radius, at scales from 0.01 to 500 and up to 3000 from the origin), leaving
 * roughly outward, find through rt_nearest_but the same object at the same distance as with
 * the cut switched off (behind = -R_MAX), and the cut decides many of them, near misses
 * included. A cut 2^-10 too close to -r fails here (origins just inside, aimed out). */
static void test_behind_cut(void **state)
{
    (void)state;
    static rt_scene s, plain;
    int n = 200000, cut = 0, near_cut = 0, hits = 0;
    fx_events_reset();
    for (int i = 0; i < n; i++) {
        double size = i % 7 == 0 ? rnd(20, 500) : (i % 7 == 1 ? rnd(0.01, 0.1) : rnd(0.2, 3));
        double span = i % 5 == 0 ? 3000.0 : 10.0;
        s = (rt_scene){0};
        s.nobjects = 1 + i % 3;
        double ox = rnd(-span, span), oy = rnd(-span, span), oz = rnd(-span, span);
        for (int j = 0; j < s.nobjects; j++)
            s.objects[j] = sphere(ox + rnd(-3, 3) * size, oy + rnd(-3, 3) * size,
                                  oz + rnd(-3, 3) * size, rnd(0.3, 1) * size);
        s.nmaterials = 1;
        s.materials[0].ior = R_ONE;
        rt_scene_prepare(&s);
        plain = s;
        for (int j = 0; j < s.nobjects; j++)
            plain.objects[j].behind = r_neg(R_MAX);
        /* an origin near the surface of sphere k, along a random u from its centre */
        const rt_object *o = &s.objects[i % s.nobjects];
        double cx = to_d(o->center.x), cy = to_d(o->center.y), cz = to_d(o->center.z),
               r = to_d(o->radius);
        double ux = rnd(-1, 1), uy = rnd(-1, 1), uz = rnd(-1, 1);
        double un = sqrt(ux * ux + uy * uy + uz * uz) + 1e-9;
        ux /= un, uy /= un, uz /= un;
        double rq = r + rnd(-0.002, 0.002) + r * rnd(-0.001, 0.001);
        vec3 org = vd(cx + ux * rq, cy + uy * rq, cz + uz * rq);
        double j = i % 4 == 0 ? 1.5 : 0.05;
        dir3 d = dirv(ux + rnd(-j, j), uy + rnd(-j, j), uz + rnd(-j, j));
        real t_got, t_want;
        int got = rt_nearest_but(&s, org, d, R_T_MAX, -1, &t_got);
        int want = rt_nearest_but(&plain, org, d, R_T_MAX, -1, &t_want);
        if (got != want || t_got != t_want)
            fail_msg("with the cut object %d at %g, without %d at %g (case %d)", got, to_d(t_got),
                     want, to_d(t_want), i);
        hits += want >= 0;
        real tca = v3_dot_d_in(v3_sub_in(o->center, org), d);
        if (tca < o->behind) {
            cut++;
            if (r_abs(r_sub(tca, o->behind)) < from_d(0.001 + r * 0.0005))
                near_cut++;
        }
    }
    print_message("behind cut: %d rays near sphere surfaces, %d hits, %d cut (%d within "
                  "0.001 + 0.05%% of r of the cut)\n",
                  n, hits, cut, near_cut);
    assert_true(hits > n / 10);
    assert_true(cut > n / 20);
    assert_true(near_cut > n / 200);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
}

/* The bounding sphere's rejection of shadow rays (rt_scene.bound_*) and the quadrants of the
 * light's shadow rays (rt_scene.cull.shadow_quad) never change a result: for clusters of 2 to 6
 * spheres and a light, shadow segments built as trace.c builds them that pass just outside or
 * inside the bound, or graze a sphere touching it, are blocked through rt_occluded exactly when
 * they are with the bound switched off (bound_set = 0), and with the quadrants switched off too
 * (every mask all ones: each sphere then tested on its own); the bound does reject many of them,
 * near misses included, and the quadrants leave out spheres for many. */
static void test_shadow_bound(void **state)
{
    (void)state;
    static rt_scene s, plain, open;
    int n = 100000, rejected = 0, near_rejected = 0, blocked = 0, quad_cut = 0;
    fx_events_reset();
    for (int i = 0; i < n; i++) {
        double span = i % 10 == 0 ? 1000.0 : 10.0, size = i % 10 == 0 ? 50.0 : 2.0;
        s = (rt_scene){0};
        s.nobjects = 2 + i % 5;
        double ox = rnd(-span, span), oy = rnd(-span, span), oz = rnd(-span, span);
        for (int j = 0; j < s.nobjects; j++)
            s.objects[j] = sphere(ox + rnd(-size, size), oy + rnd(-size, size),
                                  oz + rnd(-size, size), rnd(0.02, 1) * size);
        s.nmaterials = 1;
        s.materials[0].ior = R_ONE;
        s.nlights = 1;
        double lx = ox + rnd(-8, 8) * size, ly = oy + rnd(-8, 8) * size,
               lz = oz + rnd(-8, 8) * size;
        s.lights[0].pos = vd(lx, ly, lz);
        rt_scene_prepare(&s);
        if (!s.cull.bound_set)
            fail_msg("no bound for %d spheres", s.nobjects);
        plain = s;
        plain.cull.bound_set = 0;
        open = plain;
        for (int q = 0; q < 4; q++)
            open.cull.shadow_quad[0][q] = 0xFFFFFFFFu;
        /* a point q near the bound's surface (or, every third case, near a sphere's), at right
         * angles to the light, and a surface point p beyond it as seen from the light */
        double cx = to_d(s.cull.bound_center.x), cy = to_d(s.cull.bound_center.y),
               cz = to_d(s.cull.bound_center.z), rb = to_d(s.cull.bound_radius);
        if (i % 3 == 0) {
            const rt_object *o = &s.objects[i % s.nobjects];
            cx = to_d(o->center.x), cy = to_d(o->center.y), cz = to_d(o->center.z);
            rb = to_d(o->radius);
        }
        double ux = rnd(-1, 1), uy = rnd(-1, 1), uz = rnd(-1, 1);
        double ax = cx - lx, ay = cy - ly, az = cz - lz;
        double a2 = ax * ax + ay * ay + az * az + 1e-30, ua = (ux * ax + uy * ay + uz * az) / a2;
        ux -= ua * ax, uy -= ua * ay, uz -= ua * az;
        double rq = i % 4 == 1 ? rb * rnd(1, 3) : rb + rnd(-0.003, 0.02) + rb * rnd(0, 0.002);
        vec3 p_out;
        dir3 l;
        real seg;
        if (!shadow_segment(&s, cx, cy, cz, ux, uy, uz, rq, i & 1, &p_out, &l, &seg))
            continue;
        uint32_t all = ((uint32_t)1 << s.nobjects) - 1;
        rt_stats st = {0}, st_plain = {0}, st_open = {0};
        int got = rt_occluded(&s, &st, 0, all, &p_out, &l, seg);
        int want = rt_occluded(&plain, &st_plain, 0, all, &p_out, &l, seg);
        int open_got = rt_occluded(&open, &st_open, 0, all, &p_out, &l, seg);
        if (got != want || open_got != want)
            fail_msg("with the bound %d, without %d, without the quadrants too %d (case %d, %d "
                     "spheres)",
                     got, want, open_got, i, s.nobjects);
        blocked += want;
        quad_cut += st_plain.shadow_tests < st_open.shadow_tests;
        if (st.shadow_tests < st_plain.shadow_tests && !want) {
            rejected++;
            if (i % 3 != 0 && i % 4 != 1)
                near_rejected++;
        }
    }
    print_message("shadow bound: %d segments, %d blocked, %d rejected by the bound (%d of them "
                  "passing within 0.02 + 0.2%% of its radius), %d with spheres left out by their "
                  "quadrant\n",
                  n, blocked, rejected, near_rejected, quad_cut);
    assert_true(blocked > n / 20);
    assert_true(rejected > n / 20);
    assert_true(near_rejected > n / 500);
    assert_true(quad_cut > n / 20);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
}

/* The per-object occluder sets (rt_scene.cull.occ_of) never change a result: shadow segments built
 * as trace.c builds them (from a point, lifted R_EPS_OFFSET along a normal facing the light,
 * aimed from the point or from the lifted point) from points of a sphere A (on its surface or
 * off it by up to 1e-4) are blocked through rt_occluded with occ_of[0][A] exactly when they are
 * with every other sphere (occluders). Half the cases are a sphere B between A and the light
 * whose outline, seen from the light, passes within 0.02 radians of A's (overlapping or apart),
 * the segment leaving A's outline on B's side, so that it grazes B; the others, clusters of 2
 * to 6 spheres at random and points of A at random or on its rim. The sets leave spheres out
 * for many of them. */
static void test_shadow_pairs(void **state)
{
    (void)state;
    static rt_scene s;
    int n = 100000, cut = 0, blocked = 0, tried = 0, graze_cut = 0;
    fx_events_reset();
    for (int i = 0; i < n; i++) {
        double span = i % 10 == 0 ? 1000.0 : 10.0, size = i % 10 == 0 ? 50.0 : 2.0;
        s = (rt_scene){0};
        s.nmaterials = 1;
        s.materials[0].ior = R_ONE;
        s.nlights = 1;
        double ox = rnd(-span, span), oy = rnd(-span, span), oz = rnd(-span, span);
        double lx = ox + rnd(-8, 8) * size, ly = oy + rnd(-8, 8) * size,
               lz = oz + rnd(-8, 8) * size;
        int graze = i & 8;
        /* u: from the light toward A; w: at right angles to it, toward B */
        double ux = rnd(-1, 1), uy = rnd(-1, 1), uz = rnd(-1, 1);
        double un = sqrt(ux * ux + uy * uy + uz * uz) + 1e-12;
        ux /= un, uy /= un, uz /= un;
        double wx = rnd(-1, 1), wy = rnd(-1, 1), wz = rnd(-1, 1), wu = wx * ux + wy * uy + wz * uz;
        wx -= wu * ux, wy -= wu * uy, wz -= wu * uz;
        double wn = sqrt(wx * wx + wy * wy + wz * wz) + 1e-12;
        wx /= wn, wy /= wn, wz /= wn;
        double px, py, pz, cx, cy, cz, r;
        int a;
        if (graze) {
            double da = rnd(2, 10) * size, ra = rnd(0.05, 0.5) * da;
            double db = rnd(0.2, 0.9) * da, rb = rnd(0.02, 0.9) * db;
            double alpha = asin(ra / da), beta = asin(rb / db),
                   th = alpha + beta + rnd(-0.02, 0.02);
            s.nobjects = 2;
            a = i & 16 ? 1 : 0;
            cx = lx + ux * da, cy = ly + uy * da, cz = lz + uz * da, r = ra;
            s.objects[a] = sphere(cx, cy, cz, ra);
            s.objects[1 - a] = sphere(lx + (ux * cos(th) + wx * sin(th)) * db,
                                      ly + (uy * cos(th) + wy * sin(th)) * db,
                                      lz + (uz * cos(th) + wz * sin(th)) * db, rb);
            /* the point where the line from the light touches A, on B's side */
            double tl = sqrt(da * da - ra * ra) + rnd(-1e-4, 1e-4);
            px = lx + (ux * cos(alpha) + wx * sin(alpha)) * tl;
            py = ly + (uy * cos(alpha) + wy * sin(alpha)) * tl;
            pz = lz + (uz * cos(alpha) + wz * sin(alpha)) * tl;
        } else {
            s.nobjects = 2 + i % 5;
            for (int j = 0; j < s.nobjects; j++)
                s.objects[j] = sphere(ox + rnd(-size, size), oy + rnd(-size, size),
                                      oz + rnd(-size, size), rnd(0.02, 1) * size);
            a = i % s.nobjects;
            const rt_object *o = &s.objects[a];
            cx = to_d(o->center.x), cy = to_d(o->center.y), cz = to_d(o->center.z);
            r = to_d(o->radius);
            if (i & 2) { /* on its rim: w at right angles to the light */
                double ax = cx - lx, ay = cy - ly, az = cz - lz;
                double a2 = ax * ax + ay * ay + az * az + 1e-30,
                       wa = (wx * ax + wy * ay + wz * az) / a2;
                wx -= wa * ax, wy -= wa * ay, wz -= wa * az;
                wn = sqrt(wx * wx + wy * wy + wz * wz) + 1e-12;
                wx /= wn, wy /= wn, wz /= wn;
            }
            double rp = r + rnd(-1e-4, 1e-4);
            px = cx + wx * rp, py = cy + wy * rp, pz = cz + wz * rp;
        }
        s.lights[0].pos = vd(lx, ly, lz);
        rt_scene_prepare(&s);
        vec3 p = vd(px, py, pz);
        if (!v3_within(p, R_SCENE_MAX))
            continue;
        vec3 to_light = v3_sub(s.lights[0].pos, p);
        if (v3_is_zero(to_light))
            continue;
        dir3 l = d3_norm(to_light, 0);
        /* a normal facing the light, tilted at random */
        dir3 nrm = d3_norm(
            vd(to_d(l.x) + rnd(-0.9, 0.9), to_d(l.y) + rnd(-0.9, 0.9), to_d(l.z) + rnd(-0.9, 0.9)),
            0);
        if (d3_dot(nrm, l) <= 0)
            continue;
        vec3 p_out = v3_along(p, nrm, R_EPS_OFFSET);
        vec3 t2 = v3_sub(s.lights[0].pos, i & 1 ? p_out : p);
        if (v3_is_zero(t2))
            continue;
        real dist;
        l = d3_norm(t2, &dist);
        if (dist <= R_EPS_OFFSET)
            continue;
        real seg = r_sub(dist, R_EPS_OFFSET);
        uint32_t self = (uint32_t)1 << a, all = s.occluders[0] & ~self,
                 some = s.cull.occ_of[0][a] & ~self;
        if ((some & ~all) != 0)
            fail_msg("occ_of %x is not within the occluders %x (case %d)", (unsigned)some,
                     (unsigned)all, i);
        rt_stats st = {0};
        int want = all ? rt_occluded(&s, &st, 0, all, &p_out, &l, seg) : 0;
        int got = some ? rt_occluded(&s, &st, 0, some, &p_out, &l, seg) : 0;
        if (got != want)
            fail_msg("with occ_of %d, with every sphere %d (case %d, %d spheres, receiver %d, "
                     "centre %g %g %g radius %g)",
                     got, want, i, s.nobjects, a, cx, cy, cz, r);
        tried++;
        blocked += want;
        cut += some != all;
        graze_cut += graze && some != all;
    }
    print_message("shadow pairs: %d segments from sphere points, %d blocked, %d with spheres left "
                  "out by the receiver's occluder set (%d grazing the sphere left out)\n",
                  tried, blocked, cut, graze_cut);
    assert_true(tried > n / 4);
    assert_true(blocked > n / 20);
    assert_true(cut > n / 10);
    assert_true(graze_cut > n / 40);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
}

/* The plane rule of the occluder sets (scene_shadow_pairs): a plane left out of a sphere's
 * set never blocks a shadow ray cast from that sphere. A floor (tilted at random in half the
 * cases) with a sphere resting on it (tangent, or up to 0.05 above) and another below it (so
 * the floor is an occluder), a light above the floor at 0.3 to 90 degrees' elevation from
 * the resting sphere; points of the resting sphere (half of them in the cap within 8 degrees
 * of its contact point, where p_out can dip below the floor) with the normal the tracer forms
 * there, seen from outside or (a quarter) from inside, which adds the planes back as
 * rt_light_reach does; only rays the tracer casts (n . l > 0). The segments are blocked with
 * the set exactly as with every occluder. A floor dropped for any sphere that does not cut it
 * fails it: low lights reach the contact cap. */
static void test_plane_pairs(void **state)
{
    (void)state;
    static rt_scene s;
    int n = 100000, tried = 0, cut = 0, floor_blocks = 0;
    fx_events_reset();
    for (int i = 0; i < n; i++) {
        s = (rt_scene){0};
        s.nmaterials = 1;
        s.materials[0].ior = R_ONE;
        s.nlights = 1;
        s.nobjects = 3;
        /* an orthonormal frame: e (the floor's normal), f and g along the floor */
        double ex = 0, ey = 1, ez = 0;
        if (i & 4) {
            ex = rnd(-1, 1), ey = rnd(0.2, 1), ez = rnd(-1, 1);
            double en = sqrt(ex * ex + ey * ey + ez * ez);
            ex /= en, ey /= en, ez /= en;
        }
        double fx = ey, fy = -ex, fz = 0, fn = sqrt(fx * fx + fy * fy) + 1e-12;
        if (fn < 0.1)
            fx = 0, fy = ez, fz = -ey, fn = sqrt(fy * fy + fz * fz);
        fx /= fn, fy /= fn, fz /= fn;
        double gx = ey * fz - ez * fy, gy = ez * fx - ex * fz, gz = ex * fy - ey * fx;
        double off = rnd(-3, 3), r = rnd(0.1, 2), h = r + (i & 8 ? rnd(0, 0.05) : 0);
        double u = rnd(-5, 5), v = rnd(-5, 5);
        int a = i % 2, pl = 2;
        s.objects[pl] = plane(ex, ey, ez, off);
        /* where the floor's normal is tilted, its stored normal is the one the rule uses */
        double cx = (off + h) * ex + u * fx + v * gx, cy = (off + h) * ey + u * fy + v * gy,
               cz = (off + h) * ez + u * fz + v * gz;
        s.objects[a] = sphere(cx, cy, cz, r);
        s.objects[1 - a] =
            sphere(cx + 3 * fx - 2 * ex, cy + 3 * fy - 2 * ey, cz + 3 * fz - 2 * ez, 1);
        double el = i & 16 ? rnd(0.005, 0.15) : rnd(0.005, 1.57), az = rnd(0, 6.2832),
               dl = rnd(1.2, 4) * r + rnd(0, 40);
        double lh = sin(el) * dl, lf = cos(el) * cos(az) * dl, lg = cos(el) * sin(az) * dl;
        double lx = cx + lh * ex + lf * fx + lg * gx, ly = cy + lh * ey + lf * fy + lg * gy,
               lz = cz + lh * ez + lf * fz + lg * gz;
        s.lights[0].pos = vd(lx, ly, lz);
        rt_scene_prepare(&s);
        /* a point of the resting sphere: in its contact cap, or anywhere */
        double qx, qy, qz;
        if (i & 32) {
            double th = rnd(0, 0.14), ph = rnd(0, 6.2832);
            qx = -cos(th) * ex + sin(th) * (cos(ph) * fx + sin(ph) * gx);
            qy = -cos(th) * ey + sin(th) * (cos(ph) * fy + sin(ph) * gy);
            qz = -cos(th) * ez + sin(th) * (cos(ph) * fz + sin(ph) * gz);
        } else {
            qx = rnd(-1, 1), qy = rnd(-1, 1), qz = rnd(-1, 1);
        }
        double qn = sqrt(qx * qx + qy * qy + qz * qz) + 1e-12, rp = r + rnd(-1e-4, 1e-4);
        vec3 p = vd(cx + qx / qn * rp, cy + qy / qn * rp, cz + qz / qn * rp);
        dir3 nrm = rt_sphere_normal(&s.objects[a], &p);
        int inside = (i & 3) == 3;
        if (inside)
            nrm = d3_neg(nrm);
        vec3 to_light = v3_sub(s.lights[0].pos, p);
        if (v3_is_zero(to_light))
            continue;
        dir3 l = d3_norm(to_light, 0);
        if (d3_dot(nrm, l) <= 0)
            continue; /* no shadow ray */
        vec3 p_out = v3_along(p, nrm, R_EPS_OFFSET);
        vec3 t2 = v3_sub(s.lights[0].pos, i & 64 ? p_out : p);
        if (v3_is_zero(t2))
            continue;
        real dist;
        l = d3_norm(t2, &dist);
        if (dist <= R_EPS_OFFSET)
            continue;
        real seg = r_sub(dist, R_EPS_OFFSET);
        uint32_t self = (uint32_t)1 << a, floor = (uint32_t)1 << pl;
        uint32_t all = s.occluders[0] & ~self, some = s.cull.occ_of[0][a];
        if (inside && RT_PLANE_CULL)
            some |= s.occluders[0] & s.cull.plane_set;
        assert_true((all & floor) != 0);
        rt_stats st = {0};
        int want = rt_occluded(&s, &st, 0, all, &p_out, &l, seg);
        int got = some ? rt_occluded(&s, &st, 0, some, &p_out, &l, seg) : 0;
        if (got != want)
            fail_msg("plane left out: with occ_of %d, with every occluder %d (case %d, radius %g, "
                     "height %g, elevation %g, inside %d)",
                     got, want, i, r, h, el, inside);
        tried++;
        cut += !(some & floor);
        floor_blocks += rt_occluded(&s, &st, 0, floor, &p_out, &l, seg);
    }
    print_message("plane pairs: %d segments from resting spheres, %d with the floor left out, %d "
                  "blocked by the floor\n",
                  tried, cut, floor_blocks);
    assert_true(tried > n / 4);
    assert_true(cut > n / 40);
    assert_true(floor_blocks > n / 2000);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
}

/* rt_nearest_primary (spheres' l and quick rejection prepared for the camera's eye) finds the
 * same object at the same distance as rt_nearest, for rays from the eye that graze spheres,
 * miss them by a hair or start inside one, and rejects early on many of them. */
static void test_primary_cull(void **state)
{
    (void)state;
    static rt_scene s;
    int n = 100000, culled = 0, near_culled = 0, hits = 0;
    fx_events_reset();
    for (int i = 0; i < n; i++) {
        double span = i % 10 == 0 ? 2000.0 : 20.0;
        s = (rt_scene){0};
        s.nobjects = 4;
        /* the plane last, or first (then rt_nearest_primary tests it after the spheres) */
        int base = (i >> 1) & 1;
        for (int j = base; j < base + 3; j++)
            s.objects[j] = sphere(rnd(-span, span), rnd(-span, span), rnd(-span, span),
                                  i % 10 == 0 ? rnd(0.05, 100) : rnd(0.05, 5));
        s.objects[base ? 0 : 3] = plane(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1), rnd(-span, span));
        s.nmaterials = 1;
        s.materials[0].ior = R_ONE;
        double ex = rnd(-span, span), ey = rnd(-span, span), ez = rnd(-span, span);
        if (i % 7 == 0) { /* the eye inside the first sphere */
            ex = to_d(s.objects[base].center.x) + rnd(-0.5, 0.5) * to_d(s.objects[base].radius);
            ey = to_d(s.objects[base].center.y);
            ez = to_d(s.objects[base].center.z);
        }
        s.camera.eye = vd(ex, ey, ez);
        rt_scene_prepare(&s);
        /* aim at a point about the radius off a sphere's centre, at right angles to the view
         * now and then: rays that pass just inside or just outside it */
        const rt_object *o = &s.objects[base + i % 3];
        double cx = to_d(o->center.x), cy = to_d(o->center.y), cz = to_d(o->center.z);
        double r = to_d(o->radius);
        double ux = rnd(-1, 1), uy = rnd(-1, 1), uz = rnd(-1, 1);
        double ax = cx - ex, ay = cy - ey, az = cz - ez;
        double a2 = ax * ax + ay * ay + az * az + 1e-30, ua = (ux * ax + uy * ay + uz * az) / a2;
        ux -= ua * ax, uy -= ua * ay, uz -= ua * az;
        double un = sqrt(ux * ux + uy * uy + uz * uz) + 1e-12;
        double rq = i & 1 ? r + rnd(-0.002, 0.012) + r * rnd(0, 0.002) : r * rnd(0, 3);
        vec3 to = vd(cx + ux / un * rq - ex, cy + uy / un * rq - ey, cz + uz / un * rq - ez);
        if (v3_is_zero(to))
            continue;
        dir3 d = d3_norm(to, 0);
        real t1, t2;
        int id1 = rt_nearest(&s, s.camera.eye, d, R_T_MAX, &t1);
        int id2 = rt_nearest_primary(&s, d, 0xFFFFFFFFu, &t2);
        if (id1 != id2 || t1 != t2)
            fail_msg("rt_nearest %d at %g, rt_nearest_primary %d at %g (case %d)", id1, to_d(t1),
                     id2, to_d(t2), i);
        hits += id1 >= 0 && s.objects[id1].kind == RT_SPHERE;
        real tca = v3_dot_d_in(s.cull.eye_l[base + i % 3], d);
        wide k = s.cull.eye_cull[base + i % 3];
        if (k > 0 && (tca <= 0 || w_sq(tca) < k)) {
            culled++;
            if (rq - r < 0.012 + r * 0.002 && rq > r)
                near_culled++;
        }
    }
    print_message("primary cull: %d rays, %d hit a sphere, %d rejected early (%d of them passing "
                  "within 0.012 + 0.2%% of the radius)\n",
                  n, hits, culled, near_culled);
    assert_true(hits > n / 10);
    assert_true(culled > n / 10);
    assert_true(near_culled > n / 100);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
}

/* rt_view_cull's candidate sets leave a sphere out of a pixel only where eye_cull rejects that
 * pixel's primary ray, so that rt_nearest_primary finds the same hit with them as with every
 * object: random scenes of spheres in front of, behind, around and at the eye (inside one now
 * and then), at every field of view, on frames whose tiles are 4 and 8 pixels; and they leave
 * most spheres out of most pixels. */
static void test_primary_tiles(void **state)
{
    (void)state;
    static rt_scene s;
    static const int sizes[][2] = {{64, 48}, {128, 64}, {33, 97}, {320, 240}, {200, 20}};
    long tests = 0, skipped = 0, pixels = 0;
    fx_events_reset();
    for (int n = 0; n < 300; n++) {
        double span = n % 5 == 0 ? 200.0 : 12.0;
        s = (rt_scene){0};
        s.nobjects = 9;
        for (int j = 0; j < 8; j++)
            s.objects[j] = sphere(rnd(-span, span), rnd(-span, span), rnd(-span, span),
                                  n % 5 == 0 ? rnd(0.05, 30) : rnd(0.05, 3));
        s.objects[8] = plane(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1), rnd(-span, span));
        s.nmaterials = 1;
        s.materials[0].ior = R_ONE;
        double ex = rnd(-span, span), ey = rnd(-span, span), ez = rnd(-span, span);
        if (n % 7 == 0) { /* the eye inside a sphere */
            ex = to_d(s.objects[1].center.x) + rnd(-0.5, 0.5) * to_d(s.objects[1].radius);
            ey = to_d(s.objects[1].center.y);
            ez = to_d(s.objects[1].center.z);
        }
        /* look at a sphere (its silhouette then crosses the frame), or anywhere */
        const rt_object *a = &s.objects[n % 8];
        vec3 at = n % 3 ? a->center : vd(rnd(-span, span), rnd(-span, span), rnd(-span, span));
        s.camera = (rt_camera){vd(ex, ey, ez), at, vd(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)),
                               from_d(n % 4 == 0 ? rnd(10, 120) : rnd(30, 60))};
        if (!rt_view_ok(&s.camera))
            continue;
        rt_scene_prepare(&s);
        const int *wh = sizes[n % 5];
        static rt_view v;
        rt_view_init(&v, &s.camera, wh[0], wh[1]);
        rt_view_cull(&v, &s);
        for (int y = 0; y < wh[1]; y++)
            for (int x = 0; x < wh[0]; x++) {
                dir3 d = rt_view_ray(&v, x, y);
                uint32_t cand = rt_view_candidates(&v, x, y);
                for (int i = 0; i < 8; i++) {
                    if (cand & (1u << i))
                        continue;
                    real tca = v3_dot_d_in(s.cull.eye_l[i], d);
                    wide k = s.cull.eye_cull[i];
                    if (!(k > 0 && (tca <= 0 || w_sq(tca) < k)))
                        fail_msg("case %d: sphere %d left out of pixel (%d, %d) of %dx%d, whose "
                                 "ray eye_cull does not reject",
                                 n, i, x, y, wh[0], wh[1]);
                    skipped++;
                }
                tests += 8;
                pixels++;
                if ((x + y) % 7 == 0) {
                    real t1, t2;
                    int id1 = rt_nearest_primary(&s, d, 0xFFFFFFFFu, &t1);
                    int id2 = rt_nearest_primary(&s, d, cand, &t2);
                    if (id1 != id2 || t1 != t2)
                        fail_msg("case %d pixel (%d, %d): %d at %g with every object, %d at %g "
                                 "with the candidates",
                                 n, x, y, id1, to_d(t1), id2, to_d(t2));
                }
            }
    }
    print_message("primary tiles: %ld pixels, %ld of %ld sphere tests left out\n", pixels, skipped,
                  tests);
    assert_true(skipped > tests / 2);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
    assert_int_equal(fx_event_count[FX_EV_DOMAIN], 0);
}

#if REAL_FIXED
static double ud(unit u) { return ldexp((double)u, -FX_UNIT_FRAC); }
#else
static double ud(unit u) { return u; }
#endif

/* rt_view_cull's mirror candidates keep every sphere that the reflection off the view's mirror
 * plane can hit: random views of spheres over a mirror plane (a few across it), the eye on its
 * front, looking at a sphere or at its mirror image, at every field of view. For each pixel
 * whose primary ray's nearest hit is the plane, the reflected ray as trace_secondary casts it
 * (from p_out along d3_reflect_k) is tested against every sphere: a sphere it hits must be among
 * the pixel's mirror candidates, and the pixel's direction must lie within the sphere's mirror
 * cone (rt_scene_mirror_cone, the angle in double); rt_nearest_set with the candidates gives
 * rt_nearest_but's hit. Most sphere tests are left out. */
static void test_mirror_tiles(void **state)
{
    (void)state;
    static rt_scene s;
    static rt_view v;
    static const int sizes[][2] = {{64, 48}, {128, 64}, {33, 97}, {320, 240}, {200, 20}};
    const int pl = 3; /* the mirror, between spheres in the objects' order */
    long tests = 0, skipped = 0, rays = 0, hits = 0, views = 0;
    double closest = 0; /* a hit's sine from the cone's axis over the cone's sine, at most */
    fx_events_reset();
    for (int n = 0; n < 300; n++) {
        double span = n % 5 == 0 ? 200.0 : 12.0;
        s = (rt_scene){0};
        s.nobjects = 9;
        double nx = rnd(-1, 1), ny = rnd(-1, 1), nz = rnd(-1, 1);
        if (n % 3 == 0) /* a floor, as in the intro */
            nx = nz = 0, ny = 1;
        double len = sqrt(nx * nx + ny * ny + nz * nz), off = rnd(-span / 4, span / 4);
        if (len < 0.1)
            continue;
        nx /= len, ny /= len, nz /= len;
        for (int j = 0, k = 0; j < 8; j++, k++) {
            if (k == pl)
                k++;
            double r = n % 5 == 0 ? rnd(0.05, 30) : rnd(0.05, 3);
            double c[3] = {rnd(-span, span), rnd(-span, span), rnd(-span, span)};
            double h = c[0] * nx + c[1] * ny + c[2] * nz - off;
            if (h < 0 && j % 4) /* most in front of the mirror */
                c[0] -= 2 * h * nx, c[1] -= 2 * h * ny, c[2] -= 2 * h * nz;
            s.objects[k] = sphere(c[0], c[1], c[2], r);
        }
        s.objects[pl] = plane(nx, ny, nz, off);
        s.objects[pl].material = 1;
        s.nmaterials = 2;
        s.materials[0].ior = R_ONE;
        s.materials[1].ior = R_ONE;
        s.materials[1].reflect = R(0.5);
        double e[3] = {rnd(-span, span), rnd(-span, span), rnd(-span, span)};
        double h = e[0] * nx + e[1] * ny + e[2] * nz - off;
        if (h < 0)
            e[0] -= 2 * h * nx, e[1] -= 2 * h * ny, e[2] -= 2 * h * nz;
        /* look at a sphere, at its mirror image, or anywhere */
        const rt_object *a = &s.objects[n % 3];
        double ac[3] = {to_d(a->center.x), to_d(a->center.y), to_d(a->center.z)};
        double ah = ac[0] * nx + ac[1] * ny + ac[2] * nz - off;
        vec3 at = n % 3 == 1 ? a->center
            : n % 3 == 2     ? vd(ac[0] - 2 * ah * nx, ac[1] - 2 * ah * ny, ac[2] - 2 * ah * nz)
                             : vd(rnd(-span, span), rnd(-span, span), rnd(-span, span));
        s.camera = (rt_camera){vd(e[0], e[1], e[2]), at, vd(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)),
                               from_d(n % 4 == 0 ? rnd(10, 120) : rnd(30, 60))};
        if (!rt_view_ok(&s.camera))
            continue;
        rt_scene_prepare(&s);
        const int *wh = sizes[n % 5];
        rt_view_init(&v, &s.camera, wh[0], wh[1]);
        rt_view_cull(&v, &s);
        if (s.cull.eye_num[pl] >= 0) { /* the eye (rounded) on the plane or behind it: no mirror */
            assert_int_equal(v.mirror_plane, -1);
            continue;
        }
        assert_int_equal(v.mirror_plane, pl);
        views++;
        vec3 axis[RT_MAX_OBJECTS];
        real cone[RT_MAX_OBJECTS];
        for (int i = 0; i < s.nobjects; i++)
            cone[i] = rt_scene_mirror_cone(&s, pl, i, &axis[i]);
        const dir3 nn = s.objects[pl].normal;
        for (int y = 0; y < wh[1]; y++)
            for (int x = 0; x < wh[0]; x++) {
                dir3 d = rt_view_ray(&v, x, y);
                real t;
                if (rt_nearest_primary(&s, d, rt_view_candidates(&v, x, y), &t) != pl)
                    continue;
                vec3 p = v3_along_in(s.cull.eye_at, d, t);
                unit dn = d3_dot(d, nn);
                if (!v3_within(p, R_SCENE_MAX) || dn > 0)
                    continue; /* no reflected ray (hit from behind: not the mirror's case) */
                vec3 p_out = v3_along_in(p, nn, R_EPS_OFFSET);
                dir3 r = d3_reflect_k(d, nn, dn);
                uint32_t cand = rt_view_mirror_candidates(&v, x, y);
                rays++;
                for (int i = 0; i < s.nobjects; i++) {
                    if (i == pl)
                        continue;
                    tests++;
                    skipped += !(cand & (1u << i));
                    real th;
                    if (!rt_intersect(&s.objects[i], p_out, r, R_T_MAX, &th))
                        continue;
                    hits++;
                    if (!(cand & (1u << i)))
                        fail_msg("case %d: sphere %d left out of pixel (%d, %d) of %dx%d, whose "
                                 "reflected ray hits it at %g",
                                 n, i, x, y, wh[0], wh[1], to_d(th));
                    if (cone[i] <= 0)
                        continue;
                    double lx = to_d(axis[i].x), ly = to_d(axis[i].y), lz = to_d(axis[i].z);
                    double dx = ud(d.x), dy = ud(d.y), dz = ud(d.z);
                    double cs = (lx * dx + ly * dy + lz * dz) / sqrt(lx * lx + ly * ly + lz * lz) /
                        sqrt(dx * dx + dy * dy + dz * dz);
                    double sn = sqrt(cs < 1 ? 1 - cs * cs : 0) / to_d(cone[i]);
                    if (cs <= 0 || sn > 1)
                        fail_msg("case %d pixel (%d, %d): sphere %d hit by the reflection, the "
                                 "view ray %.6f of its mirror cone's sine off the axis",
                                 n, x, y, i, cs <= 0 ? 99.0 : sn);
                    closest = sn > closest ? sn : closest;
                }
                real t1, t2;
                int id1 = rt_nearest_but(&s, p_out, r, R_T_MAX, pl, &t1);
                int id2 = rt_nearest_set(&s, p_out, r, R_T_MAX, cand & ~((uint32_t)1 << pl), &t2);
                if (id1 != id2 || t1 != t2)
                    fail_msg("case %d pixel (%d, %d): %d at %g with every object, %d at %g with "
                             "the mirror candidates",
                             n, x, y, id1, to_d(t1), id2, to_d(t2));
            }
    }
    print_message("mirror tiles: %ld views, %ld reflected rays, %ld sphere hits (the closest to "
                  "its cone's edge at %.4f of the cone's sine), %ld of %ld sphere tests left "
                  "out\n",
                  views, rays, hits, closest, skipped, tests);
    assert_true(views > 100);
    assert_true(hits > rays / 20);
    assert_true(closest > 0.9);
    assert_true(skipped > tests / 2);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
    assert_int_equal(fx_event_count[FX_EV_DOMAIN], 0);
}

/* Tracing a pixel fills the per-sample record adaptive subsampling will compare. */
static void test_sample_record(void **state)
{
    (void)state;
    static rt_scene s;
    s = (rt_scene){0};
    s.background = vd(0.1, 0.2, 0.3);
    s.ambient = vd(0.2, 0.2, 0.2);
    s.depth = 3;
    s.materials[0] = (rt_material){.diffuse = vd(0.8, 0.2, 0.2),
                                   .ambient = R_ONE,
                                   .specular = R(0.9),
                                   .shininess = 8,
                                   .ior = R_ONE};
    s.materials[1] = (rt_material){
        .diffuse = vd(0.1, 0.1, 0.1), .ambient = R_ONE, .reflect = R(0.8), .ior = R_ONE};
    s.nmaterials = 2;
    s.objects[0] = sphere(0, 0, -10, 2);
    s.objects[0].material = 0;
    s.nobjects = 1;
    s.lights[0] = (rt_light){vd(0, 0, 10), vd(1, 1, 1)};
    s.nlights = 1;
    s.camera = (rt_camera){vd(0, 0, 0), vd(0, 0, -10), vd(0, 1, 0), R(40.0)};
    rt_scene_prepare(&s);
    rt_view v;
    rt_view_init(&v, &s.camera, 64, 64);
    rt_stats st = {0};
    rt_sample sm;
    const rt_params prm = {.depth = 3};

    /* centre pixel: the sphere, lit head-on with a highlight */
    rt_trace_pixel(&s, &v, &prm, 32, 32, &st, &sm);
    assert_int_equal(sm.nhits, 1);
    assert_int_equal(sm.hits[0].object, 0);
    assert_int_equal(sm.hits[0].level, 0);
    assert_int_equal(rt_light_state(&sm, 0), 2);
    /* corner pixel: background */
    rt_trace_pixel(&s, &v, &prm, 0, 0, &st, &sm);
    assert_int_equal(sm.nhits, 1);
    assert_int_equal(sm.hits[0].object, RT_NO_OBJECT);
    assert_int_equal(rt_color_pixel(sm.color), rt_color_pixel(s.background));

    /* a second sphere between light and the first: the centre is in shadow */
    s.objects[1] = sphere(0, 0, 2, 1);
    s.objects[1].material = 1;
    s.nobjects = 2;
    s.camera.eye = vd(0, 6, 0);
    rt_scene_prepare(&s);
    rt_view_init(&v, &s.camera, 64, 64);
    rt_trace_pixel(&s, &v, &prm, 32, 32, &st, &sm);
    assert_int_equal(sm.hits[0].object, 0);
    assert_int_equal(rt_light_state(&sm, 0), 0);

    /* look at the mirror sphere from the side: level 0 is the mirror, level 1 what it shows */
    s.camera = (rt_camera){vd(0, 0, 6), vd(0, 0, 2), vd(0, 1, 0), R(40.0)};
    rt_scene_prepare(&s);
    rt_view_init(&v, &s.camera, 64, 64);
    st = (rt_stats){0};
    rt_trace_pixel(&s, &v, &prm, 32, 32, &st, &sm);
    assert_int_equal(sm.hits[0].object, 1);
    assert_true(sm.nhits >= 2);
    assert_int_equal(sm.hits[1].level, 1);
    assert_int_equal(st.rays_primary, 1);
    assert_true(st.rays_reflect >= 1);
}

/* Two facing mirror planes far apart: rays bounce outwards, each bounce up to R_T_MAX further.
 * Every ray origin must stay where the tracer's 64-bit bounds hold (UBSan would report signed
 * overflow otherwise) and no saturation may happen. */
static void test_far_mirror_chain(void **state)
{
    (void)state;
    static rt_scene s;
    s = (rt_scene){0};
    s.background = vd(0.1, 0.2, 0.3);
    s.ambient = vd(0.2, 0.2, 0.2);
    s.depth = RT_MAX_DEPTH;
    s.materials[0] = (rt_material){
        .diffuse = vd(0.2, 0.2, 0.2), .ambient = R_ONE, .reflect = R(0.9), .ior = R_ONE};
    s.materials[1] = (rt_material){.diffuse = vd(0.8, 0.2, 0.2), .ambient = R_ONE, .ior = R_ONE};
    s.nmaterials = 2;
    s.objects[0] = plane(0, 1, 0, 0);      /* floor */
    s.objects[1] = plane(0, -1, 0, -4000); /* ceiling at y = 4000 */
    s.objects[2] = sphere(-4000, 100, -4000, 10);
    s.objects[2].material = 1;
    s.nobjects = 3;
    s.lights[0] = (rt_light){vd(0, 3000, 0), vd(1, 1, 1)};
    s.nlights = 1;
    /* look along the diagonal, 14 degrees down: about 16000 units between bounces */
    s.camera = (rt_camera){vd(0, 2000, 0), vd(1000, 1647, 1000), vd(0, 1, 0), R(20.0)};
    rt_scene_prepare(&s);
    rt_view v;
    rt_view_init(&v, &s.camera, 32, 32);
    rt_stats st = {0};
    static uint32_t pixels[32 * 32];
    fx_events_reset();
    const rt_params prm = {.depth = RT_MAX_DEPTH, .mode = RT_MODE_FULL};
    rt_render(&s, &v, &prm, pixels, 32, &st, NULL, NULL);
    print_message("far mirror chain: %lu reflected rays, %lu overflow events\n",
                  (unsigned long)st.rays_reflect, fx_event_count[FX_EV_OVERFLOW]);
    assert_true(st.rays_reflect > 0);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
}

/* The secondary rays' candidate sets (rt_scene.cull.ray_oct, ray_in): rays cast as trace_secondary
 * casts them from hits on a sphere (mirrored and refracted, from outside and inside) among
 * spheres that rest on a floor, touch, overlap or stand apart, find through rt_nearest_from with
 * the sets (and ray_in's check: searched again with ray_oct's where the sphere is not the hit)
 * the object and distance the search of every object finds, in both builds. Scenes near the origin and far out (where
 * hit points are least exact). */
static void test_ray_sets(void **state)
{
    (void)state;
    static rt_scene s;
    int n = 60000, rays = 0, into_rays = 0, again = 0;
    long tests_all = 0, tests_set = 0;
    fx_events_reset();
    for (int i = 0; i < n; i++) {
        double span = i % 8 == 0 ? 1500.0 : 4.0, base = i % 8 == 0 ? rnd(-1500, 1500) : 0;
        s = (rt_scene){0};
        int ns = 3 + i % 5, pl = (i >> 3) % 3 == 0 ? ns / 2 : 0;
        s.nobjects = ns + 1;
        s.objects[pl] = plane(0, 1, 0, base);
        for (int j = 0, k = 0; j < ns; j++, k++) {
            if (k == pl)
                k++;
            double r = i % 8 == 0 ? rnd(0.5, 200) : rnd(0.2, 1.5);
            double x = rnd(-span, span), z = rnd(-span, span);
            /* resting on the floor, floating, or cutting it */
            double y = base + (j % 3 == 0 ? r : j % 3 == 1 ? r + rnd(0, span) : rnd(-r, r));
            if (j > 0 && i % 4 == 1) { /* touching the previous sphere, or overlapping it */
                const rt_object *o = &s.objects[k - 1 == pl ? k - 2 : k - 1];
                double ux = rnd(-1, 1), uy = rnd(-1, 1), uz = rnd(-1, 1);
                double un = sqrt(ux * ux + uy * uy + uz * uz) + 1e-9;
                double dd = to_d(o->radius) + r + (i & 32 ? 0 : rnd(-0.3, 0.01) * r);
                x = to_d(o->center.x) + ux / un * dd;
                y = to_d(o->center.y) + uy / un * dd;
                z = to_d(o->center.z) + uz / un * dd;
            }
            s.objects[k] = sphere(x, y, z, r);
        }
        s.nmaterials = 1;
        s.materials[0].ior = R_ONE;
        s.camera.eye = vd(base, base + 1000, base);
        rt_scene_prepare(&s);
        /* a hit on sphere a, from a ray aimed at a point of it from outside or inside */
        int a = pl == 0 ? 1 + (int)rnd(0, ns - 0.001) : (int)rnd(0, ns + 0.999);
        if (a == pl || a > ns)
            continue;
        const rt_object *oa = &s.objects[a];
        double ca[3] = {to_d(oa->center.x), to_d(oa->center.y), to_d(oa->center.z)};
        double ra = to_d(oa->radius);
        double qx = rnd(-1, 1), qy = rnd(-1, 1), qz = rnd(-1, 1);
        double qn = sqrt(qx * qx + qy * qy + qz * qz) + 1e-9;
        double far = i & 2 ? 0.3 * ra : ra + rnd(0.5, 4) * ra;
        vec3 org = vd(ca[0] + qx / qn * far, ca[1] + qy / qn * far, ca[2] + qz / qn * far);
        double tx = rnd(-1, 1), ty = rnd(-1, 1), tz = rnd(-1, 1);
        double tn = sqrt(tx * tx + ty * ty + tz * tz) + 1e-9;
        dir3 d = dirv(ca[0] + tx / tn * ra - to_d(org.x), ca[1] + ty / tn * ra - to_d(org.y),
                      ca[2] + tz / tn * ra - to_d(org.z));
        real t;
        if (!v3_within(org, R_SCENE_MAX) || rt_nearest(&s, org, d, R_T_MAX, &t) != a)
            continue;
        vec3 p = v3_along(org, d, t);
        if (!v3_within(p, R_SCENE_MAX))
            continue;
        dir3 nrm = rt_sphere_normal(oa, &p);
        unit dn = d3_dot(d, nrm);
        int inside = dn > 0;
        if (inside) {
            nrm = d3_neg(nrm);
            dn = u_neg(dn);
        }
        for (int kind = 0; kind < 2; kind++) {
            dir3 rd;
            vec3 o2;
            int into;
            if (kind == 0) { /* mirrored */
                rd = d3_reflect_k(d, nrm, dn);
                o2 = v3_along(p, nrm, R_EPS_OFFSET);
                into = inside;
            } else { /* refracted */
                real eta = inside ? from_d(rnd(1, 2)) : from_d(rnd(0.5, 1));
                if (!d3_refract_k(d, nrm, dn, eta, &rd))
                    continue;
                o2 = v3_along(p, nrm, r_neg(R_EPS_OFFSET));
                into = !inside;
            }
            real t1, t2, t_in;
            int want = rt_nearest_set(&s, o2, rd, R_T_MAX, ~(uint32_t)0, &t1);
            int got = rt_nearest_from(&s, o2, rd, R_T_MAX, 2 * a + into, ~(uint32_t)0, &t2);
            uint32_t cand = s.cull.ray_oct[a][rt_octant(rd)], all = ((uint32_t)1 << s.nobjects) - 1;
            uint32_t in = cand & s.cull.ray_in[a];
            if (into && rt_nearest_set(&s, o2, rd, R_T_MAX, in, &t_in) != a) {
                again++;
                in = cand; /* searched again with ray_oct's */
            }
            if (got != want || (got >= 0 && t1 != t2))
                fail_msg("ray from sphere %d (%s, %s): sets give %d at %g, every object %d at %g "
                         "(case %d)",
                         a, kind ? "refracted" : "mirrored", into ? "inside" : "outside", got,
                         to_d(t2), want, to_d(t1), i);
            rays++;
            into_rays += into;
            tests_all += __builtin_popcount(all);
            tests_set += __builtin_popcount((into ? in : cand) & all);
        }
    }
    print_message("ray sets: %d secondary rays (%d from inside), %ld of %ld object tests left "
                  "out, %d searched again\n",
                  rays, into_rays, tests_all - tests_set, tests_all, again);
    assert_true(rays > n / 4);
    assert_true(into_rays > n / 20);
    assert_true(tests_set < tests_all * 9 / 10); /* the sets leave tests out */
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
}

/* A point seen from inside a sphere is in the sphere's own shadow where rt_scene.cull.dark_inside and
 * dark_r say so: rt_light_reach's shortcut (no normalisation, no shadow ray test) gives what
 * the full test gives, for points of glass spheres of radius 0.05 to 200 hit from inside (near
 * the origin and 1500 units out) or off the surface by up to 3 R_EPS_OFFSET either side, lights
 * far off, just outside the margin and near the surface (aimed from p_out), a floor and a
 * neighbour among the occluders, in both builds. */
static void test_dark_inside(void **state)
{
    (void)state;
    static rt_scene s, plain;
    int n = 60000, tried = 0, edge_tried = 0, dark = 0, lit = 0;
    fx_events_reset();
    for (int i = 0; i < n; i++) {
        /* near the origin, anywhere within +-1500, or near the scene's edge (+-R_SCENE_MAX,
         * 4096: every position of the case, lights and eye included, within +-3960) */
        const int edge = i % 16 == 4;
        double base = i % 8 == 0 ? rnd(-1500, 1500)
            : edge               ? (i & 32 ? 1 : -1) * rnd(3700, 3800)
                                 : 0;
        double r = i % 3 == 0 ? rnd(0.05, 0.5) : i % 3 == 1 ? rnd(0.5, 3) : rnd(3, edge ? 30 : 200);
        s = (rt_scene){0};
        s.nobjects = 3;
        s.nlights = 2;
        double cx = base + rnd(-5, 5), cy = base + r + rnd(0, 2), cz = base + rnd(-5, 5);
        s.objects[0] = plane(0, 1, 0, base);
        s.objects[1] = sphere(cx, cy, cz, r);
        s.objects[2] = sphere(cx + 2.5 * r + 1, cy, cz, r);
        s.nmaterials = 1;
        s.materials[0].ior = R(1.5);
        s.materials[0].transmit = R(0.85); /* glass: rays get inside */
        for (int l = 0; l < 2; l++) {
            double ux = rnd(-1, 1), uy = rnd(-1, 1), uz = rnd(-1, 1);
            double un = sqrt(ux * ux + uy * uy + uz * uz) + 1e-9;
            /* far, just outside the shortcut's margin, or near the surface */
            double dl = l == 0 ? r + rnd(1, 60) : r + (i & 4 ? rnd(0, 0.05) : rnd(0.0005, 0.004));
            s.lights[l].pos = vd(cx + ux / un * dl, cy + uy / un * dl, cz + uz / un * dl);
            s.lights[l].color = v3(R_ONE, R_ONE, R_ONE);
        }
        s.camera.eye = vd(base, base + (edge ? 100 : 1000), base);
        rt_scene_prepare(&s);
        plain = s;
        for (int l = 0; l < RT_MAX_LIGHTS; l++)
            plain.cull.dark_inside[l] = 0;
        /* a hit on sphere 1 from inside it, as the tracer finds it */
        double q = rnd(0, 0.9) * r, ox = rnd(-1, 1), oy = rnd(-1, 1), oz = rnd(-1, 1);
        double on = sqrt(ox * ox + oy * oy + oz * oz) + 1e-9;
        vec3 org = vd(cx + ox / on * q, cy + oy / on * q, cz + oz / on * q);
        dir3 d = dirv(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1));
        real t;
        vec3 p;
        dir3 nrm;
        if (i & 1) { /* or a point off the surface by up to 3 R_EPS_OFFSET, either side */
            double e = r + rnd(-3, 3) * to_d(R_EPS_OFFSET);
            p = vd(cx + ox / on * e, cy + oy / on * e, cz + oz / on * e);
            nrm = d3_neg(rt_sphere_normal(&s.objects[1], &p));
        } else {
            if (rt_nearest(&s, org, d, R_T_MAX, &t) != 1)
                continue;
            p = v3_along(org, d, t);
            nrm = rt_sphere_normal(&s.objects[1], &p);
            if (d3_dot(d, nrm) <= 0)
                continue; /* not seen from inside */
            nrm = d3_neg(nrm);
        }
        vec3 p_out = v3_along(p, nrm, R_EPS_OFFSET);
        for (int l = 0; l < 2; l++) {
            rt_stats st = {0}, st_plain = {0};
            dir3 l1, l2;
            unit got = rt_light_reach(&s, &st, l, 1, 1, &p, &p_out, nrm, &l1);
            unit want = rt_light_reach(&plain, &st_plain, l, 1, 1, &p, &p_out, nrm, &l2);
            if (got != want)
                fail_msg("light %d at a point seen from inside: %d with the shortcut, %d without "
                         "(case %d, radius %g)",
                         l, got, want, i, r);
            tried++;
            edge_tried += edge;
            dark += st.shadow_tests < st_plain.shadow_tests;
            lit += want != 0;
        }
    }
    print_message("dark inside: %d light tests from inside (%d near the scene's edge), %d decided "
                  "by the shortcut, %d lit\n",
                  tried, edge_tried, dark, lit);
    assert_true(tried > n / 2);
    assert_true(dark > tried / 6);
    assert_true(edge_tried > tried / 40);
    assert_int_equal(fx_event_count[FX_EV_OVERFLOW], 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere_cases),     cmocka_unit_test(test_plane_cases),
        cmocka_unit_test(test_sphere_random),    cmocka_unit_test(test_shadow_cull),
        cmocka_unit_test(test_shadow_bound),     cmocka_unit_test(test_behind_cut),
        cmocka_unit_test(test_primary_cull),     cmocka_unit_test(test_primary_tiles),
        cmocka_unit_test(test_mirror_tiles),     cmocka_unit_test(test_sample_record),
        cmocka_unit_test(test_far_mirror_chain), cmocka_unit_test(test_shadow_pairs),
        cmocka_unit_test(test_plane_pairs),      cmocka_unit_test(test_ray_sets),
        cmocka_unit_test(test_dark_inside),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
