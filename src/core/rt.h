/* rt.h: the ray tracer core's public interface: scene, view, render settings, statistics, frames and bands.
 * Whitted ray tracing as in the thesis: nearest hit, hard shadows from point lights, Phong
 * shading, reflection and refraction up to a depth limit, procedural textures, adaptive
 * subsampling. The core never allocates: every buffer is handed in. One source builds in float
 * and in fixed point (fixed/real.h). Fill an rt_scene, call rt_scene_prepare, set up an rt_view
 * (rt_view_init, rt_view_cull), render with rt_render or by bands. Core plumbing: rt_local.h. */
#ifndef FIXRAY_RT_H
#define FIXRAY_RT_H

#include <stdint.h>
#include "real.h"

/* A scene's limits; object sets are 32-bit masks: at most 32 objects. The boards define these to
 * their compiled scene's sizes (Makefile: BOARD_MAX_*; src/app/intro.c refuses more). */
#ifndef RT_MAX_OBJECTS
#define RT_MAX_OBJECTS 32
#endif
#ifndef RT_MAX_LIGHTS
#define RT_MAX_LIGHTS 4
#endif
#ifndef RT_MAX_MATERIALS
#define RT_MAX_MATERIALS 16
#endif
#define RT_MAX_DEPTH 8
/* Nodes of the ray tree stored per sample (primary hit first, then secondary hits in
 * depth-first order, refraction before reflection). Further nodes are counted, not stored. */
#define RT_SAMPLE_MAX_HITS 8
/* Object id recorded for a ray that leaves the scene. */
#define RT_NO_OBJECT 0xFF

typedef vec3 rt_color;

enum rt_texture_kind {
    RT_TEX_NONE,    /* plain diffuse colour */
    RT_TEX_CHECKER, /* 3D checkerboard of diffuse and color2 */
    RT_TEX_MARBLE,  /* sine veins disturbed by turbulence, through a palette */
    RT_TEX_WOOD,    /* rings around the y axis disturbed by noise, through a palette */
    RT_TEX_NOISE,   /* fBm noise straight through a palette */
    RT_TEX_COUNT
};

enum rt_palette_id { RT_PAL_MARBLE, RT_PAL_WOOD, RT_PAL_LAVA, RT_PAL_SKY, RT_PAL_COUNT };

typedef struct rt_texture {
    uint8_t kind;    /* enum rt_texture_kind */
    uint8_t palette; /* enum rt_palette_id */
    uint8_t octaves; /* noise octaves, 1..RT_NOISE_MAX_OCTAVES */
    uint8_t active;  /* rt_scene_prepare: 1 if it changes the colour (noise, 2-colour checker) */
    real scale;      /* texture features per scene unit */
    real turbulence; /* strength of the noise disturbance */
    rt_color color2; /* second colour of the checkerboard */
} rt_texture;

typedef struct rt_material {
    rt_color diffuse; /* r_d: diffuse colour (unless textured) */
    rt_texture tex;
    real ambient;          /* r_a: share of the ambient light reflected */
    real specular;         /* r_s in [0, 1] */
    uint16_t shininess;    /* h >= 1: highlight exponent */
    real reflect;          /* weight of the mirror ray, [0, 1] */
    real transmit;         /* weight of the refracted ray, [0, 1] */
    real ior;              /* index of refraction (inside / outside), in [1, 3] */
    real ior_inv;          /* 1 / ior, kept so that no ray divides */
    unit spec_zero;        /* u_pow(v, shininess) is exactly 0 for every v <= this */
    rt_color ambient_term; /* diffuse x scene ambient x ambient, as trace_ray forms it */
} rt_material;

enum rt_shape_kind { RT_SPHERE, RT_PLANE, RT_SHAPE_COUNT };

typedef struct rt_object {
    uint8_t kind;     /* enum rt_shape_kind */
    uint8_t material; /* index into rt_scene.materials */
    vec3 center;      /* sphere */
    real radius;
    real behind; /* sphere: tca below it: ray starts outside, sphere behind (rt_sphere_behind) */
    wide radius2;
    rinv inv_radius; /* sphere: for its normals (d3_norm_near), filled by rt_scene_prepare */
    vec3 axis;       /* plane: normal as given (any length) */
    real offset;     /* plane: points p with p . unit(axis) = offset */
    dir3 normal;     /* plane: unit(axis), filled by rt_scene_prepare */
} rt_object;

typedef struct rt_light {
    vec3 pos;
    rt_color color;
} rt_light;

typedef struct rt_camera {
    vec3 eye, at, up;
    real fov; /* vertical field of view, degrees, in [10, 120] */
} rt_camera;

/* Effects a scene may need (bits): the tracer skips the code of those not in rt_scene.effects
 * (rt_scene_prepare derives them, or all forced on). Macros: the preprocessor tests them. */
#define RT_FX_SHADOW 1u   /* shadow rays: some object can come between a light and a surface */
#define RT_FX_SPECULAR 2u /* Phong highlights: some material has specular > 0 */
#define RT_FX_REFLECT 4u  /* mirror rays: some material reflects (or transmits: total reflection) */
#define RT_FX_REFRACT 8u  /* refracted rays: some material transmits */
#define RT_FX_TEXTURE 16u /* some material is textured */
#define RT_FX_NOISE 32u   /* some texture uses Perlin noise (marble, wood, noise) */
#define RT_FX_ALL 63u

/* Effects compiled in: a compiled-in scene (scenec) sets its timeline's; others are not linked. */
#ifndef RT_COMPILED_EFFECTS
#define RT_COMPILED_EFFECTS RT_FX_ALL
#endif

#include "rt_cull.h" /* rt_scene_cull, the core's own part of rt_scene */

typedef struct rt_scene {
    rt_color background;
    rt_color ambient;
    int depth; /* recursion limit of the scene */
    int nobjects, nlights, nmaterials;
    rt_object objects[RT_MAX_OBJECTS];
    rt_light lights[RT_MAX_LIGHTS];
    rt_material materials[RT_MAX_MATERIALS];
    rt_camera camera;
    /* Derived by rt_scene_prepare (or rt_scene_force_effects): */
    unsigned effects;                  /* RT_FX_* bits the frame needs */
    int reach_depth;                   /* recursion depth the materials can reach */
    uint32_t occluders[RT_MAX_LIGHTS]; /* per light: objects that can shadow something */
    rt_scene_cull cull;                /* the tracer's culling data (rt_cull.h) */
} rt_scene;

/* Tiles per row and column of rt_view's candidate sets: the tiles are the smallest power-of-two
 * squares (at least 4 pixels) that keep both counts within it. */
#ifndef RT_PIXEL_RGB24
#define RT_PIXEL_RGB24 0 /* 1: pixels of 3 bytes, R, G, B (rt_local.h, rt_px) */
#endif

#ifndef RT_VIEW_TILES
#define RT_VIEW_TILES 40 /* the Cortex-M boards' 128x64 frames need 32 (Makefile) */
#endif

/* The camera prepared for one image size: primary ray of pixel (x, y) is
 * eye + t * unit(fwd + right * step*(2x+1-w) + up * step*(h-2y-1)). */
typedef struct rt_view {
    vec3 eye;
    dir3 fwd, right, up;
    ustep step;    /* tan(fov/2) / height */
    real pixel;    /* a pixel's width at distance 1, 2 tan(fov/2) / height (noise footprint) */
    real tan_half; /* tan(fov/2) */
    int width, height;
    /* Candidate sets per tile (rt_view_cull; rt_local.h: rt_view_candidates), for primary rays
     * and their reflections off plane mirror_plane (-1: none). */
    int cull_shift;
    uint32_t cull_cols[RT_VIEW_TILES], cull_rows[RT_VIEW_TILES];
    int mirror_plane;
    uint32_t mirror_cols[RT_VIEW_TILES], mirror_rows[RT_VIEW_TILES];
    /* Small spheres (rt_view_cull): bit i when sphere i's outline lies within the pixels box[i]
     * (x0, y0, x1, y1, inclusive); a square overlapping it with no corner on it is split. */
    uint32_t small;
    int16_t box[RT_MAX_OBJECTS][4];
    /* Checker planes (rt_view_cull): the largest square side, in pixels (a power of two), over
     * which plane i's cell ids (rt_sample.cell) tell its cells apart everywhere in the frame; 0
     * where the cells can be finer (up to the horizon): each square is tested. 255 for other
     * objects. */
    uint8_t cell_side[RT_MAX_OBJECTS];
    /* Pools of light (rt_view_cull): bit i when light i lies so close to plane pool_plane[i]
     * that the peak of its light there, under it, is thinner than a square in the frame:
     * pool_box[i] (x0, y0, x1, y1, inclusive) bounds it; a square overlapping it with a corner on
     * the plane is split down to its pixels. */
    uint32_t pool;
    uint8_t pool_plane[RT_MAX_LIGHTS];
    int16_t pool_box[RT_MAX_LIGHTS][4];
} rt_view;

/* One node of the ray tree as adaptive subsampling compares it. */
typedef struct rt_hit_rec {
    uint8_t object;     /* object index, or RT_NO_OBJECT */
    uint8_t level;      /* recursion level (low 4 bits; 0 = primary), checker cell (high 4) */
    uint8_t contrib[3]; /* this node's local colour times its weight in the pixel, 0..255 */
} rt_hit_rec;

/* Everything traced for one image point, as adaptive subsampling compares it (60 bytes). */
typedef struct rt_sample {
    rt_color color;
    union {
        struct {
            uint8_t nhits;  /* nodes of the ray tree (saturates at 255); 0 = not traced yet */
            uint8_t lights; /* at the primary hit, 2 bits per light (rt_light_state) */
            uint8_t cell;   /* texture cell at the primary hit (checker), 0 for other textures */
            uint8_t flags;  /* probe mode: RT_SAMPLE_PROBED, RT_SAMPLE_OPAQUE (0 in other modes) */
        };
        uint32_t head; /* the four bytes above as one word: rt_corners_differ's first compare */
    };
    rt_hit_rec hits[RT_SAMPLE_MAX_HITS]; /* the first nodes, up to RT_SAMPLE_MAX_HITS */
    uint8_t alt[3];    /* adaptive and probe mode: what alt_known says (rt_local.h) */
    uint8_t alt_known; /* enum rt_alt */
} rt_sample;

/* Adaptive squares: powers of two up to RT_GRID_MAX; level 0 is --grid, level k halved k times. */
#define RT_GRID_MAX 16
#define RT_GRID_LEVELS 4
/* The largest grid a build renders: less on the Cortex-M boards (src/app/intro.c refuses more). */
#ifndef RT_GRID_BUILD_MAX
#define RT_GRID_BUILD_MAX RT_GRID_MAX
#endif

/* full: every pixel traced; adaptive: the thesis' subsampling; probe: subsampling whose new
 * points are probed first and shaded only where needed (probe.c). */
enum rt_mode { RT_MODE_FULL, RT_MODE_ADAPTIVE, RT_MODE_PROBE };

/* The name of a mode as --mode takes it: "full", "adaptive" or "probe". */
static inline const char *rt_mode_name(int mode)
{
    return mode == RT_MODE_FULL ? "full" : mode == RT_MODE_PROBE ? "probe" : "adaptive";
}

/* How a frame is rendered. */
typedef struct rt_params {
    int depth;        /* recursion limit, 0..RT_MAX_DEPTH */
    real min_contrib; /* secondary rays of less weight in the pixel are not cast (0: cast all) */
    int mode;         /* enum rt_mode */
    int grid;         /* adaptive: size of the top-level squares, 2, 4, 8 or 16 */
    real threshold;   /* adaptive: split when a node's contribution differs by more than this
                         between corners (colour units, 0..1; 1 disables the criterion) */
    int octaves;      /* noise octaves: each texture sums min(its own, this); 0 = its own */
    int footprint;    /* 1: noise octaves finer than a pixel's footprint are left out */
} rt_params;

/* Why the corners of a square disagree, in the order the criteria are checked. */
enum rt_split_reason {
    RT_SPLIT_NONE,      /* the corners agree: interpolate */
    RT_SPLIT_OBJECT,    /* primary object, or its checker cell, differs */
    RT_SPLIT_LIGHT,     /* a highlight, or lit and unlit corners whose colours differ */
    RT_SPLIT_SECONDARY, /* the ray tree differs where its nodes' colours show it */
    RT_SPLIT_CONTRIB,   /* a node's contribution differs by more than the threshold */
    RT_SPLIT_COUNT      /* the number of reasons, RT_SPLIT_NONE included */
};

/* What a frame cost; rt_render adds to it (from squares on: adaptive and probe mode only). */
typedef struct rt_stats {
    uint32_t rays_primary, rays_shadow, rays_reflect, rays_refract;
    uint32_t shadow_tests;                    /* object intersection tests made by shadow rays */
    uint32_t noise_octaves;                   /* noise octaves summed by the textures evaluated */
    uint32_t squares[RT_GRID_LEVELS];         /* squares examined at each level */
    uint32_t split[RT_GRID_LEVELS];           /* of those, split into four */
    uint32_t split_by[RT_SPLIT_COUNT];        /* splits by enum rt_split_reason */
    uint32_t probes;                          /* probe mode: points probed (rt_probe_point) */
    uint32_t texture_squares, texture_pixels; /* filled by checker cell; cells looked up */
    uint32_t noise_squares, noise_pixels;     /* filled by noise texture; textures evaluated */
    uint32_t shadow_squares, shadow_pixels;   /* filled by one light's shadow; lights tested */
    uint32_t centre_tests; /* 2x2 squares split for contributions whose centre was traced */
    uint32_t contrib_kept; /* of those, filled unsplit (rt_centre_smooth) */
    uint32_t local_points; /* points whose primary hit's local part was interpolated */
} rt_stats;

/* Fills the derived fields of objects and materials (radius2, plane normal, ior_inv, spec_zero),
 * effects, reach_depth, occluders and cull. Call it again whenever the scene changes. */
void rt_scene_prepare(rt_scene *s);

/* After rt_scene_prepare: every effect on, the path effects on demand is measured against. */
void rt_scene_force_effects(rt_scene *s);

/* 0 when eye and look-at point coincide (an animated camera can, between keys): no view. */
int rt_view_ok(const rt_camera *cam);

/* Sets up the primary-ray frame for an image of width x height pixels. Without rt_view_ok(cam)
 * the camera looks down -z; an up vector of zero, or along the view, is replaced. */
void rt_view_init(rt_view *v, const rt_camera *cam, int width, int height);

/* Fills the view's candidate sets for prepared scene s and the view's eye: same pictures, fewer
 * intersection tests. Call again when scene or view changes; rt_view_init resets them to all. */
void rt_view_cull(rt_view *v, const rt_scene *s);

/* Bytes of working storage rt_render needs for frames `width` pixels wide: in adaptive mode
 * two rows of square corners and the samples of one square; 0 in full mode. */
unsigned long rt_render_work_size(const rt_params *p, int width);

/* Renders a frame of v->width x v->height into `pixels` (0x00RRGGBB, `stride` pixels per row)
 * in p->mode. Adaptive and probe mode need `work`, rt_render_work_size(p, width) bytes aligned
 * for rt_sample. `traced`, if not NULL, gets one byte per pixel (`width` per row): the
 * RT_TRACED_ bits of every way the point was traced (the same for any number of bands). */
#define RT_TRACED_FULL 1  /* shaded in full */
#define RT_TRACED_PROBE 2 /* only probed (probe mode) */
#define RT_TRACED_LOCAL 4 /* shaded with its local part from its square's corners (local_points) */
void rt_render(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
               int stride, rt_stats *stats, void *work, uint8_t *traced);

/* Renders band `band` of `nbands` horizontal bands (rows of grid squares, or of pixels in full
 * mode): disjoint pixels, at the same time if each has its own `work` and `stats`; together
 * rt_render's frame byte for byte. `traced` is cleared before the first band (bits are added
 * atomically). Corners on a band edge are traced by both bands (not so rt_render_band_edges). */
void rt_render_band(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
                    int stride, rt_stats *stats, void *work, uint8_t *traced, int band, int nbands);

/* Bands that trace no point twice: the corner rows on the band edges (rt_render_edge_size bytes
 * in `edges`, 0 in full mode) are traced first by rt_render_edge, row e = 0..nbands in any order
 * or at once; rt_render_band_edges then renders a band taking those rows from `edges`. The same
 * picture and summed stats as rt_render, for any nbands <= rt_render_band_count. */
unsigned long rt_render_edge_size(const rt_params *p, int width, int nbands);
void rt_render_edge(const rt_scene *s, const rt_view *v, const rt_params *p, rt_stats *stats,
                    void *edges, uint8_t *traced, int e, int nbands);
void rt_render_band_edges(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
                          int stride, rt_stats *stats, void *work, const void *edges,
                          uint8_t *traced, int band, int nbands);

/* The most bands a frame of `height` rows splits into (more bands leave some empty). */
int rt_render_band_count(const rt_params *p, int height);

/* The pixel rows band `band` of `nbands` of rt_render_band writes in a frame of `height` rows:
 * rows *y0 .. *y0 + *rows - 1 (*rows = 0: an empty band). Bands in order cover the frame. */
void rt_render_band_rows(const rt_params *p, int height, int band, int nbands, int *y0, int *rows);

/* rt_render_band into memory holding only the band: `rows` is its first row (y0 of
 * rt_render_band_rows), rows `stride` pixels apart. With `keep`, the previous call with this
 * `work` rendered band - 1 of the same frame and the shared row of corners is taken from `work`:
 * bands in order trace and give what one rt_render does, with no frame in RAM. */
void rt_render_band_into(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *rows,
                         int stride, rt_stats *stats, void *work, uint8_t *traced, int band,
                         int nbands, int keep);

#endif
