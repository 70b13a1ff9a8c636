/* demo.c: the built-in demo scene: six spheres over a checkered mirror floor, orbited by the camera. */
#include "rt.h"

#define C(r, g, b) v3(R(r), R(g), R(b))

static int demo_material(rt_scene *s, rt_material m)
{
    s->materials[s->nmaterials] = m;
    return s->nmaterials++;
}

static void demo_sphere(rt_scene *s, int material, vec3 center, real radius)
{
    rt_object *o = &s->objects[s->nobjects++];
    *o = (rt_object){.kind = RT_SPHERE, .material = (uint8_t)material};
    o->center = center;
    o->radius = radius;
}

void rt_demo_scene(rt_scene *s, int32_t time_ms)
{
    *s = (rt_scene){0};
    s->background = C(0.42, 0.55, 0.78);
    s->ambient = C(0.30, 0.30, 0.36);
    s->depth = 5;

    rt_material floor = {.diffuse = C(0.86, 0.83, 0.76), .ambient = R(0.5), .specular = R(0.2),
                         .shininess = 20, .reflect = R(0.3), .ior = R_ONE};
    floor.tex = (rt_texture){.kind = RT_TEX_CHECKER, .scale = R(0.25), .color2 = C(0.20, 0.24, 0.30)};
    rt_material mirror = {.diffuse = C(0.08, 0.08, 0.10), .ambient = R(0.5), .specular = R(0.8),
                          .shininess = 60, .reflect = R(0.75), .ior = R_ONE};
    rt_material glass = {.diffuse = C(0.04, 0.05, 0.05), .ambient = R(0.2), .specular = R(0.9),
                         .shininess = 120, .reflect = R(0.08), .transmit = R(0.85),
                         .ior = R(1.5)};
    rt_material marble = {.ambient = R(0.5), .specular = R(0.5), .shininess = 40, .ior = R_ONE};
    marble.tex = (rt_texture){.kind = RT_TEX_MARBLE, .palette = RT_PAL_MARBLE, .octaves = 4,
                              .scale = R(1.2), .turbulence = R(2.5)};
    rt_material wood = {.ambient = R(0.5), .specular = R(0.3), .shininess = 16, .ior = R_ONE};
    wood.tex = (rt_texture){.kind = RT_TEX_WOOD, .palette = RT_PAL_WOOD, .octaves = 3,
                            .scale = R(3.0), .turbulence = R(0.6)};
    rt_material lava = {.ambient = R(0.6), .specular = R(0.4), .shininess = 24, .ior = R_ONE};
    lava.tex = (rt_texture){.kind = RT_TEX_NOISE, .palette = RT_PAL_LAVA, .octaves = 4,
                            .scale = R(2.5), .turbulence = R_ONE};
    rt_material red = {.diffuse = C(0.85, 0.15, 0.12), .ambient = R(0.5), .specular = R(0.6),
                       .shininess = 30, .reflect = R(0.1), .ior = R_ONE};

    int m_floor = demo_material(s, floor);
    rt_object *pl = &s->objects[s->nobjects++];
    *pl = (rt_object){.kind = RT_PLANE, .material = (uint8_t)m_floor};
    pl->axis = C(0, 1, 0);
    pl->offset = 0;

    demo_sphere(s, demo_material(s, mirror), C(0, 1.5, 0), R(1.5));
    demo_sphere(s, demo_material(s, glass), C(2.6, 1.0, 1.8), R(1.0));
    demo_sphere(s, demo_material(s, marble), C(-2.6, 1.1, 1.4), R(1.1));
    demo_sphere(s, demo_material(s, wood), C(1.2, 0.8, -2.7), R(0.8));
    demo_sphere(s, demo_material(s, lava), C(-1.6, 0.6, -2.3), R(0.6));
    demo_sphere(s, demo_material(s, red), C(0.3, 0.35, 2.9), R(0.35));

    s->lights[0] = (rt_light){C(6.0, 9.0, 5.0), C(0.90, 0.85, 0.75)};
    s->lights[1] = (rt_light){C(-7.0, 6.0, -3.0), C(0.30, 0.35, 0.50)};
    s->nlights = 2;

    /* One orbit every RT_DEMO_PERIOD_MS, starting in front of the scene (+z). */
    int32_t phase = time_ms % RT_DEMO_PERIOD_MS;
    if (phase < 0)
        phase += RT_DEMO_PERIOD_MS;
    unit sn, cs;
    u_sincos_deg(r_from_ratio(phase * 360, RT_DEMO_PERIOD_MS), &sn, &cs);
    s->camera.eye = v3(r_mul_u(R(7.5), sn), R(7.5), r_mul_u(R(7.5), cs));
    s->camera.at = C(0, 0.6, 0);
    s->camera.up = C(0, 1, 0);
    s->camera.fov = R(50.0);
    rt_scene_prepare(s);
}
