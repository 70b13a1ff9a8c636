/* test_optics.c: pixels whose colour is known in closed form: mirrors, glass, total internal reflection, shadows, probe agreement. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "rt_local.h"

#if REAL_FIXED
static real from_d(double x) { return (real)llround(x * 65536.0); }
#else
static real from_d(double x) { return (real)x; }
#endif

static vec3 vd(double x, double y, double z) { return v3(from_d(x), from_d(y), from_d(z)); }

/* Frames of N x N pixels: pixel (C, C) looks exactly along the camera's axis. */
#define N 9
#define C (N / 2)

/* A scene with no light and an ambient light of 1: a surface of ambient 1 shows exactly its
 * diffuse colour, one of diffuse 0 only what its rays bring back. */
static void optics_base(rt_scene *s, int depth)
{
    memset(s, 0, sizeof *s);
    s->background = vd(0.1, 0.2, 0.3);
    s->ambient = vd(1, 1, 1);
    s->depth = depth;
}

static int add_material(rt_scene *s, double r, double g, double b, double reflect, double transmit,
                        double ior)
{
    rt_material *m = &s->materials[s->nmaterials];
    *m = (rt_material){.diffuse = vd(r, g, b),
                       .ambient = from_d(1),
                       .shininess = 1,
                       .reflect = from_d(reflect),
                       .transmit = from_d(transmit),
                       .ior = from_d(ior)};
    return s->nmaterials++;
}

/* The plane n . p = offset (n a unit axis) facing along n. */
static void add_plane(rt_scene *s, int mat, double nx, double ny, double nz, double offset)
{
    rt_object *o = &s->objects[s->nobjects++];
    *o = (rt_object){.kind = RT_PLANE, .material = (uint8_t)mat};
    o->axis = vd(nx, ny, nz);
    o->offset = from_d(offset);
}

static void add_sphere(rt_scene *s, int mat, double x, double y, double z, double r)
{
    rt_object *o = &s->objects[s->nobjects++];
    *o = (rt_object){.kind = RT_SPHERE, .material = (uint8_t)mat};
    o->center = vd(x, y, z);
    o->radius = from_d(r);
}

/* The full-mode record of pixel (x, y), every ray cast (min_contrib 0). */
static rt_sample trace_at(rt_scene *s, int x, int y)
{
    rt_scene_prepare(s);
    rt_view v;
    rt_view_init(&v, &s->camera, N, N);
    const rt_params p = {.depth = s->depth, .mode = RT_MODE_FULL};
    rt_stats st = {0};
    rt_sample sm;
    rt_trace_pixel(s, &v, &p, x, y, &st, &sm);
    return sm;
}

/* The pixel's bytes are r, g, b (each in [0, 1]) within tol levels. */
static void assert_pixel(const rt_sample *sm, double r, double g, double b, int tol,
                         const char *what)
{
    const uint32_t px = rt_color_pixel(sm->color);
    const double want[3] = {r, g, b};
    for (int ch = 0; ch < 3; ch++) {
        const int got = (int)(px >> (16 - 8 * ch) & 0xFF), w = (int)lround(want[ch] * 255);
        if (abs(got - w) > tol)
            fail_msg("%s: channel %d is %d, want %d (+-%d)", what, ch, got, w, tol);
    }
}

/* Between a wall of colour A behind the camera and a wall of colour B beyond: a pane of glass
 * (a plane, diffuse 0) at normal incidence reflects `kr` of A back and lets `kt` of B through,
 * undeviated: the pixel is kr A + kt B. Swapping the two weights gives kt A + kr B. */
static void test_glass_pane_normal(void **state)
{
    (void)state;
    static rt_scene s;
    optics_base(&s, 2);
    const double kr = 0.25, kt = 0.6;
    const int glass = add_material(&s, 0, 0, 0, kr, kt, 1.5);
    const int wall_a = add_material(&s, 0.8, 0.4, 0.2, 0, 0, 1);
    const int wall_b = add_material(&s, 0.2, 0.5, 0.9, 0, 0, 1);
    add_plane(&s, glass, 0, 0, 1, -2);   /* z = -2, facing the camera */
    add_plane(&s, wall_a, 0, 0, -1, -3); /* z = 3, behind the camera, facing it */
    add_plane(&s, wall_b, 0, 0, 1, -6);  /* z = -6, beyond the glass */
    s.camera = (rt_camera){vd(0, 0, 0), vd(0, 0, -1), vd(0, 1, 0), from_d(30)};
    rt_sample sm = trace_at(&s, C, C);
    assert_int_equal(sm.nhits, 3); /* the pane, then what it lets through and what it mirrors */
    assert_pixel(&sm, kr * 0.8 + kt * 0.2, kr * 0.4 + kt * 0.5, kr * 0.2 + kt * 0.9, 1,
                 "glass pane at normal incidence");
    /* the pane's nodes: what it lets through weighs kt, what it mirrors kr */
    assert_int_equal(sm.hits[1].object, 2);
    assert_int_equal(sm.hits[1].contrib[2], (int)lround(kt * 0.9 * 255));
    assert_int_equal(sm.hits[2].object, 1);
    assert_int_equal(sm.hits[2].contrib[0], (int)lround(kr * 0.8 * 255));
}

/* A glass ball (diffuse 0, no reflection) on the camera's axis in front of a wall: the central
 * ray enters and leaves at normal incidence, undeviated, and shows kt^2 of the wall (one kt
 * entering, one leaving); a ball of ior 1 is the same at any pixel that meets the wall. */
static void test_glass_ball_normal(void **state)
{
    (void)state;
    static rt_scene s;
    optics_base(&s, 3);
    const double kt = 0.8;
    const int glass = add_material(&s, 0, 0, 0, 0, kt, 1.5);
    const int wall = add_material(&s, 0.9, 0.6, 0.3, 0, 0, 1);
    add_sphere(&s, glass, 0, 0, -4, 1);
    add_plane(&s, wall, 0, 0, 1, -8);
    s.camera = (rt_camera){vd(0, 0, 0), vd(0, 0, -1), vd(0, 1, 0), from_d(30)};
    rt_sample sm = trace_at(&s, C, C);
    assert_pixel(&sm, kt * kt * 0.9, kt * kt * 0.6, kt * kt * 0.3, 1, "glass ball, centre");
}

/* A mirror ball (diffuse 0, reflect kr) on the camera's axis: the central ray comes straight
 * back and shows kr of the wall behind the camera; without that wall, kr of the background. */
static void test_mirror_ball_faces(void **state)
{
    (void)state;
    static rt_scene s;
    optics_base(&s, 2);
    const double kr = 0.9;
    const int mirror = add_material(&s, 0, 0, 0, kr, 0, 1);
    const int wall = add_material(&s, 0.3, 0.7, 0.5, 0, 0, 1);
    add_sphere(&s, mirror, 0, 0, -5, 1);
    s.camera = (rt_camera){vd(0, 0, 0), vd(0, 0, -1), vd(0, 1, 0), from_d(30)};
    rt_sample sm = trace_at(&s, C, C);
    assert_pixel(&sm, kr * 0.1, kr * 0.2, kr * 0.3, 1, "mirror ball, the background behind");
    add_plane(&s, wall, 0, 0, -1, -3); /* z = 3, behind the camera */
    sm = trace_at(&s, C, C);
    assert_pixel(&sm, kr * 0.3, kr * 0.7, kr * 0.5, 1, "mirror ball, the wall behind");
}

/* Light trapped in a glass ball: seen from inside, off its centre, the ray meets the surface
 * beyond the critical angle (cos 0.436 < sqrt(1 - 1/1.5^2) = 0.745) at every bounce, so the
 * transmitted share is reflected too (total internal reflection: kr + kt) and each of the
 * depth + 1 hits adds the surface's own colour L, weighted by (kr + kt)^k:
 * L (1 + q + q^2 + q^3), q = kr + kt. Dropping the transmitted share gives q = kr. */
static void test_total_internal_reflection(void **state)
{
    (void)state;
    static rt_scene s;
    optics_base(&s, 3);
    const double kr = 0.2, kt = 0.7, q = kr + kt, sum = 1 + q + q * q + q * q * q;
    const int glass = add_material(&s, 0.1, 0.05, 0.2, kr, kt, 1.5);
    add_sphere(&s, glass, 0, 0, 0, 1);
    s.camera = (rt_camera){vd(0.9, 0, 0), vd(0.9, 0, -1), vd(0, 1, 0), from_d(30)};
    rt_sample sm = trace_at(&s, C, C);
    assert_int_equal(sm.nhits, 4); /* four hits inside, none leaving */
    for (int j = 0; j < 4; j++)
        assert_int_equal(sm.hits[j].object, 0);
    assert_pixel(&sm, 0.1 * sum, 0.05 * sum, 0.2 * sum, 2, "total internal reflection");
}

/* Every light's own shadow: four lights over a matte floor (ambient 0), the camera looking at
 * the floor's origin P. A small ball on the segment from P to light i blocks light i alone, and
 * P then shows the other three lights' Lambert terms: diffuse x colour x cos, cos = the light's
 * height over its distance. */
static void test_each_light_shadow(void **state)
{
    (void)state;
    static rt_scene s;
    const double lp[4][3] = {{3, 6, 1}, {-4, 5, 2}, {1, 7, -3}, {-2, 4, -4}};
    const double lc[4][3] = {{0.3, 0.1, 0.1}, {0.1, 0.3, 0.1}, {0.1, 0.1, 0.3}, {0.2, 0.2, 0.2}};
    const double dif[3] = {0.9, 0.8, 0.7};
    for (int blocked = -1; blocked < 4; blocked++) {
        memset(&s, 0, sizeof s);
        s.background = vd(0, 0, 0);
        s.depth = 0;
        s.nlights = 4;
        for (int i = 0; i < 4; i++)
            s.lights[i] =
                (rt_light){vd(lp[i][0], lp[i][1], lp[i][2]), vd(lc[i][0], lc[i][1], lc[i][2])};
        const int floor = add_material(&s, dif[0], dif[1], dif[2], 0, 0, 1);
        const int ball = add_material(&s, 1, 1, 1, 0, 0, 1);
        add_plane(&s, floor, 0, 1, 0, 0);
        if (blocked >= 0) /* halfway to the light, radius 0.2: no other light's ray comes near */
            add_sphere(&s, ball, lp[blocked][0] / 2, lp[blocked][1] / 2, lp[blocked][2] / 2, 0.2);
        s.camera = (rt_camera){vd(0, 3, 8), vd(0, 0, 0), vd(0, 1, 0), from_d(20)};
        rt_sample sm = trace_at(&s, C, C);
        double want[3] = {0, 0, 0};
        for (int i = 0; i < 4; i++) {
            const double len =
                sqrt(lp[i][0] * lp[i][0] + lp[i][1] * lp[i][1] + lp[i][2] * lp[i][2]);
            for (int ch = 0; ch < 3; ch++)
                want[ch] += i == blocked ? 0 : dif[ch] * lc[i][ch] * lp[i][1] / len;
        }
        for (int i = 0; i < 4; i++)
            assert_int_equal(rt_light_state(&sm, i) != 0, i != blocked);
        char what[64];
        snprintf(what, sizeof what, "floor point, light %d blocked", blocked);
        assert_pixel(&sm, want[0], want[1], want[2], 1, what);
    }
}

/* Probe mode's test of two ends' contributions (rt_probe_point): ends with one record whose
 * contributions differ by more than the threshold are not probed, whichever end is the larger;
 * by the threshold or less, the point between them is. */
static void test_probe_disagree_both_ways(void **state)
{
    (void)state;
    static rt_scene s;
    optics_base(&s, 0);
    s.ambient = vd(0.5, 0.5, 0.5);
    const int floor = add_material(&s, 0.6, 0.6, 0.6, 0, 0, 1);
    add_plane(&s, floor, 0, 1, 0, 0);
    s.camera = (rt_camera){vd(0, 3, 8), vd(0, 0, 0), vd(0, 1, 0), from_d(30)};
    rt_scene_prepare(&s);
    rt_view v;
    rt_view_init(&v, &s.camera, N, N);
    const rt_params p = {.depth = 0, .mode = RT_MODE_PROBE};
    rt_stats st = {0};
    rt_sample a, b, out;
    rt_trace_pixel(&s, &v, &p, C - 1, C, &st, &a);
    a.flags = 0;
    const int thr8 = 16, base = a.hits[0].contrib[1];
    for (int d = -thr8 - 1; d <= thr8 + 1; d++) {
        b = a;
        b.hits[0].contrib[1] = (uint8_t)(base + d);
        for (int swap = 0; swap < 2; swap++) {
            rt_primary pri;
            st = (rt_stats){0};
            int r = rt_probe_point(&s, &v, &st, thr8, C, C, swap ? &b : &a, swap ? &a : &b,
                                   r_from_ratio(1, 2), 2, &pri, &out);
            if (d < -thr8 || d > thr8) {
                if (r != -1 || st.probes != 0)
                    fail_msg("ends %d apart (%s first) probed: %d", d, swap ? "b" : "a", r);
            } else if (r != 1 || st.probes != 1) {
                fail_msg("ends %d apart (%s first) not interpolated: %d", d, swap ? "b" : "a", r);
            }
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_glass_pane_normal), cmocka_unit_test(test_glass_ball_normal),
        cmocka_unit_test(test_mirror_ball_faces), cmocka_unit_test(test_total_internal_reflection),
        cmocka_unit_test(test_each_light_shadow), cmocka_unit_test(test_probe_disagree_both_ways),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
