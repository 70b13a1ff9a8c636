/* rt_local.h: the ray tracer core's own interface between its files (not for callers: rt.h is theirs).
 *
 * Build switches, the shapes' table, the nearest-hit searches and their candidate sets, the
 * light test shared by the shading and probe mode, the per-pixel entry points adaptive
 * subsampling and probe mode trace through, and the fills. As Quake's r_local.h beside render.h.
 * The unit tests include it too, to test these parts one by one.
 */
#ifndef FIXRAY_RT_LOCAL_H
#define FIXRAY_RT_LOCAL_H

#include "rt.h"

/* The build settings that rt.h takes from the Makefile, checked once for every core file. */
#if RT_MAX_OBJECTS > 32 || RT_MAX_OBJECTS < 1
#error "RT_MAX_OBJECTS must be 1..32: sets of objects are 32-bit masks"
#endif
#if (RT_COMPILED_EFFECTS) > RT_FX_ALL
#error "RT_COMPILED_EFFECTS must be a set of enum rt_effect bits"
#endif

/* The side, in pixels, under which a sphere's box makes it small (rt_view.small). */
#define RT_SMALL_MAX 32
/* A light's state becomes 2 (highlight) when its specular term exceeds this. */
#define RT_HIGHLIGHT_MIN R(0.125)
/* Noise pixels: the largest lighting factor A a sample keeps (as A / 2 in a byte). */
#define RT_NOISE_A_MAX R(2.0)

/* What rt_sample.alt holds (alt_known), for a primary hit seen from the prepared eye in
 * adaptive and probe mode (trace.c: trace_alt_mid). */
enum rt_alt {
    RT_ALT_NONE, /* nothing */
    /* on a two-tone checker: alt is the colour the point would have in a cell of the other
     * tone (the same lights and secondary rays), as the bytes of a pixel (red, green, blue) */
    RT_ALT_TONE,
    /* on a noise texture, no secondary ray (nhits 1): the colour is b x A + B, b the texture's
     * colour, A the lighting that multiplies it (ambient, Lambert), B the rest (highlights);
     * alt holds A / 2 as bytes (A <= RT_NOISE_A_MAX), hits[1].contrib B (clamped to [0, 1]) */
    RT_ALT_NOISE
};

/* A sphere's rt_object.behind: -(radius + 2^-10 + radius 2^-13). A ray whose tca = l . d (as the
 * sphere test forms it) is below this starts outside the sphere (shapes.c: sphere_hit). */
static inline real rt_sphere_behind(real radius)
{
    return r_neg(r_add(r_add(radius, R(0.0009765625)), r_shr(radius, 13)));
}

/* The octant of direction d, as rt_scene.cull.ray_oct indexes it: bit k set where component k (x,
 * y, z) is negative. */
static inline unsigned rt_octant(dir3 d)
{
    return (unsigned)(d.x < 0) | (unsigned)(d.y < 0) << 1 | (unsigned)(d.z < 0) << 2;
}

/* Is p the point the scene was prepared for (eye_at), exactly? Only rays from it may use the
 * per-eye data (eye_l, eye_cull, eye_num: rt_nearest_primary, rt_view_cull). */
static inline int rt_scene_at_eye(const rt_scene *s, vec3 p)
{
    return p.x == s->cull.eye_at.x && p.y == s->cull.eye_at.y && p.z == s->cull.eye_at.z;
}

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

/* Are the shadow rays' narrower occluder sets compiled in: per object (rt_scene.cull.occ_of,
 * scene_shadow_pairs) and per quadrant of directions (shadow_quad, scene_shadow_quads)? The
 * intro player defines this to 0 (its 64 kB): a shadow ray from object j then tests every
 * occluder but j itself, as rt_light_reach forms it, the rejections of each sphere deciding.
 * The pictures are the same: the sets leave out only spheres whose rejection (shadow_cull)
 * refuses the ray anyway, or that lie beyond its reach (rt_scene_prepare; test_shapes). */
#ifndef RT_SHADOW_SETS
#define RT_SHADOW_SETS 1
#endif

/* Are the secondary rays' candidate sets (rt_scene.cull.ray_oct, ray_in) compiled in? Off with the
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

/* Does adaptive subsampling look for detail finer than its squares that the frame's geometry
 * shows before a ray is traced: checker cells finer than a square (rt_view.cell_side,
 * ss_cells_apart) and pools of light (rt_view.pool, ss_pool_over)? The ARM926 build and the
 * intro players (build/intro-*) define this to 0: they render the intro, at 320x240 on the
 * board, which keeps the far floor off the frame and its lights well above it, and whose
 * pictures these tests leave unchanged there (every frame checked, both builds and modes);
 * they would cost the board 0.7 M instructions a mean frame and 1.5 kB of its image, and the
 * players their 64 kB. The Cortex-M boards keep them: at 128x64 the cell test changes some
 * intro frames. */
#ifndef RT_FINE_DETAIL
#define RT_FINE_DETAIL 1
#endif

/* Do the per-object occluder sets leave out a plane that cannot come between a resting
 * sphere's lit points and the light (scene_shadow_pairs)? Pictures are the same either way;
 * the intro player (build/intro-*) defines this to 0 to stay within its 64 kB. */
#ifndef RT_PLANE_CULL
#define RT_PLANE_CULL 1
#endif

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

/* Is `e` (RT_FX_* bits) both compiled in and needed by the scene? */
static inline int rt_scene_has(const rt_scene *s, unsigned e)
{
    return (s->effects & (RT_COMPILED_EFFECTS)&e) != 0;
}

/* Direction of the primary ray through the centre of pixel (x, y). Inline: the tracer asks
 * for one per traced point, and the call would cost more than the two offsets it forms. */
static inline dir3 rt_view_ray(const rt_view *v, int x, int y)
{
    return d3_ray_at(&v->fwd, &v->right, &v->up, v->step, 2 * x + 1 - v->width,
                     v->height - 2 * y - 1);
}

/* A primary hit's local part given (adaptive and probe mode, subsample_local.c: ss_local): where the
 * point's primary ray meets object `id` in checker cell `cell`, its ambient and light terms are not
 * formed: `col` (in [0, 1]) is taken as its colour there and `lights` as its light states; its
 * secondary rays are traced as usual. */
typedef struct rt_local {
    rt_color col;
    uint8_t id, cell, lights;
} rt_local;

/* rt_trace_pixel with the primary hit's local part given by *loc where it applies (loc NULL:
 * rt_trace_pixel itself); such a record keeps no other tone (RT_ALT_NONE). */
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
 * in rt_scene.cull.ray_oct's for the ray's octant; from below, those in ray_in's first, and all of
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
            cand &= s->cull.ray_oct[a][rt_octant(d)];
            if ((from & 1) && s->cull.ray_in[a] != 0xFFFFFFFFu)
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
    int id = rt_nearest_set(s, org, d, tmax, need >= 0 ? cand & s->cull.ray_in[need] : cand, t);
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

/* rt_nearest for a ray from s->cull.eye_at (a primary ray), the same result: the sphere test
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
        (s->cull.dark_inside[i] >> id & 1) &&
        w_len2(v3_sub_in(*p_out, s->objects[id].center)) < w_sq(s->cull.dark_r[id])) {
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
            occ = s->cull.occ_of[i][id];
            if (inside) /* and the planes: occ_of's plane rule holds for points seen outside */
                occ |= s->occluders[i] &
                    (((uint32_t)1 << id) | (RT_PLANE_CULL ? s->cull.plane_set : 0));
        } else {
            occ = s->occluders[i];
            if (!inside && !s->cull.forced)
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
        if (s->cull.near_lights & (1u << i)) {
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

/* What the pixel memory handed to a band holds. */
enum rt_band_memory {
    RT_BAND_FRAME, /* the whole frame (rt_render_band) */
    RT_BAND_ONLY,  /* only the band, from its first row (rt_render_band_into) */
    RT_BAND_KEEP   /* only the band, and `work` holds its top row of corners (keep) */
};

/* The adaptive and probe modes of rt_render_band, rt_render_band_edges and
 * rt_render_band_into (subsample.c); edges: rt_render_edge's rows, or NULL. */
void rt_render_adaptive(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
                        int stride, rt_stats *stats, void *work, uint8_t *traced, int band,
                        int nbands, enum rt_band_memory mem, const void *edges);

/* Probe mode (probe.c), for a point (x, y) that splitting a square adds in the middle of one
 * of its edges, from sample a to sample b (the point at fraction t from a to b; span: the
 * edge's length in pixels), ends that are not both opaque and agree on every light.
 * Returns -1 without a probe unless the edge is 2 pixels long and its ends have one record
 * (rt_probe_same) with no secondary ray, a is not opaque (rt_probe_opaque: no noise texture,
 * no highlight) and their contributions agree within thr8 (1/255 steps) in both directions:
 * the point is to be shaded in full where the squares below need it. Else probes the point's
 * primary hit and checker cell (as its full shade finds them) and returns 1 when they are the
 * ends': *out then gets a's record, the colour interpolated between a and b, a's other tone's
 * colour as its own (rt_sample.alt, alt_known), and flags RT_SAMPLE_PROBED. Returns 0 when
 * the probed point must be shaded in full (*out untouched): *pri then holds its primary ray
 * and hit (rt_trace_pixel_from). Counts probes in st->probes. */
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

/* The pixel memory the renderer writes (the `uint32_t *` buffers of rt.h): a 0x00RRGGBB word a
 * pixel, or, where the build sets RT_PIXEL_RGB24 (the Cortex-M0, whose band it makes a quarter
 * smaller), three bytes R, G, B, strides still counted in pixels. rt_px is its element, RT_PX(p, i)
 * pixel i from p, rt_px_set and rt_px_get a pixel's 0x00RRGGBB value. */
#if RT_PIXEL_RGB24
typedef uint8_t rt_px;
#define RT_PX_N 3
static inline void rt_px_set(rt_px *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 16);
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)v;
}
static inline uint32_t rt_px_get(const rt_px *p)
{
    return (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
}
#else
typedef uint32_t rt_px;
#define RT_PX_N 1
static inline void rt_px_set(rt_px *p, uint32_t v) { *p = v; }
static inline uint32_t rt_px_get(const rt_px *p) { return *p; }
#endif
#define RT_PX(p, i) ((p) + (i)*RT_PX_N)

#endif
