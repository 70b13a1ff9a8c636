/* rt_cull.h: the culling data rt_scene_prepare derives from a scene (rt_scene.cull), the core's own.
 *
 * rt.h includes this header for rt_scene's layout only: callers never read or write these
 * fields. rt_scene_prepare (prepare.c) fills them and rt_view_cull reads the per-eye part; the
 * tracer (trace.c, shapes.c, rt_local.h) uses them to skip intersection tests that cannot
 * change a result. Every set only ever leaves out objects whose test would not report a hit
 * for the ray in question, so the pictures are those of testing every object.
 */
#ifndef FIXRAY_RT_CULL_H
#define FIXRAY_RT_CULL_H

#include <stdint.h>

#include "real.h"

typedef struct rt_scene_cull {
    /* Per light l and object j: the occluders[l] other than j that a shadow ray from a point
     * of j toward l can meet; each sphere left out has a rejection (shadow_cull) that refuses
     * every such ray, or lies wholly beyond the segment's reach (rt_scene_prepare). Every
     * object, j too, when forced. */
    uint32_t occ_of[RT_MAX_LIGHTS][RT_MAX_OBJECTS];
    int forced;           /* 1: every effect forced on, nothing skipped */
    uint32_t near_lights; /* bit i: a surface passes within RT_NEAR_LIGHT of light i (shadow
                             rays are then aimed with care) */
    /* Per light and sphere, a quick shadow-ray rejection (0: none): a shadow ray toward light
     * l along d certainly misses sphere i when c = center - light pos has c . d >= 0 or
     * (c . d)^2 < k, k > 0 (rt_scene_prepare), i.e. when r_cull_rejects(c . d,
     * shadow_cull[l][i]) for a non-zero entry (the test as the numeric layer prepares it). */
    rcull shadow_cull[RT_MAX_LIGHTS][RT_MAX_OBJECTS];
    /* Per sphere, for rays from the point eye_at (the camera's eye when prepared): eye_l =
     * centre - eye_at, and the same rejection as shadow_cull (eye_cull > 0 and tca <= 0 or
     * tca^2 < eye_cull: a miss). */
    vec3 eye_at;
    vec3 eye_l[RT_MAX_OBJECTS];
    wide eye_cull[RT_MAX_OBJECTS];
    /* Per sphere, the sine of the half-angle of the cone of directions from eye_at (around the
     * centre's) outside which eye_cull rejects every ray, 0 when it has none (rt_view_cull);
     * per plane, eye_num = offset - eye_at . normal, the signed distance plane_intersect forms. */
    real eye_cone[RT_MAX_OBJECTS];
    real eye_num[RT_MAX_OBJECTS];
    uint32_t plane_set; /* bit i: object i is a plane */
    /* A sphere around every sphere of the scene (bound_set: their bits, 0 when there are
     * fewer than two), with the shadow-ray rejection of one sphere (bound_shadow_cull[l], as
     * shadow_cull): a shadow ray it rejects misses every sphere inside, whose own tests are then
     * skipped. (Primary rays gain nothing from it: the view is mostly inside its cone.) */
    uint32_t bound_set;
    vec3 bound_center;
    real bound_radius;
    rcull bound_shadow_cull[RT_MAX_LIGHTS];
    /* Per light l, two planes through it (normals shadow_plane[l][0], [1]; zero when unused)
     * split the directions of its shadow rays into four quadrants: a ray toward the light along
     * d is in quadrant q = d3_below(d, n0) + 2 d3_below(d, n1). shadow_quad[l][q]: the
     * objects that can block a ray of quadrant q; every sphere left out has its shadow_cull cone
     * wholly on the other side of a plane, so its rejection would refuse the ray anyway. */
    dir3 shadow_plane[RT_MAX_LIGHTS][2];
    uint32_t shadow_quad[RT_MAX_LIGHTS][4];
    /* Secondary rays from a hit on sphere a (trace_secondary), by the octant of their direction
     * d, q = rt_octant(d): ray_oct[a][q] holds every object whose test can report a hit for such
     * a ray; each sphere left out lies wholly on one side of a coordinate plane through a's
     * neighbourhood, beyond the ray's reach for that octant (rt_scene_prepare: scene_ray_sets).
     * ray_in[a]: the objects that can be met no later than a's own hit by a ray from there (its
     * origin inside a: refracted in, or mirrored inside); every sphere left out is apart from a,
     * after every plane in the objects' order, so where a's test reports the nearest hit of
     * ray_in[a]'s objects it is the nearest of all. A plane's ray_oct, for its rays mirrored
     * off its front (rt_nearest_from), is every object but itself, its ray_in every object.
     * Every object everywhere when effects are forced. */
    uint32_t ray_oct[RT_MAX_OBJECTS][8];
    uint32_t ray_in[RT_MAX_OBJECTS];
    /* Per light l, bit a: sphere a is among the light's occluders and the light lies well
     * outside it, so that a point of a seen from inside whose offset start p_out lies within
     * dark_r[a] of the centre is in a's own shadow: its shadow ray, whatever its rounding, would
     * meet a (rt_light_reach; rt_scene_prepare: scene_ray_sets). */
    uint32_t dark_inside[RT_MAX_LIGHTS];
    real dark_r[RT_MAX_OBJECTS];
} rt_scene_cull;

#endif
