/* rt.h: the ray tracer core: scene description, per-sample record and tracing entry points.
 *
 * Whitted ray tracing as in the thesis: nearest hit, hard shadows from point lights, Phong
 * shading, reflection and refraction up to a depth limit, procedural textures. The core
 * never allocates, sleeps or polls; every buffer is handed in by the caller. The same source
 * builds in float and in fixed point through fixed/real.h.
 */
#ifndef FIXRAY_RT_H
#define FIXRAY_RT_H

#include <stdint.h>

#include "real.h"

/* Objects a scene may have: at most 32 (sets of objects are 32-bit masks). The boards, which
 * play only the scene compiled into them, define it smaller to save RAM (Makefile:
 * BOARD_MAX_OBJECTS; src/app/intro.c refuses a compiled scene with more). */
#ifndef RT_MAX_OBJECTS
#define RT_MAX_OBJECTS 32
#endif
#if RT_MAX_OBJECTS > 32 || RT_MAX_OBJECTS < 1
#error "RT_MAX_OBJECTS must be 1..32: sets of objects are 32-bit masks"
#endif
/* Lights and materials a scene may have; the Cortex-M boards define them to their compiled
 * scene's (Makefile: BOARD_MAX_LIGHTS, BOARD_MAX_MATERIALS; intro.c refuses a scene with more). */
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
/* A light's state becomes 2 (highlight) when its specular term exceeds this. */
#define RT_HIGHLIGHT_MIN R(0.125)
/* Noise pixels: the largest lighting factor A a sample keeps (as A / 2 in a byte). */
#define RT_NOISE_A_MAX R(2.0)

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
    uint8_t active;  /* set each frame by rt_scene_prepare: 1 when the texture changes the
                        colour (a noise texture, a checker whose two colours differ); 0 for none,
                        or a checker of one colour (no cell edge to see: no cells either) */
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
    real behind; /* sphere: a ray with tca below it starts outside, the sphere behind it
                    (rt_sphere_behind(radius), filled by rt_scene_prepare) */
    wide radius2;
    rinv inv_radius; /* sphere: for its normals (d3_norm_near), filled by rt_scene_prepare */
    vec3 axis;       /* plane: normal as given (any length) */
    real offset;     /* plane: points p with p . unit(axis) = offset */
    dir3 normal;     /* plane: unit(axis), filled by rt_scene_prepare */
} rt_object;

/* A sphere's rt_object.behind: -(radius + 2^-10 + radius 2^-13). A ray whose tca = l . d (as the
 * sphere test forms it) is below this starts outside the sphere (shapes.c: sphere_hit). */
static inline real rt_sphere_behind(real radius)
{
    return r_neg(r_add(r_add(radius, R(0.0009765625)), r_shr(radius, 13)));
}

typedef struct rt_light {
    vec3 pos;
    rt_color color;
} rt_light;

typedef struct rt_camera {
    vec3 eye, at, up;
    real fov; /* vertical field of view, degrees, in [10, 120] */
} rt_camera;

/* Effects a scene may need (bits); the tracer skips the code of every effect not in
 * rt_scene.effects. Derived from the scene by rt_scene_prepare (effects on demand), or all
 * forced on. Macros rather than an enum: RT_COMPILED_EFFECTS is tested by the preprocessor. */
#define RT_FX_SHADOW 1u   /* shadow rays: some object can come between a light and a surface */
#define RT_FX_SPECULAR 2u /* Phong highlights: some material has specular > 0 */
#define RT_FX_REFLECT 4u  /* mirror rays: some material reflects (or transmits: total reflection) */
#define RT_FX_REFRACT 8u  /* refracted rays: some material transmits */
#define RT_FX_TEXTURE 16u /* some material is textured */
#define RT_FX_NOISE 32u   /* some texture uses Perlin noise (marble, wood, noise) */
#define RT_FX_ALL 63u

/* Effects compiled into the tracer: a scene compiled into the program (scenec) defines this
 * to the effects of its whole timeline, and the code of the others is not linked at all. */
#ifndef RT_COMPILED_EFFECTS
#define RT_COMPILED_EFFECTS RT_FX_ALL
#endif
#if (RT_COMPILED_EFFECTS) > RT_FX_ALL
#error "RT_COMPILED_EFFECTS must be a set of enum rt_effect bits"
#endif

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
    /* Per light l and object j: the occluders[l] other than j that a shadow ray from a point
     * of j toward l can meet; each sphere left out has a rejection (shadow_cull) that refuses
     * every such ray, or lies wholly beyond the segment's reach (rt_scene_prepare). Every
     * object, j too, when forced. */
    uint32_t occ_of[RT_MAX_LIGHTS][RT_MAX_OBJECTS];
    int forced;           /* 1: every effect forced on, nothing skipped */
    uint32_t near_lights; /* bit i: a surface passes within RT_NEAR_LIGHT of
                                           light i (shadow rays are then aimed with care) */
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
} rt_scene;

/* The octant of direction d, as rt_scene.ray_oct indexes it: bit k set where component k (x,
 * y, z) is negative. */
static inline unsigned rt_octant(dir3 d)
{
    return (unsigned)(d.x < 0) | (unsigned)(d.y < 0) << 1 | (unsigned)(d.z < 0) << 2;
}

/* Is p the point the scene was prepared for (eye_at), exactly? Only rays from it may use the
 * per-eye data (eye_l, eye_cull, eye_num: rt_nearest_primary, rt_view_cull). */
static inline int rt_scene_at_eye(const rt_scene *s, vec3 p)
{
    return p.x == s->eye_at.x && p.y == s->eye_at.y && p.z == s->eye_at.z;
}

/* Tiles per row and per column of rt_view's candidate sets: a frame's tiles are the smallest
 * power-of-two squares (at least 4 pixels) that keep both counts within it. */
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
    /* Primary-ray candidates (rt_view_cull): the objects whose test can find pixel (x, y)'s
     * primary ray a hit are among the bits of cull_cols[x >> cull_shift] &
     * cull_rows[y >> cull_shift] (every bit set until rt_view_cull). */
    int cull_shift;
    uint32_t cull_cols[RT_VIEW_TILES], cull_rows[RT_VIEW_TILES];
    /* Mirror candidates (rt_view_cull): when pixel (x, y)'s primary ray from the prepared eye
     * meets plane mirror_plane (-1: none) from the front as its nearest hit, the objects whose
     * test can find the reflected ray trace_secondary casts from there a hit are among the bits
     * of mirror_cols[x >> cull_shift] & mirror_rows[y >> cull_shift]. */
    int mirror_plane;
    uint32_t mirror_cols[RT_VIEW_TILES], mirror_rows[RT_VIEW_TILES];
} rt_view;

/* The objects rt_nearest_primary must test for pixel (x, y) of the view. */
static inline uint32_t rt_view_candidates(const rt_view *v, int x, int y)
{
    return v->cull_cols[x >> v->cull_shift] & v->cull_rows[y >> v->cull_shift];
}

/* The objects the reflection off v->mirror_plane of pixel (x, y)'s primary ray must test. */
static inline uint32_t rt_view_mirror_candidates(const rt_view *v, int x, int y)
{
    return v->mirror_cols[x >> v->cull_shift] & v->mirror_rows[y >> v->cull_shift];
}

/* One node of the ray tree as adaptive subsampling compares it. */
typedef struct rt_hit_rec {
    uint8_t object;     /* object index, or RT_NO_OBJECT */
    uint8_t level;      /* recursion level, 0 = primary */
    uint8_t contrib[3]; /* this node's local colour times its weight in the pixel, 0..255 */
} rt_hit_rec;

/* Everything traced for one image point: the record adaptive subsampling compares. Kept
 * small (60 bytes) because a row of squares' worth of them is the working storage. */
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
    /* alt_known 1 (adaptive and probe mode, a primary hit on a two-tone checker seen from the
     * prepared eye): alt is the colour the point would have in a cell of the other colour (the
     * same lights, highlights and secondary rays, the other diffuse colour) as the bytes of a
     * pixel (r_to_byte of each channel: red, green, blue). alt_known 2 (adaptive and probe
     * mode, a primary hit on a noise texture seen from the prepared eye, no secondary ray:
     * nhits 1): the colour is
     * b x A + B, b the texture's colour at the hit, A the lighting that multiplies it (ambient
     * and Lambert terms) and B the rest (highlights); alt holds A / 2 as bytes (r_to_byte,
     * A <= RT_NOISE_A_MAX) and hits[1].contrib, the node past the tree, B as bytes (clamped to [0, 1]: a B
     * of 1 or more gives a pixel of 1 whatever b x A adds). Else 0. */
    uint8_t alt[3];
    uint8_t alt_known;
} rt_sample;

/* The colour of a checker cell (rt_sample.cell, non-zero): 1 for the texture's color2, 0 for
 * the diffuse colour (the parity of the cell's coordinates, rt_texture_color). */
static inline int rt_cell_tone(uint8_t cell)
{
    unsigned c = (unsigned)cell - 1;
    return (int)((c ^ c >> 2 ^ c >> 4) & 1);
}

#if RT_MAX_LIGHTS > 4
#error "rt_sample.lights holds the states of at most 4 lights"
#endif
/* rt_sample.flags: the colour was reconstructed from a probe, not shaded */
#define RT_SAMPLE_PROBED 1u
/* rt_sample.flags: a shaded sample whose record cannot stand for its neighbours' colours (on a
 * noise texture, a texture beyond the primary hit, a highlight: rt_probe_opaque) */
#define RT_SAMPLE_OPAQUE 2u

/* Light i's state at a sample's primary hit: 0 unlit, 1 lit, 2 highlight. */
static inline int rt_light_state(const rt_sample *sm, int i) { return sm->lights >> (2 * i) & 3; }
/* The bits of rt_sample.lights that are set only by a highlight (state 2). */
#define RT_LIGHTS_HIGHLIGHT 0xAAu

/* Adaptive subsampling: square sizes are powers of two up to RT_GRID_MAX; level 0 is the
 * --grid square, level k its halves k times over. */
#define RT_GRID_MAX 16
#define RT_GRID_LEVELS 4
/* The largest grid a build renders (the size of the per-square arrays on the stack of
 * subsample.c): RT_GRID_MAX, or less on a board that offers only smaller grids (the Cortex-M
 * boards: 8) and refuses the others before rendering (rt_render_adaptive draws nothing then). */
#ifndef RT_GRID_BUILD_MAX
#define RT_GRID_BUILD_MAX RT_GRID_MAX
#endif

/* full: every pixel traced; adaptive: the thesis' adaptive subsampling; probe: adaptive
 * subsampling whose new points are probed first and shaded only where needed (probe.c). */
enum rt_mode { RT_MODE_FULL, RT_MODE_ADAPTIVE, RT_MODE_PROBE };

/* Are the shadow rays' narrower occluder sets compiled in: per object (rt_scene.occ_of,
 * scene_shadow_pairs) and per quadrant of directions (shadow_quad, scene_shadow_quads)? The
 * intro player defines this to 0 (its 64 kB): a shadow ray from object j then tests every
 * occluder but j itself, as rt_light_reach forms it, the rejections of each sphere deciding.
 * The pictures are the same: the sets leave out only spheres whose rejection (shadow_cull)
 * refuses the ray anyway, or that lie beyond its reach (rt_scene_prepare; test_shapes). */
#ifndef RT_SHADOW_SETS
#define RT_SHADOW_SETS 1
#endif

/* Are the secondary rays' candidate sets (rt_scene.ray_oct, ray_in) compiled in? Off with the
 * shadow sets (the intro player): every secondary ray then tests every object, with the same
 * hits (the sets leave out only objects whose test cannot change the nearest hit). */
#ifndef RT_RAY_SETS
#define RT_RAY_SETS RT_SHADOW_SETS
#endif

/* Is probe mode compiled in? The intro player (build/intro-*), which renders adaptively only,
 * defines this to 0 to stay within its 64 kB: rt_render then takes RT_MODE_PROBE as adaptive. */
#ifndef RT_COMPILED_PROBE
#define RT_COMPILED_PROBE 1
#endif

/* Do the per-object occluder sets leave out a plane that cannot come between a resting
 * sphere's lit points and the light (scene_shadow_pairs)? Pictures are the same either way;
 * the intro player (build/intro-*) defines this to 0 to stay within its 64 kB. */
#ifndef RT_PLANE_CULL
#define RT_PLANE_CULL 1
#endif

/* The name of a mode as --mode takes it: "full", "adaptive" or "probe". */
static inline const char *rt_mode_name(int mode)
{
    return mode == RT_MODE_FULL ? "full" : mode == RT_MODE_PROBE ? "probe" : "adaptive";
}

/* How a frame is rendered. */
typedef struct rt_params {
    int depth;        /* recursion limit, 0..RT_MAX_DEPTH */
    real min_contrib; /* adaptive recursion control: secondary rays whose weight in the pixel
                         is below this are not cast (0 = cast every ray) */
    int mode;         /* enum rt_mode */
    int grid;         /* adaptive: size of the top-level squares, 2, 4, 8 or 16 */
    real threshold;   /* adaptive: split when a node's contribution differs by more than this
                         between corners (colour units, 0..1; 1 disables the criterion) */
    int octaves;      /* cap on noise octaves: each texture sums min(its octaves, this);
                         0 = every texture's own (the scene's) */
    int footprint;    /* 1: noise octaves finer than a pixel's footprint are left out */
} rt_params;

/* Why the corners of a square disagree, in the order the criteria are checked. */
enum rt_split_reason {
    RT_SPLIT_NONE,      /* the corners agree: interpolate */
    RT_SPLIT_OBJECT,    /* primary object, or its checker cell, differs */
    RT_SPLIT_LIGHT,     /* a highlight at some corners, or lit and unlit corners whose
                           contributions differ by more than half the threshold */
    RT_SPLIT_SECONDARY, /* the ray tree's shape or an object at a secondary level differs, in
                           a node contributing more than half the threshold, or with
                           contributions differing by more than that */
    RT_SPLIT_CONTRIB,   /* a node's contribution differs by more than the threshold */
    RT_SPLIT_COUNT      /* the number of reasons, RT_SPLIT_NONE included */
};

typedef struct rt_stats {
    uint32_t rays_primary, rays_shadow, rays_reflect, rays_refract;
    uint32_t shadow_tests;             /* object intersection tests made by shadow rays */
    uint32_t noise_octaves;            /* noise octaves summed by the textures evaluated (each noise
                               texture at a point adds the octaves it sums) */
    uint32_t squares[RT_GRID_LEVELS];  /* adaptive: squares examined at each level */
    uint32_t split[RT_GRID_LEVELS];    /* adaptive: of those, split into four */
    uint32_t split_by[RT_SPLIT_COUNT]; /* adaptive: splits by enum rt_split_reason */
    uint32_t probes;                   /* probe mode: points probed (rt_probe_point) */
    uint32_t texture_squares; /* adaptive: squares split only by checker cells, filled instead
                                 with the cell of each pixel (subsample.c) */
    uint32_t texture_pixels;  /* adaptive: pixels of those squares whose cell was looked up */
    uint32_t noise_squares;   /* adaptive: squares on a noise texture split only by its colour,
                                 filled instead with each pixel's own texture (subsample.c) */
    uint32_t noise_pixels;    /* adaptive: pixels of those squares whose texture was evaluated */
    uint32_t shadow_squares;  /* adaptive: squares split only by one light's shadow edge, filled
                                 instead with each pixel's own test of that light (subsample.c) */
    uint32_t shadow_pixels;   /* adaptive: pixels of those squares whose light was tested */
    uint32_t centre_tests;    /* adaptive: 2x2 squares split only for contributions whose
                                 centre was traced first for the centre test (subsample.c) */
    uint32_t contrib_kept;    /* adaptive: of those, filled unsplit (rt_centre_smooth) */
    uint32_t local_points;    /* adaptive and probe: points of squares split for their secondary
                                 rays whose primary hit's local part was interpolated (ss_local) */
} rt_stats;

/* A light closer than this to a surface gets shadow rays aimed from their offset origin: the
 * plain ray from an offset origin along the direction from the hit point ends up to
 * 2 R_EPS_OFFSET from the light, which could put its end behind that surface. */
#define RT_NEAR_LIGHT r_muli(R_EPS_OFFSET, 4)

/* Marks a helper the tracer keeps out of line on 32-bit ARM, where its loop would otherwise
 * spill the ray to the stack (fewer instructions there, measured under QEMU); elsewhere (x86-64,
 * twice the registers) inlining it measured cheaper, so the compiler decides. */
#if defined(__arm__)
#define RT_OUT_OF_LINE __attribute__((noinline))
#else
#define RT_OUT_OF_LINE
#endif

/* Per-type interface: every shape is shaded through this table. */
typedef struct rt_shape_ops {
    /* Outward unit normal at a point p on the surface. */
    dir3 (*normal)(const rt_object *o, vec3 p);
} rt_shape_ops;

extern const rt_shape_ops rt_shapes[RT_SHAPE_COUNT];

/* Object o's nearest hit at distance t in (0, tmax): returns 1 and sets *t, else returns 0: the
 * test the tracer's searches (rt_nearest_set, rt_nearest_primary) make, for one object (the
 * tests and tools; the searches inline it). The ray starts at a ray origin of the tracer and
 * tmax is at most 30573, the longest shadow segment (docs/numerics.md: the sphere test's
 * unchecked arithmetic relies on both). */
int rt_intersect(const rt_object *o, vec3 org, dir3 d, real tmax, real *t);

/* rt_shapes[RT_SPHERE].normal with the point passed in place: the tracer's direct call (no
 * table, no copy of the point); a plane's normal is its rt_object.normal. */
dir3 rt_sphere_normal(const rt_object *o, const vec3 *p);

/* Fills the derived fields of objects and materials (radius2, plane normal, ior_inv, spec_zero) and
 * derives the effects the scene needs: effects, reach_depth, occluders and occ_of. */
void rt_scene_prepare(rt_scene *s);

/* The frame's mirror for rt_view_cull's mirror candidates: the first plane whose material
 * reflects or transmits, with the prepared eye (eye_at) on its front side, when the scene needs
 * reflected rays and its effects are not forced; -1 when there is none. */
int rt_scene_mirror(const rt_scene *s);

/* For the mirror plane `pl` (rt_scene_mirror) and sphere i: the sine of the half-angle of a
 * cone of directions from eye_at around *l (set to the mirrored centre - eye_at) that holds the
 * direction d of every primary ray from eye_at whose reflection off the front of the plane,
 * as trace_secondary casts it from the ray's nearest hit there, the sphere test can find a hit
 * on sphere i (the reasoning is in prepare.c); 0 when there is no such cone (then *l is 0). */
real rt_scene_mirror_cone(const rt_scene *s, int pl, int i, vec3 *l);

/* After rt_scene_prepare: turns every effect on (every light tested against every object, full
 * recursion), the generic path that effects on demand is measured against. */
void rt_scene_force_effects(rt_scene *s);

/* Is `e` (RT_FX_* bits) both compiled in and needed by the scene? */
static inline int rt_scene_has(const rt_scene *s, unsigned e)
{
    return (s->effects & (RT_COMPILED_EFFECTS)&e) != 0;
}

/* 0 when the camera has no view direction: its eye and the point it looks at coincide (an
 * animated camera can get there between keys). Such a view cannot be set up. */
int rt_view_ok(const rt_camera *cam);

/* Sets up the primary-ray frame for an image of width x height pixels. Without rt_view_ok(cam)
 * the camera looks down -z; an up vector of zero, or along the view, is replaced by another
 * axis. */
void rt_view_init(rt_view *v, const rt_camera *cam, int width, int height);

/* Direction of the primary ray through the centre of pixel (x, y). Inline: the tracer asks
 * for one per traced point, and the call would cost more than the two offsets it forms. */
static inline dir3 rt_view_ray(const rt_view *v, int x, int y)
{
    return d3_ray_at(&v->fwd, &v->right, &v->up, v->step, 2 * x + 1 - v->width,
                     v->height - 2 * y - 1);
}

/* Fills the view's primary-ray candidate sets (rt_view_candidates) for scene s as prepared
 * (rt_scene_prepare) with its eye_at at the view's eye: a sphere is left out of the tiles
 * where eye_cull would reject every primary ray (an over-estimate of its outline on the
 * image, by a margin above the rounding of either build), so rt_nearest_primary gives the
 * same results with the sets as without. Likewise the mirror candidates
 * (rt_view_mirror_candidates, mirror_plane = rt_scene_mirror(s)): a sphere is left out of the
 * tiles outside its rt_scene_mirror_cone, so rt_nearest_set with them gives the reflected
 * ray's rt_nearest_but result. Call it again whenever the scene or the view changes;
 * rt_view_init resets the sets to every object (and mirror_plane to -1). */
void rt_view_cull(rt_view *v, const rt_scene *s);

/* A primary hit's local part given (adaptive and probe mode, subsample.c: ss_local): where the
 * point's primary ray meets object `id` in checker cell `cell`, its ambient and light terms are not
 * formed: `col` (in [0, 1]) is taken as its colour there and `lights` as its light states; its
 * secondary rays are traced as usual. */
typedef struct rt_local {
    rt_color col;
    uint8_t id, cell, lights;
} rt_local;

/* rt_trace_pixel with the primary hit's local part given by *loc where it applies (loc NULL:
 * rt_trace_pixel itself); such a record keeps no other tone (alt_known 0). */
void rt_trace_pixel_local(const rt_scene *s, const rt_view *v, const rt_params *p, int x, int y,
                          const rt_local *loc, rt_stats *stats, rt_sample *out);

/* Traces the primary ray through pixel (x, y) with at most p->depth bounces and p->min_contrib
 * recursion control; fills *out and adds the rays cast to *stats. */
static inline void rt_trace_pixel(const rt_scene *s, const rt_view *v, const rt_params *p, int x,
                                  int y, rt_stats *stats, rt_sample *out)
{
    rt_trace_pixel_local(s, v, p, x, y, (const rt_local *)0, stats, out);
}

/* A pixel's primary ray and its nearest hit: found by the probe of the pixel (probe mode,
 * rt_probe_point) and reused by its full shade, which then casts no primary ray of its own. */
typedef struct rt_primary {
    dir3 d; /* the ray's direction, rt_view_ray */
    real t; /* distance to the hit (id >= 0) */
    int id; /* object hit, -1 none, RT_PRIMARY_UNKNOWN: not traced yet */
} rt_primary;
#define RT_PRIMARY_UNKNOWN (-2)

/* rt_trace_pixel (the same record, colour and stats) for a pixel whose primary ray and hit a
 * probe may have found: *pri holds them, or id RT_PRIMARY_UNKNOWN (traced here, into *pri). */
void rt_trace_pixel_from(const rt_scene *s, const rt_view *v, const rt_params *p, int x, int y,
                         rt_primary *pri, rt_stats *stats, rt_sample *out);

/* Index of the nearest object of `cand` (bit i: object i) hit by the ray within (0, tmax), or
 * -1; *t gets the distance (tmax for none). The objects are tested in their order, so the result
 * is that of testing every object wherever each one left out cannot report a hit for the ray
 * (rt_nearest_from). tmax is at most R_T_MAX, and org a ray origin of the tracer (in the scene
 * cube, or a hit point of a ray cast from it: docs/numerics.md), as the sphere and plane tests'
 * unchecked arithmetic takes them. */
int rt_nearest_set(const rt_scene *s, vec3 org, dir3 d, real tmax, uint32_t cand, real *t);

/* rt_nearest_set for a ray leaving from `from`: -1 (anywhere: the objects of `cand`), 2 i for a
 * plane i it leaves by mirroring off its front (i itself is not tested), 2 i or 2 i + 1 for a
 * hit on sphere i, its origin R_EPS_OFFSET above or below the surface: the objects of `cand`
 * in rt_scene.ray_oct's for the ray's octant; from below, those in ray_in's first, and all of
 * them only where that search does not find i. The same result as testing every object of
 * `cand` (rt_scene_prepare: the objects left out cannot report a hit for the ray, or for ray_in
 * only one beyond i's): `cand` may leave out only such objects too (the mirror candidates,
 * rt_view_mirror_candidates, for a reflection off the view's mirror plane). */
int rt_nearest_from(const rt_scene *s, vec3 org, dir3 d, real tmax, int from, uint32_t cand,
                    real *t);

/* rt_nearest_from's candidates: `cand` narrowed for a ray along d from `from`, with *need the
 * sphere the first search must find (ray_in's objects) or -1. */
static inline uint32_t rt_ray_cand(const rt_scene *s, int from, dir3 d, uint32_t cand, int *need)
{
    *need = -1;
    if (from >= 0) {
        const int a = from >> 1;
        if (RT_RAY_SETS) { /* a plane's ray_oct leaves out the plane itself */
            cand &= s->ray_oct[a][rt_octant(d)];
            if ((from & 1) && s->ray_in[a] != 0xFFFFFFFFu)
                *need = a;
        } else if (s->objects[a].kind == RT_PLANE) {
            cand &= ~((uint32_t)1 << a);
        }
    }
    return cand;
}

/* rt_nearest_from inlined into the caller (trace_ray on ARM, where its registers are free to
 * work out the candidates and the loop stays rt_nearest_set's: fewer instructions there; on
 * x86-64 the call measured fewer). */
static inline __attribute__((always_inline)) int rt_nearest_from_in(const rt_scene *s, vec3 org,
                                                                    dir3 d, real tmax, int from,
                                                                    uint32_t cand, real *t)
{
    int need;
    cand = rt_ray_cand(s, from, d, cand, &need);
    int id = rt_nearest_set(s, org, d, tmax, need >= 0 ? cand & s->ray_in[need] : cand, t);
    return need < 0 || id == need ? id : rt_nearest_set(s, org, d, tmax, cand, t);
}

/* The nearest object hit by the ray within (0, tmax), or -1: rt_nearest_set of every object. */
static inline int rt_nearest(const rt_scene *s, vec3 org, dir3 d, real tmax, real *t)
{
    return rt_nearest_set(s, org, d, tmax, ~(uint32_t)0, t);
}

/* rt_nearest without object `skip` (-1: none), for a ray that certainly cannot meet it (one
 * mirrored off a plane's front, from the offset origin). */
static inline int rt_nearest_but(const rt_scene *s, vec3 org, dir3 d, real tmax, int skip, real *t)
{
    return rt_nearest_set(s, org, d, tmax, skip >= 0 ? ~((uint32_t)1 << skip) : ~(uint32_t)0, t);
}

/* rt_nearest for a ray from s->eye_at (a primary ray), the same result: the sphere test
 * starts from the frame's eye_l and eye_cull, the plane test from eye_num. Only the objects
 * in `cand` are tested (bit i: object i): every object whose test could report a hit for d
 * must be in it (rt_view_candidates of the ray's pixel, or all bits). */
int rt_nearest_primary(const rt_scene *s, dir3 d, uint32_t cand, real *t);

/* rt_nearest_primary(s, d, 1 << id, t) == id for object id, a plane, without the loop: its
 * last-plane path (the plane test from eye_num, the division), the same t; 0 for a miss.
 * Only in the builds with probe mode (RT_COMPILED_PROBE: the players stay within their size). */
int rt_plane_primary(const rt_scene *s, int id, dir3 d, real *t);

/* Does any object of the set `occ` (bit i: object i) block the shadow ray toward light
 * `light`, the segment from org along d of length dist? Counts the objects tested in
 * st->shadow_tests. */
int rt_occluded(const rt_scene *s, rt_stats *st, int light, uint32_t occ, const vec3 *org,
                const dir3 *d, real dist);

/* Does light i reach point p (normal n, facing the ray; on object id, seen from inside when
 * `inside`; p_out: p lifted off the surface for secondary rays)? Returns n . l > 0 with the
 * direction to the light in *l where it does, else 0: a light behind the surface or exactly on
 * the point (no direction), or one shadow ray finding an occluder (counted in
 * st->rays_shadow). Shared by the shading (trace_light) and probe mode's light test, so both
 * decide light and shadow alike; p_out is read only when a shadow ray is cast. With st NULL no
 * shadow ray is cast: the light's facing and n . l alone (a light's term where nothing would
 * occlude it, rt_light_term). */
static inline __attribute__((always_inline)) unit rt_light_reach(const rt_scene *s, rt_stats *st,
                                                                 int i, int id, int inside,
                                                                 const vec3 *p, const vec3 *p_out,
                                                                 dir3 n, dir3 *l)
{
    const rt_light *li = &s->lights[i];
    vec3 to_light = v3_sub_in(li->pos, *p);
    if (!v3_faces(to_light, n))
        return 0;
    /* A point seen from inside a sphere whose own shadow ray would certainly meet the sphere
     * (dark_inside, p_out well inside): unlit, without the normalisation and the ray's tests;
     * counted as the shadow ray it decides. (A bit is set only where the sphere occludes the
     * light, which turns the shadow effect on; a build compiled without shadows has none.) */
    if (RT_RAY_SETS && (RT_COMPILED_EFFECTS & RT_FX_SHADOW) && inside && st &&
        (s->dark_inside[i] >> id & 1) &&
        w_len2(v3_sub_in(*p_out, s->objects[id].center)) < w_sq(s->dark_r[id])) {
        st->rays_shadow++;
        return 0;
    }
    const real dist = d3_norm_len(to_light, l);
    unit ndl = d3_dot(n, *l);
    if (ndl <= 0)
        return 0; /* the light is not in front of the surface */
    /* A convex surface never shadows its own lit side (occ_of leaves the object itself out);
     * seen from inside (glass) it can. Lights nothing can occlude cast no shadow ray at all. */
    uint32_t occ = 0;
    if (rt_scene_has(s, RT_FX_SHADOW)) {
        if (RT_SHADOW_SETS) {
            occ = s->occ_of[i][id];
            if (inside) /* and the planes: occ_of's plane rule holds for points seen outside */
                occ |= s->occluders[i] & (((uint32_t)1 << id) | (RT_PLANE_CULL ? s->plane_set : 0));
        } else {
            occ = s->occluders[i];
            if (!inside && !s->forced)
                occ &= ~((uint32_t)1 << id);
        }
    }
    if (occ) {
        if (!st)
            return ndl; /* no shadow ray */
        /* From p_out along l the segment would end up to 2 R_EPS_OFFSET from the
         * light, behind a surface that passes closer to the light than that (a light
         * just above a floor seen from the underside of a ball: a false shadow). For
         * such lights it is aimed from p_out itself and ends at the light. */
        real sdist = dist;
        dir3 near_l;
        const dir3 *sl = l;
        if (s->near_lights & (1u << i)) {
            vec3 to_light_out = v3_sub_in(li->pos, *p_out);
            sdist = 0;
            if (!v3_is_zero(to_light_out)) {
                sdist = d3_norm_len(to_light_out, &near_l);
                sl = &near_l;
            }
        }
        /* The segment stops R_EPS_OFFSET short of the light, as it starts that far
         * off the surface: a surface through the light itself (a light in a corner of
         * two walls) would otherwise shadow or not by rounding, pixel by pixel. (The
         * difference of two positive reals is in range: r_add_in, r_sub's value.) */
        st->rays_shadow++;
        if (sdist > R_EPS_OFFSET &&
            rt_occluded(s, st, i, occ, p_out, sl, r_add_in(sdist, r_neg_in(R_EPS_OFFSET))))
            return 0;
    }
    return ndl;
}

/* What one hit point looks like to the lights (the shading's trace_light, rt_light_term). */
typedef struct rt_hit {
    vec3 p, p_out; /* the point, and lifted R_EPS_OFFSET off the surface */
    dir3 n, d;     /* normal facing the ray, and the ray's direction */
    unit dn;       /* d . n (<= 0) */
    rt_color base; /* diffuse colour at p */
    const rt_material *m;
    int id, inside;          /* object hit; 1 when hit from behind */
    real ndl[RT_MAX_LIGHTS]; /* light i's n . l, set by trace_light where it lights the point */
} rt_hit;

/* Light i at the hit *h as the shading sees it (trace_light): with `term` NULL, its state there
 * (rt_light_reach, its shadow ray counted in st): 0 unlit, 1 lit, 2 highlight. Else the state
 * and the colour trace_light adds (Lambert and Phong) into *term as if nothing occluded the
 * light: no shadow ray, so the state is 0 and the term 0 only where the light does not face the
 * point. */
int rt_light_term(const rt_scene *s, rt_stats *st, rt_hit *h, int i, rt_color *term);

/* Renders a frame of v->width x v->height into `pixels` (0x00RRGGBB, `stride` pixels per row)
 * in p->mode. Adaptive mode needs `work`, rt_render_work_size(p, width) bytes, suitably
 * aligned for rt_sample (probe mode the same). If `traced` is not NULL it gets one byte per pixel
 * (`width` per row), 0 where no point was traced, else the RT_TRACED_ bits of every way the
 * point was (a point on a square's edge may be traced by the squares on either side of it;
 * their union is the same for any number of bands or threads). */
#define RT_TRACED_FULL 1  /* shaded in full */
#define RT_TRACED_PROBE 2 /* only probed (probe mode) */
#define RT_TRACED_LOCAL 4 /* shaded with its local part from its square's corners (local_points) */
void rt_render(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
               int stride, rt_stats *stats, void *work, uint8_t *traced);

/* Renders band `band` of `nbands` horizontal bands of the frame: bands of whole rows of grid
 * squares (adaptive) or of pixel rows (full), split as evenly as the squares allow. Bands write
 * disjoint pixels, so they may run at the same time (each with its own `work` and `stats`), and
 * together they give rt_render's frame byte for byte. `traced`, if not NULL, must be cleared
 * before the first band; bands only add RT_TRACED_ bits to it (atomically: two bands may mark
 * the same point of the edge between them). A band traces the corners on its lower edge again,
 * as the next band does: summed stats count those twice. */
void rt_render_band(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
                    int stride, rt_stats *stats, void *work, uint8_t *traced, int band, int nbands);

/* The most bands a frame of `height` rows splits into: its rows of squares (adaptive) or of
 * pixels (full); more bands than this leave some empty. */
int rt_render_band_count(const rt_params *p, int height);

/* The pixel rows band `band` of `nbands` of rt_render_band writes in a frame of `height` rows:
 * rows *y0 .. *y0 + *rows - 1 (*rows = 0: an empty band). Bands in order cover the frame. */
void rt_render_band_rows(const rt_params *p, int height, int band, int nbands, int *y0, int *rows);

/* rt_render_band into memory that holds only the band: `rows` is the band's first row (pixel row
 * y0 of rt_render_band_rows), rows `stride` pixels apart. With `keep`, the previous call with
 * this `work` rendered band - 1 of the same frame (scene, view, params, nbands): the row of corner
 * samples the two bands share is taken from `work` instead of being traced again, so bands
 * rendered in order trace what one rt_render traces, and give its pixels and stats. keep = 0
 * traces it (any band, any order). A display that keeps its own pixels needs no frame in RAM. */
void rt_render_band_into(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *rows,
                         int stride, rt_stats *stats, void *work, uint8_t *traced, int band,
                         int nbands, int keep);

/* What the pixel memory handed to a band holds. */
enum rt_band_memory {
    RT_BAND_FRAME, /* the whole frame (rt_render_band) */
    RT_BAND_ONLY,  /* only the band, from its first row (rt_render_band_into) */
    RT_BAND_KEEP   /* only the band, and `work` holds its top row of corners (keep) */
};

/* The adaptive and probe modes of rt_render_band and rt_render_band_into (subsample.c). */
void rt_render_adaptive(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
                        int stride, rt_stats *stats, void *work, uint8_t *traced, int band,
                        int nbands, enum rt_band_memory mem);

/* Probe mode (probe.c), for a point (x, y) that splitting a square adds in the middle of one
 * of its edges, from sample a to sample b (the point at fraction t from a to b; span: the
 * edge's length in pixels), ends that are not both opaque and agree on every light.
 * Returns -1 without a probe where one cannot pay (ends with one record but contributions
 * that disagree; ends that differ and both cast secondary rays, whose trees a probe would have
 * to trace; an edge longer than RT_PROBE_ONE_SPAN whose ends differ in primary object or
 * cell): the point is to be shaded in full. Else probes the point's primary hit and checker
 * cell (as its full shade finds them) and returns 1 when its colour can be reconstructed: the
 * ends with its primary object and cell (the matching ones) give its record (the first of them
 * casts no secondary ray, or the ends have one record), both match, or one and span <=
 * RT_PROBE_ONE_SPAN; that record is not opaque (rt_probe_opaque: no noise texture, no texture
 * beyond the primary hit, no highlight); the ends' contributions agree within thr8 (1/255
 * steps) where both match; and (but on an edge of 2 pixels whose ends both match) every
 * light the first matching end has unlit leaves the point unlit too (its facing test, n . l and shadow ray,
 * counted in st->rays_shadow: a lit wedge between shadows neither end sees). *out then gets the
 * first matching end's record, the colour interpolated from the matching ends alone (or the
 * one's colour), that end's other tone's colour as its own (rt_sample.alt, alt_known), and
 * flags RT_SAMPLE_PROBED. Returns 0 when the probed point must be shaded in full (*out
 * untouched): *pri then holds its primary ray and hit (rt_trace_pixel_from). Counts probes in
 * st->probes. */
#define RT_PROBE_ONE_SPAN 4
int rt_probe_point(const rt_scene *s, const rt_view *v, rt_stats *st, int thr8, int x, int y,
                   const rt_sample *a, const rt_sample *b, real t, int span, rt_primary *pri,
                   rt_sample *out);

/* Do two records have the same shape: primary object and cell, light states, and the objects
 * and levels of the ray tree (what rt_corners_differ compares before contributions)? */
int rt_probe_same(const rt_sample *a, const rt_sample *b);

/* Probe mode: the objects (bit i: object i) whose colour no record holds where a ray meets
 * them: at a primary hit (`primary`: noise textures), at a secondary hit (`beyond`: any
 * texture). Worked out once a frame (rt_probe_masks_of) for rt_probe_opaque. */
typedef struct rt_probe_masks {
    uint32_t primary, beyond;
} rt_probe_masks;
rt_probe_masks rt_probe_masks_of(const rt_scene *s);

/* Probe mode: RT_SAMPLE_OPAQUE for a shaded sample whose record cannot stand for the colour of
 * a neighbour with the same record (rt_probe_point would never interpolate from it), else 0;
 * mk: rt_probe_masks_of the sample's scene. */
unsigned rt_probe_opaque(const rt_probe_masks *mk, const rt_sample *sm);

/* Bytes of working storage rt_render needs for frames `width` pixels wide: in adaptive mode
 * two rows of square corners and the samples of one square; 0 in full mode. */
unsigned long rt_render_work_size(const rt_params *p, int width);

/* Compares the four corner samples of a square (in any order); thr8 is the contribution
 * threshold in 1/255 colour steps. */
enum rt_split_reason rt_corners_differ(const rt_sample *const corner[4], int thr8);

/* The centre test of a square split only for its contributions (rt_corners_differ gave
 * RT_SPLIT_CONTRIB for corner[0..3]: (0, 0), (w, 0), (0, h), (w, h)): 1 when the sample at its
 * centre, mid, has the corners' shape (rt_probe_same with corner[0]: primary object, cell, light
 * states, the objects and levels of its ray tree) and each stored node's contribution, in each
 * channel, lies within tol (1/255 steps, >= 0) of the mean of either diagonal's ends (corner[0]
 * and corner[3], corner[1] and corner[2]): the colour varies linearly along both diagonals, so
 * it lies on the corners' bilinear mean too; else 0 (split). */
int rt_centre_smooth(const rt_sample *const corner[4], const rt_sample *mid, int tol);

/* Fills `cols` x `rows` pixels from dst (stride pixels per row) by bilinear interpolation of
 * the colours at the corners of a w x h square: c00 at (0, 0), c10 at (w, 0), c01 at (0, h),
 * c11 at (w, h), each clamped to [0, 1] first. cols <= w + 1 and rows <= h + 1; corner pixels
 * get their colour exactly. */
void rt_interpolate(uint32_t *dst, int stride, int w, int h, int cols, int rows, rt_color c00,
                    rt_color c10, rt_color c01, rt_color c11);

/* A colour as a 0x00RRGGBB pixel: each channel clamped to [0, 1] and rounded to 8 bits. */
static inline uint32_t rt_color_pixel(rt_color c)
{
    return (uint32_t)r_to_byte(c.x) << 16 | (uint32_t)r_to_byte(c.y) << 8 | r_to_byte(c.z);
}

/* The diffuse colour of material m at the scene point p (its texture, if any), its noise
 * summed over at most max_octaves octaves (0: the texture's own count) and only those a pixel
 * covering `footprint` scene units resolves (0: all, rt_noise_detail_for), the octaves summed
 * added to st->noise_octaves; *cell gets the id of the texture cell p lies in (checkerboard),
 * 0 for textures without cells. */
rt_color rt_texture_color(const rt_material *m, vec3 p, int max_octaves, real footprint,
                          rt_stats *st, uint8_t *cell);

#endif
