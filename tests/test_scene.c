/* test_scene.c: unit tests of scene files: number parsing, timeline interpolation, effects on demand. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "scn.h"
#include "scn_parse.h"

static scn_file test_file;
static char test_err[640];

static const scn_desc *parse_ok(const char *text)
{
    int rc = scn_parse("t.scene", text, strlen(text), &test_file, test_err, sizeof test_err);
    if (rc != 0)
        print_error("unexpected parse error: %s\n", test_err);
    assert_int_equal(rc, 0);
    return &test_file.desc;
}

#define HEAD "camera eye 0 2 8 at 0 1 0\nmaterial m\n"

static void numbers_round_to_q16(void **state)
{
    (void)state;
    const scn_desc *d = parse_ok(HEAD "sphere s material m center 0.5 -1.25 4096 radius 0.0078125\n"
                                      "background 0.00001 0.000008 1\n");
    assert_int_equal(d->objects[0].center[0], 32768);
    assert_int_equal(d->objects[0].center[1], -81920);
    assert_int_equal(d->objects[0].center[2], 4096 * 65536);
    assert_int_equal(d->objects[0].radius, 512);
    assert_int_equal(d->background[0], 1); /* 0.65536 rounds up */
    assert_int_equal(d->background[1], 1); /* 0.524 rounds up */
    assert_int_equal(d->background[2], 65536);
    char buf[16];
    scn_format_q16(-81920, buf);
    assert_string_equal(buf, "-1.25");
    scn_format_q16(512, buf);
    assert_string_equal(buf, "0.007813");
    scn_format_q16(4096 * 65536, buf);
    assert_string_equal(buf, "4096");
}

/* One fov track (arity 1), keys given as (seconds, kind, value). */
static const scn_desc *fov_track(const char *keys)
{
    static char text[2048];
    snprintf(text, sizeof text, HEAD "sphere s material m center 0 0 0 radius 1\nduration 20\n%s",
             keys);
    return parse_ok(text);
}

static int32_t fov_at(const scn_desc *d, int32_t ms)
{
    int32_t v[3];
    assert_int_equal(d->ntracks, 1);
    scn_track_value(d, &d->tracks[0], ms, v);
    return v[0];
}

static void timeline_kinds_at_keys_between_and_past_the_ends(void **state)
{
    (void)state;
    const scn_desc *d = fov_track("key camera.fov 1 linear 20\n"
                                  "key camera.fov 3 smooth 60\n"
                                  "key camera.fov 5 step 40\n"
                                  "key camera.fov 7 linear 100\n");
    /* at the keys */
    assert_int_equal(fov_at(d, 1000), 20 * SCN_ONE);
    assert_int_equal(fov_at(d, 3000), 60 * SCN_ONE);
    assert_int_equal(fov_at(d, 5000), 40 * SCN_ONE);
    assert_int_equal(fov_at(d, 7000), 100 * SCN_ONE);
    /* before the first key and past the last: held */
    assert_int_equal(fov_at(d, 0), 20 * SCN_ONE);
    assert_int_equal(fov_at(d, 999), 20 * SCN_ONE);
    assert_int_equal(fov_at(d, 7001), 100 * SCN_ONE);
    assert_int_equal(fov_at(d, 20000), 100 * SCN_ONE);
    /* linear */
    assert_int_equal(fov_at(d, 2000), 40 * SCN_ONE);
    assert_int_equal(fov_at(d, 1500), 30 * SCN_ONE);
    /* smooth: 3u^2 - 2u^3, symmetric about the middle, at rest at both keys */
    assert_int_equal(fov_at(d, 4000), 50 * SCN_ONE);
    int32_t q1 = fov_at(d, 3500), q3 = fov_at(d, 4500); /* u = 1/4: 0.15625 */
    assert_true(q1 >= 56 * SCN_ONE + SCN_ONE * 7 / 8 - 2 &&
                q1 <= 56 * SCN_ONE + SCN_ONE * 7 / 8 + 2);
    assert_true(q1 - 50 * SCN_ONE >= 50 * SCN_ONE - q3 - 2 &&
                q1 - 50 * SCN_ONE <= 50 * SCN_ONE - q3 + 2);
    assert_true(60 * SCN_ONE - fov_at(d, 3010) < SCN_ONE / 100); /* barely moved after 10 ms */
    /* step: holds until the next key */
    assert_int_equal(fov_at(d, 5001), 40 * SCN_ONE);
    assert_int_equal(fov_at(d, 6999), 40 * SCN_ONE);
}

static void spline_passes_through_keys_and_keeps_lines_straight(void **state)
{
    (void)state;
    /* Evenly spaced keys on a line: Catmull-Rom reproduces the line. */
    const scn_desc *d = fov_track("key camera.fov 0 spline 20\nkey camera.fov 2 spline 40\n"
                                  "key camera.fov 4 spline 60\nkey camera.fov 6 spline 80\n");
    for (int32_t ms = 2000; ms <= 4000; ms += 125) {
        int32_t want = 20 * SCN_ONE + (int32_t)((int64_t)ms * 10 * SCN_ONE / 1000);
        int32_t got = fov_at(d, ms);
        assert_true(got - want <= 2 && want - got <= 2);
    }
    /* Uneven keys: passes through each, and flows through them (no jump in the slope). */
    d = fov_track("key camera.fov 0 spline 20\nkey camera.fov 1 spline 70\n"
                  "key camera.fov 4 spline 30\nkey camera.fov 5 spline 90\n");
    assert_int_equal(fov_at(d, 1000), 70 * SCN_ONE);
    assert_int_equal(fov_at(d, 4000), 30 * SCN_ONE);
    int32_t before = fov_at(d, 1000) - fov_at(d, 990), after = fov_at(d, 1010) - fov_at(d, 1000);
    assert_true(before - after < SCN_ONE / 50 && after - before < SCN_ONE / 50);
    /* Overshoot is clamped into the parameter's range (fov 10..120). */
    d = fov_track(
        "key camera.fov 0 spline 10\nkey camera.fov 1 spline 10\n"
        "key camera.fov 2 spline 120\nkey camera.fov 3 spline 120\nkey camera.fov 4 spline 10\n");
    for (int32_t ms = 0; ms <= 4000; ms += 50) {
        int32_t v = fov_at(d, ms);
        assert_true(v >= 10 * SCN_ONE && v <= 120 * SCN_ONE);
    }
}

static void eval_applies_tracks_of_every_owner(void **state)
{
    (void)state;
    const scn_desc *d =
        parse_ok(HEAD "duration 10\nlight l pos 0 5 0 color 1 1 1\n"
                      "sphere s material m center 0 1 0 radius 1\n"
                      "key s.center 0 linear 0 1 0\nkey s.center 10 linear 10 1 0\n"
                      "key m.reflect 0 linear 0\nkey m.reflect 10 linear 1\n"
                      "key l.color 0 step 1 0 0\n"
                      "key scene.background 0 linear 0 0 0\nkey scene.background 10 linear 1 1 1\n"
                      "key camera.eye 0 linear 0 2 8\nkey camera.eye 10 linear 0 4 8\n");
    static rt_scene s;
    scn_eval(d, 5000, &s);
    assert_true(r_abs(r_sub(s.objects[0].center.x, R(5))) < R(0.001));
    assert_true(r_abs(r_sub(s.materials[0].reflect, R(0.5))) < R(0.001));
    assert_true(r_abs(r_sub(s.lights[0].color.y, R(0))) < R(0.001));
    assert_true(r_abs(r_sub(s.background.z, R(0.5))) < R(0.001));
    assert_true(r_abs(r_sub(s.camera.eye.y, R(3))) < R(0.001));
    assert_true(s.effects & RT_FX_REFLECT);
    scn_eval(d, 0, &s);
    assert_false(s.effects & RT_FX_REFLECT); /* reflect is 0 at t = 0: nothing to mirror */
    assert_true(scn_effects_union(d) & RT_FX_REFLECT);
}

static const rt_scene *eval0(const char *text)
{
    static rt_scene s;
    scn_eval(parse_ok(text), 0, &s);
    return &s;
}

static void effects_derived_from_materials_and_geometry(void **state)
{
    (void)state;
    /* one object alone shadows nothing; no specular, no secondary rays, no texture */
    const rt_scene *s =
        eval0(HEAD "light l pos 5 5 5 color 1 1 1\nsphere a material m center 0 0 0 radius 1\n");
    assert_int_equal(s->effects, 0);
    assert_int_equal(s->reach_depth, 0);
    /* two spheres: shadows, by each other only */
    s = eval0(HEAD "light l pos 5 5 5 color 1 1 1\nsphere a material m center 0 1 0 radius 1\n"
                   "sphere b material m center 3 1 0 radius 1\n");
    assert_int_equal(s->effects, RT_FX_SHADOW);
    assert_int_equal(s->occluders[0], 3u);
    /* a floor under everything, the light above it: the floor shadows nothing */
    s = eval0(HEAD "light l pos 5 5 5 color 1 1 1\nplane f material m normal 0 1 0 offset 0\n"
                   "sphere a material m center 0 1 0 radius 1\n");
    assert_int_equal(s->occluders[0], 2u);
    /* the light below the floor: the floor is in the way of the sphere */
    s = eval0(HEAD "light l pos 5 -5 5 color 1 1 1\nplane f material m normal 0 1 0 offset 0\n"
                   "sphere a material m center 0 1 0 radius 1\n");
    assert_int_equal(s->occluders[0], 3u);
    /* a sphere reaching through the floor: the floor can shadow its lower part */
    s = eval0(HEAD "light l pos 5 5 5 color 1 1 1\nplane f material m normal 0 1 0 offset 0\n"
                   "sphere a material m center 0 0.5 0 radius 1\n");
    assert_int_equal(s->occluders[0], 3u);
    /* two crossing planes shadow each other; two parallel ones with the light between do not */
    s = eval0(HEAD "light l pos 1 1 1 color 1 1 1\nplane f material m normal 0 1 0 offset 0\n"
                   "plane w material m normal 1 0 0 offset 0\n");
    assert_int_equal(s->occluders[0], 3u);
    s = eval0(HEAD "light l pos 1 1 1 color 1 1 1\nplane f material m normal 0 1 0 offset 0\n"
                   "plane c material m normal 0 -1 0 offset -5\n");
    assert_int_equal(s->occluders[0], 0u);
    assert_false(s->effects & RT_FX_SHADOW);
    /* materials: specular needs a light; textures; noise only for noise textures */
    s = eval0("camera eye 0 2 8 at 0 1 0\nmaterial m specular 0.5 texture checker\n"
              "sphere a material m center 0 0 0 radius 1\n");
    assert_int_equal(s->effects, RT_FX_TEXTURE);
    s = eval0("camera eye 0 2 8 at 0 1 0\nlight l pos 5 5 5 color 1 1 1\n"
              "material m specular 0.5 texture wood scale 2\nsphere a material m center 0 0 0 "
              "radius 1\n");
    assert_int_equal(s->effects, RT_FX_SPECULAR | RT_FX_TEXTURE | RT_FX_NOISE);
    /* reachable recursion depth */
    s = eval0(
        "camera eye 0 2 8 at 0 1 0\nmaterial m reflect 0.5\nmaterial n\n"
        "sphere a material m center 0 0 0 radius 1\nsphere b material n center 3 0 0 radius 1\n");
    assert_int_equal(s->effects, RT_FX_REFLECT);
    assert_int_equal(s->reach_depth, 1); /* one convex mirror never sees itself */
    s = eval0(
        "camera eye 0 2 8 at 0 1 0\nmaterial m reflect 0.5\n"
        "sphere a material m center 0 0 0 radius 1\nsphere b material m center 3 0 0 radius 1\n");
    assert_int_equal(s->reach_depth, RT_MAX_DEPTH); /* two mirrors face each other */
    s = eval0("camera eye 0 2 8 at 0 1 0\nmaterial g transmit 0.9 ior 1.5\n"
              "sphere a material g center 0 0 0 radius 1\n");
    assert_int_equal(s->effects, RT_FX_REFLECT | RT_FX_REFRACT);
    assert_int_equal(s->reach_depth, RT_MAX_DEPTH); /* inside a glass ball rays bounce on */
    s = eval0("camera eye 0 2 8 at 0 1 0\nmaterial g transmit 0.9 ior 1.5\n"
              "plane a material g normal 0 1 0 offset 0\n");
    assert_int_equal(s->reach_depth, 1);
}

/* A frame's ray counts: the effects a scene does not need cost no ray. */
static void unused_effects_cast_no_rays(void **state)
{
    (void)state;
    enum { W = 48, H = 36 };
    static uint32_t pixels[W * H];
    struct {
        const char *text;
        int shadow, reflect, refract;
    } cases[] = {
        {HEAD "light l pos 5 5 5 color 1 1 1\nsphere a material m center 0 1 0 radius 1\n", 0, 0,
         0},
        {HEAD "light l pos 5 5 5 color 1 1 1\nplane f material m normal 0 1 0 offset 0\n"
              "sphere a material m center 0 1 0 radius 1\n",
         1, 0, 0}, /* the ball's shadow */
        {HEAD "light l pos 5 5 5 color 1 1 1\nsphere a material m center 0 1 0 radius 1\n"
              "sphere b material m center 2.5 1 0 radius 1\n",
         1, 0, 0},
        {"camera eye 0 2 8 at 0 1 0\nlight l pos 5 5 5 color 1 1 1\nmaterial m reflect 0.5\n"
         "sphere a material m center 0 1 0 radius 1\n",
         0, 1, 0},
        {"camera eye 0 2 8 at 0 1 0\nlight l pos 5 5 5 color 1 1 1\nmaterial g transmit 0.85 "
         "reflect 0.1 ior 1.5\n"
         "sphere a material g center 0 1 0 radius 1\n",
         1, 1, 1},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        static rt_scene s;
        scn_eval(parse_ok(cases[i].text), 0, &s);
        rt_view v;
        rt_view_init(&v, &s.camera, W, H);
        rt_params p = {.depth = 5, .min_contrib = 0, .mode = RT_MODE_FULL, .grid = 8};
        rt_stats st = {0};
        rt_render(&s, &v, &p, pixels, W, &st, NULL, NULL);
        assert_int_equal(st.rays_primary, W * H);
        assert_int_equal(st.rays_shadow > 0, cases[i].shadow);
        assert_int_equal(st.rays_reflect > 0, cases[i].reflect);
        assert_int_equal(st.rays_refract > 0, cases[i].refract);
        /* the same frame with every effect forced on: the same picture */
        static uint32_t forced[W * H];
        rt_scene_force_effects(&s);
        rt_stats sf = {0};
        rt_render(&s, &v, &p, forced, W, &sf, NULL, NULL);
        assert_memory_equal(pixels, forced, sizeof pixels);
        assert_true(sf.rays_shadow >= st.rays_shadow);
    }
}

/* Every example scene: its per-frame effects lie within the union over its timeline. */
static void example_scenes_effects_within_their_union(void **state)
{
    (void)state;
    static const char *const files[] = {"scenes/intro.scene",   "scenes/demo.scene",
                                        "scenes/diffuse.scene", "scenes/shadows.scene",
                                        "scenes/mirrors.scene", "scenes/glass.scene",
                                        "scenes/textures.scene"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        int rc = scn_load(files[i], &test_file, test_err, sizeof test_err);
        if (rc != 0)
            print_error("%s\n", test_err);
        assert_int_equal(rc, 0);
        const scn_desc *d = &test_file.desc;
        unsigned all = scn_effects_union(d);
        for (int32_t ms = 0; ms <= d->duration_ms; ms += 250) {
            static rt_scene s;
            scn_eval(d, ms, &s);
            assert_int_equal(s.effects & ~all, 0);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(numbers_round_to_q16),
        cmocka_unit_test(timeline_kinds_at_keys_between_and_past_the_ends),
        cmocka_unit_test(spline_passes_through_keys_and_keeps_lines_straight),
        cmocka_unit_test(eval_applies_tracks_of_every_owner),
        cmocka_unit_test(effects_derived_from_materials_and_geometry),
        cmocka_unit_test(unused_effects_cast_no_rays),
        cmocka_unit_test(example_scenes_effects_within_their_union),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
