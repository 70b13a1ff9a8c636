/* trace.c: Whitted ray tracing: nearest hit, hard shadows, Phong shading, reflection, refraction. */
#include <stddef.h>

#include "rt_local.h"

/* State of one traced image point, threaded through the recursion. */
typedef struct trace_ctx {
    const rt_scene *scene;
    rt_stats *stats;
    rt_sample *sample;
    real min_contrib; /* adaptive recursion control */
    int depth;        /* recursion depth left to the primary ray: level k has depth - k */
    int octaves;      /* cap on noise octaves (rt_params.octaves) */
    real pixel;       /* a pixel's footprint per unit of ray length, 0 = footprint off */
    /* How the primary ray finds its hit: 0 rt_nearest_but, 1 rt_nearest_primary (the view's eye
     * is the prepared one, eye_at), 2 through `pri` (trace_first) */
    int eye_prepared;
    rt_primary *pri; /* probe mode: the primary hit, found here or given (rt_primary); or NULL */
    uint32_t primary_cand; /* the objects the primary ray's rt_nearest_primary tests */
    /* The view's mirror plane when its candidates serve this pixel (the view's eye is the
     * prepared one), else -1: a level-1 ray leaving that plane (`from`) is the reflection of
     * the pixel's own primary ray, whose tests mirror_cand bounds (rt_view_mirror_candidates). */
    int mirror;
    uint32_t mirror_cand;
    /* Adaptive and probe mode: 1 gives a primary hit on a plane with a two-tone checker its
     * other tone's colour, and one on a noise texture its lighting factors (rt_sample.alt,
     * RT_ALT_TONE or RT_ALT_NOISE: trace_alt_mid) */
    int alt;
    const rt_local *local; /* the primary hit's local part, given (rt_trace_pixel_local), or NULL */
} trace_ctx;

/* Inlined into its three callers: the colour stays in registers (no copy through the stack)
 * and the count is read once. */
static inline __attribute__((always_inline)) void trace_record(trace_ctx *c, int object, int level,
                                                               rt_color contrib)
{
    rt_sample *sm = c->sample;
    unsigned n = sm->nhits;
    if (n < RT_SAMPLE_MAX_HITS) {
        rt_hit_rec *h = &sm->hits[n];
        h->object = (uint8_t)object;
        h->level = (uint8_t)level;
        h->contrib[0] = r_to_byte(contrib.x);
        h->contrib[1] = r_to_byte(contrib.y);
        h->contrib[2] = r_to_byte(contrib.z);
    }
    sm->nhits = (uint8_t)(n + (n < 255));
}

/* A secondary hit's checker cell (rt_texture_color's, 1 + i | j << 2 | k << 4 with i, j, k the
 * cell's coordinates modulo 4) as the 4 high bits of its node's level (rt_hit_rec.level): i + j
 * and j + k modulo 4, which tell apart any two cells up to three apart on a plane normal to an
 * axis, whichever. Two corners that see the same object at a secondary level on different cells
 * then have different ray trees, and split as on different objects: a checker seen through glass
 * or in a mirror has cells of the other colour between them, as the primary hit's cell
 * criterion knows. */
static inline unsigned trace_cell_code(unsigned cell)
{
    const unsigned c = cell - 1, i = c & 3, j = c >> 2 & 3, k = c >> 4 & 3;
    return ((i + j) & 3) << 4 | ((j + k) & 3) << 6;
}

#if RT_COMPILED_PROBE
/* Probe mode's primary hit (eye_prepared 2): the one a probe of this pixel found (c->pri), or
 * found here and kept there. Out of line, off the other modes' path. */
FX_BOARD_THUMB
static __attribute__((noinline)) int trace_first(trace_ctx *c, vec3 org, dir3 d, real *t)
{
    rt_primary *pri = c->pri;
    if (pri->id == RT_PRIMARY_UNKNOWN) {
        const rt_scene *s = c->scene;
        int prepared = rt_scene_at_eye(s, org);
        pri->t = 0;
        pri->id = prepared ? rt_nearest_primary(s, d, c->primary_cand, &pri->t)
                           : rt_nearest_but(s, org, d, R_T_MAX, -1, &pri->t);
    }
    *t = pri->t;
    return pri->id;
}
#define TRACE_FIRST(c) ((c)->eye_prepared == 2)
#else
#define trace_first(c, org, d, t) (-1)
#define TRACE_FIRST(c) 0
#endif

/* What one hit point looks like to the lights (trace_light's input): rt_hit (rt.h). */
typedef rt_hit trace_hit;

/* Adaptive mode, a primary hit h on a two-tone checker (the sample's cell non-zero), its lights
 * added (states `lights`): shading is linear in the diffuse colour b, whose factor E is the
 * ambient term's (scene ambient x the material's ambient) plus light colour x n.l for each
 * light that lights the point; the other tone b' then adds (b' - b) x E to the colour (up to
 * rounding), whatever the highlights and the secondary rays add. That goes into the sample's
 * colour, with RT_ALT_TONE, until trace_point has the colour itself (trace_alt_end). E is within
 * [0, 65] and |b' - b| <= 1 (docs/numerics.md, Colours): the products and sums are in range
 * (the unchecked forms, *_in). With `noise` (a noise texture, b its colour at the hit): the
 * colour is b x E + B, and for interpolating E and B apart (ss_noise) the sample keeps E in
 * rt_sample.alt, as the bytes of E / 2 (units of 2/255; nothing is kept for an E above 2), and
 * (0 - b) x E in its colour, RT_ALT_NOISE: trace_alt_end then gives B. Out of line: off the usual
 * path. */
static __attribute__((noinline)) void trace_alt_mid(trace_ctx *c, const trace_hit *h,
                                                    unsigned lights, int noise)
{
    const rt_scene *s = c->scene;
    const rt_material *m = h->m;
    rt_color e = c3_scale_p(s->ambient, m->ambient);
    for (int l = 0; lights; l++, lights >>= 2)
        if (lights & 3)
            e = c3_madd_p(e, s->lights[l].color, h->ndl[l]);
    rt_sample *sm = c->sample;
    rt_color b2 = rt_cell_tone(sm->cell) ? m->diffuse : m->tex.color2;
    if (noise) {
        if (e.x > RT_NOISE_A_MAX || e.y > RT_NOISE_A_MAX || e.z > RT_NOISE_A_MAX)
            return;
        sm->alt[0] = r_to_byte(r_shr(e.x, 1));
        sm->alt[1] = r_to_byte(r_shr(e.y, 1));
        sm->alt[2] = r_to_byte(r_shr(e.z, 1));
        b2 = v3(0, 0, 0);
    }
    sm->color = v3(r_mul_in(r_add_in(b2.x, r_neg_in(h->base.x)), e.x),
                   r_mul_in(r_add_in(b2.y, r_neg_in(h->base.y)), e.y),
                   r_mul_in(r_add_in(b2.z, r_neg_in(h->base.z)), e.z));
    sm->alt_known = (uint8_t)(RT_ALT_TONE + noise); /* RT_ALT_NOISE on a noise texture */
}

/* The sample's other tone (rt_sample.alt; on a noise texture its B, rt_sample.hits[1]) into `to`
 * from its colour col and what trace_alt_mid left in its colour (within [-65, 65]: the sum is in
 * range), as the bytes of a pixel. */
static __attribute__((cold, noinline)) void trace_alt_end(uint8_t *to, const rt_sample *sm,
                                                          rt_color col)
{
    to[0] = r_to_byte(r_add_in(col.x, sm->color.x));
    to[1] = r_to_byte(r_add_in(col.y, sm->color.y));
    to[2] = r_to_byte(r_add_in(col.z, sm->color.z));
}

/* Light i's Lambert and Phong terms at the hit, added to *col; returns the light's state (0
 * unlit, 1 lit, 2 highlight). Out of line on ARM (RT_OUT_OF_LINE): the caller's loop then keeps
 * less in registers; so in the 64 kB players too (the builds without probe mode), where
 * trace_ray and rt_light_term share the one copy. Elsewhere (x86-64) inlined into both:
 * trace_ray's loop over lights takes fewer instructions so (callgrind; docs/tracer.md). */
#if defined(__arm__) || !RT_COMPILED_PROBE
static RT_OUT_OF_LINE uint8_t trace_light(trace_ctx *c, trace_hit *h, int i, rt_color *col)
#else
static inline __attribute__((always_inline)) uint8_t trace_light(trace_ctx *c, trace_hit *h, int i,
                                                                 rt_color *col)
#endif
{
    /* The hit's fields are read where they are used (not copied up front): most lights are
     * behind the surface or shadowed and need only p and n. */
    const rt_scene *s = c->scene;
    const rt_light *li = &s->lights[i];
    /* A light behind the surface, or exactly on the point (no direction: it lights the
     * point at a grazing angle, i.e. not at all), leaves l = 0, so n . l = 0, without the
     * cost of a normalisation. */
    dir3 l;
    const unit ndl = rt_light_reach(s, c->stats, i, h->id, h->inside, &h->p, &h->p_out, h->n, &l);
    if (!ndl)
        return 0;
    const rt_material *m = h->m;
    rt_color acc = c3_madd_p(*col, c3_mul_p(li->color, h->base), u_to_real(ndl)); /* Lambert */
    h->ndl[i] = u_to_real(ndl); /* for a checker's other tone (trace_alt_mid) */
    uint8_t state = 1;
    if (rt_scene_has(s, RT_FX_SPECULAR) && m->specular > 0) {
        /* Phong: (v . r)^h with v toward the eye, r the light mirrored in n */
        /* v . r with r = 2 (n.l) n - l: -(d.r) = d.l - 2 (n.l)(d.n), no renormalisation.
         * Subtracted in two steps: 2 (n.l)(d.n) reaches -2 (light and eye straight above
         * the point), just outside Q2.30, while every partial sum is within [-1, 1]
         * (docs/numerics.md): the in-range forms (u_mul_in, u_add_in). */
        unit ndn = u_neg(u_mul_in(ndl, h->dn));
        unit vr = u_add_in(u_add_in(d3_dot(h->d, l), ndn), ndn);
        if (vr > m->spec_zero) { /* else (v . r)^h is 0: no highlight */
            real spec = r_mul_c(m->specular, u_to_real(u_pow(vr, m->shininess)));
            acc = c3_madd_p(acc, li->color, spec);
            if (spec > RT_HIGHLIGHT_MIN)
                state = 2;
        }
    }
    *col = acc;
    return state;
}

/* How trace_ray takes its ray: in place on 32-bit ARM, where a point and a direction by value
 * are six words copied through the stack per call (fewer instructions in place, measured under
 * QEMU); by value elsewhere (x86-64 passes them in registers: fewer there, measured with
 * callgrind). TRACE_RAY_ARG(x) passes the object x, TRACE_RAY_NEW(T, v) the value v of type T;
 * TRACE_RAY_PARAMS declares the parameters and TRACE_RAY_TAKE gives the function org and d. */
#if defined(__arm__)
#define TRACE_RAY_ARG(x) (&(x))
#define TRACE_RAY_NEW(T, v) ((const T[1]){v})
#define TRACE_RAY_PARAMS const vec3 *org_at, const dir3 *d_at
#define TRACE_RAY_TAKE \
    const vec3 org = *org_at; \
    const dir3 d = *d_at
#define TRACE_RAY_PASS org_at, d_at
#else
#define TRACE_RAY_ARG(x) (x)
#define TRACE_RAY_NEW(T, v) (v)
#define TRACE_RAY_PARAMS vec3 org, dir3 d
#define TRACE_RAY_TAKE (void)0
#define TRACE_RAY_PASS org, d
#endif

static rt_color trace_ray(trace_ctx *c, TRACE_RAY_PARAMS, int level, real weight, real travelled,
                          int from);

/* trace_ray's search of a ray's nearest hit: rt_nearest_from inlined on ARM, called elsewhere
 * (each way measured fewer instructions there; docs/tracer.md). */
#if defined(__arm__)
#define TRACE_NEAREST_FROM rt_nearest_from_in
#else
#define TRACE_NEAREST_FROM rt_nearest_from
#endif

/* The reflected and refracted rays of hit h (trace_ray's, at recursion level `level`, whose
 * depth left is above 0, and weight `weight`), added to col. Inlined into trace_ray, also on
 * ARM: with the ray passed in place it measured fewer instructions there than out of line,
 * and a smaller image. */
static inline rt_color trace_secondary(trace_ctx *c, const trace_hit *h, real weight, int level,
                                       real travelled, rt_color col)
{
    const rt_scene *s = c->scene;
    const rt_material *m = h->m;
    const dir3 d = h->d, n = h->n;
    const int inside = h->inside;
    /* where the rays leave from (trace_ray's `from`): a sphere's rays from its hit, inside it
     * (2 id + 1: refracted in, or mirrored inside) or outside (2 id) */
    const int sphere = s->objects[h->id].kind == RT_SPHERE;
    real kr = m->reflect;
    /* d . n for the facing normal: dn itself, unless n was turned (rounding -(d . n) and
     * negating the rounded value can differ by a step) */
    unit dk = inside ? d3_dot(d, n) : h->dn;
    if (rt_scene_has(s, RT_FX_REFRACT) && m->transmit > 0) {
        dir3 rd;
        real eta = inside ? m->ior : m->ior_inv;
        if (d3_refract_k(d, n, dk, eta, &rd)) {
            real wt = r_mul_c(weight, m->transmit);
            if (wt >= c->min_contrib) { /* adaptive recursion control */
                c->stats->rays_refract++;
                vec3 p_in = v3_along_in(h->p, n, r_neg(R_EPS_OFFSET));
                rt_color tc = trace_ray(c, TRACE_RAY_ARG(p_in), TRACE_RAY_ARG(rd), level + 1, wt,
                                        travelled, sphere ? 2 * h->id + !inside : -1);
                col = c3_madd_p(col, tc, m->transmit);
            }
        } else {
            kr = r_add(kr, m->transmit); /* total internal reflection */
        }
    }
    real wr = r_mul_c(weight, kr);
    if (kr > 0 && wr >= c->min_contrib) {
        c->stats->rays_reflect++;
        /* Mirrored off a plane's front, it cannot meet the plane again: it starts
         * R_EPS_OFFSET in front of it (far more than the hit point's error) and leaves it.
         * (A sphere's own test is kept: at the scene's limits rt-fixed16's hit points can
         * be off by more than that. Every object is tested when effects are forced.) Off a
         * sphere, from inside it when seen from inside. */
        int from = sphere ? 2 * h->id + inside : !inside && !s->cull.forced ? 2 * h->id : -1;
        rt_color rc =
            trace_ray(c, TRACE_RAY_ARG(h->p_out), TRACE_RAY_NEW(dir3, d3_reflect_k(d, n, dk)),
                      level + 1, wr, travelled, from);
        col = c3_madd_p(col, rc, kr);
    }
    return col;
}

/* trace_ray's nearest hit and shading of the ray (org, d) at recursion level `level` (its depth
 * left is c->depth - level), its node recorded: its colour into *col; 1 when the hit casts
 * secondary rays, with *h the hit and *travelled the path's length to it (trace_secondary's
 * input), else 0. */
static inline __attribute__((always_inline)) int trace_shade(trace_ctx *c, TRACE_RAY_PARAMS,
                                                             int level, real weight,
                                                             real *travelled_at, int from,
                                                             trace_hit *h, rt_color *col_at)
{
    TRACE_RAY_TAKE;
    const rt_scene *s = c->scene;
    const int depth = c->depth - level;
    real travelled = *travelled_at;
    real t;
    int id;
    if (level > 0 || !c->eye_prepared)
        id = TRACE_NEAREST_FROM(
            s, org, d, R_T_MAX, from,
            from >= 0 && from >> 1 == c->mirror && level == 1 ? c->mirror_cand : ~(uint32_t)0, &t);
    else
        id = TRACE_FIRST(c) ? trace_first(c, org, d, &t)
                            : rt_nearest_primary(s, d, c->primary_cand, &t);
    if (id < 0) {
        trace_record(c, RT_NO_OBJECT, level,
                     weight == R_ONE ? s->background : c3_scale_p(s->background, weight));
        *col_at = s->background;
        return 0;
    }
    const rt_object *o = &s->objects[id];
    const rt_material *m = &s->materials[o->material];
    /* The hit as trace_light sees it, formed in place. */
    const vec3 p = h->p = v3_along_in(org, d, t);
    dir3 n = o->kind == RT_PLANE ? o->normal : rt_sphere_normal(o, &p); /* rt_shapes' normal */
    int inside = 0;
    unit dn = d3_dot(d, n);
    if (dn > 0) { /* hit from behind: shade the side the ray sees */
        n = d3_neg(n);
        dn = u_neg(dn);
        inside = 1;
    }
    h->n = n;
    h->d = d;
    h->dn = dn;
    h->m = m;
    h->id = id;
    h->inside = inside;
    /* Secondary rays leave from just above (or, refracted, just below) the surface. */
    h->p_out = v3_along_in(p, n, R_EPS_OFFSET);

    uint8_t cell = 0;
    /* path length from the eye, for the noise footprint: capped (beyond it a pixel covers more
     * than any noise octave) so that it cannot saturate however deep the recursion */
    const real travel_max = r_muli(R_SCENE_MAX, 2);
    /* travelled is within [0, travel_max] and t in (0, R_T_MAX): the difference and the sum
     * taken are in range (r_add_in, the same values as r_sub and r_add) */
    travelled = t < r_add_in(travel_max, r_neg_in(travelled)) ? r_add_in(travelled, t) : travel_max;
    /* a material whose texture is not active (none, or a checker of one colour) is its diffuse
     * colour with no cell, as rt_texture_color would return: tested here, without the call; the
     * footprint pixel x travelled is in range (a pixel's width at distance 1 is at most
     * 2 tan 60 deg = 3.47, travelled at most travel_max = 8192: below 28426, r_mul_in) */
    rt_color base = rt_scene_has(s, RT_FX_TEXTURE) && m->tex.active
        ? rt_texture_color(m, p, c->octaves, r_mul_in(c->pixel, travelled), c->stats, &cell)
        : m->diffuse;
    if (level == 0)
        c->sample->cell = cell; /* before trace_alt_mid, which reads it */
    rt_color col;
    unsigned lights = 0;
    const rt_local *lc = level == 0 ? c->local : NULL;
    if (lc && id == lc->id && cell == lc->cell) {
        /* the local part given (ss_local): no ambient, light or shadow terms, no other tone */
        c->stats->local_points++;
        col = lc->col;
        lights = lc->lights;
    } else {
        /* the ambient term; for the material's own diffuse colour (untextured, or a checker's
         * first colour) the frame's (rt_scene_prepare), the same value */
        col = base.x == m->diffuse.x && base.y == m->diffuse.y && base.z == m->diffuse.z
            ? m->ambient_term
            : c3_scale_p(c3_mul_p(base, s->ambient), m->ambient);
        h->base = base;
        for (int i = 0; i < s->nlights; i++)
            lights |= (unsigned)trace_light(c, h, i, &col) << (2 * i);
        if (level == 0 && c->alt && m->tex.active) {
            if (cell && (s->cull.plane_set >> id & 1))
                trace_alt_mid(c, h, lights, 0); /* a plane with a two-tone checker */
            else if (rt_scene_has(s, RT_FX_NOISE) && m->tex.kind != RT_TEX_CHECKER)
                trace_alt_mid(c, h, lights, 1); /* a noise texture */
        }
    }
    if (level == 0)
        c->sample->lights = (uint8_t)lights;
    /* A primary ray's weight is exactly 1, and scaling by 1 is exact: skipped. */
    trace_record(c, id, level | (level && cell ? trace_cell_code(cell) : 0),
                 weight == R_ONE ? col : c3_scale_p(col, weight));

    /* Reflected and refracted rays leave only from points inside the scene cube. Every ray
     * origin is then inside the cube or the hit of a ray cast from it, so within
     * R_SCENE_MAX + R_T_MAX of the centre: the bound the sphere test's arithmetic relies on
     * (fixed/real_fixed.h). Only an open plane can be hit outside the cube, so far away that
     * what it mirrors is below a pixel. A material that neither reflects nor transmits casts
     * neither ray. */
    *col_at = col;
    *travelled_at = travelled;
    return depth > 0 && rt_scene_has(s, RT_FX_REFLECT) &&
        (m->reflect > 0 || (rt_scene_has(s, RT_FX_REFRACT) && m->transmit > 0)) &&
        v3_within(p, R_SCENE_MAX);
}

#if !defined(__ARM_ARCH_6M__)
/* Colour seen along the ray (org, d) at recursion level `level` (its depth left is
 * c->depth - level); `weight` is this ray's share of the pixel, `travelled` the length of its
 * path from the eye to org, `from` where it leaves from (rt_nearest_from: a sphere's hit, or a
 * plane it leaves by mirroring off its front; -1 for any other ray). */
static rt_color trace_ray(trace_ctx *c, TRACE_RAY_PARAMS, int level, real weight, real travelled,
                          int from)
{
    trace_hit h;
    rt_color col;
    if (trace_shade(c, TRACE_RAY_PASS, level, weight, &travelled, from, &h, &col))
        col = trace_secondary(c, &h, weight, level, travelled, col);
    return col;
}
#else
/* ARMv6-M (the Cortex-M0, 16 KiB of RAM): the same rays, the same order, with a smaller frame in
 * the recursion. Inlined, the shading's and the secondary rays' temporaries in eight low registers
 * took trace_ray's frame to 464 bytes, held by every level; here trace_shade_rays, out of line,
 * shades the hit and works out the secondary rays (trace_secondary's) into a trace_rays, and only
 * that stays on the stack while they are traced. */
typedef struct trace_rays {
    vec3 p_in, p_out;   /* where the refracted and the reflected ray leave from */
    dir3 rd, rr;        /* their directions */
    real wt, wr;        /* their weights in the pixel */
    real transmit, kr;  /* their factors in the hit's colour */
    int from_t, from_r; /* trace_ray's `from` for each */
    int cast_t, cast_r; /* 1: the ray is traced */
} trace_rays;

static __attribute__((noinline)) int trace_shade_rays(trace_ctx *c, TRACE_RAY_PARAMS, int level,
                                                      real weight, real *travelled, int from,
                                                      trace_rays *r, rt_color *col)
{
    trace_hit hit;
    const trace_hit *h = &hit;
    if (!trace_shade(c, TRACE_RAY_PASS, level, weight, travelled, from, &hit, col))
        return 0;
    const rt_scene *s = c->scene;
    const rt_material *m = h->m;
    const dir3 d = h->d, n = h->n;
    const int inside = h->inside;
    const int sphere = s->objects[h->id].kind == RT_SPHERE;
    real kr = m->reflect;
    unit dk = inside ? d3_dot(d, n) : h->dn;
    r->cast_t = r->cast_r = 0;
    if (rt_scene_has(s, RT_FX_REFRACT) && m->transmit > 0) {
        real eta = inside ? m->ior : m->ior_inv;
        if (d3_refract_k(d, n, dk, eta, &r->rd)) {
            real wt = r_mul_c(weight, m->transmit);
            if (wt >= c->min_contrib) { /* adaptive recursion control */
                c->stats->rays_refract++;
                r->cast_t = 1;
                r->wt = wt;
                r->transmit = m->transmit;
                r->p_in = v3_along_in(h->p, n, r_neg(R_EPS_OFFSET));
                r->from_t = sphere ? 2 * h->id + !inside : -1;
            }
        } else {
            kr = r_add(kr, m->transmit); /* total internal reflection */
        }
    }
    real wr = r_mul_c(weight, kr);
    if (kr > 0 && wr >= c->min_contrib) {
        c->stats->rays_reflect++;
        r->cast_r = 1;
        r->wr = wr;
        r->kr = kr;
        r->p_out = h->p_out;
        r->rr = d3_reflect_k(d, n, dk);
        r->from_r = sphere ? 2 * h->id + inside : !inside && !s->cull.forced ? 2 * h->id : -1;
    }
    return 1;
}

static rt_color trace_ray(trace_ctx *c, TRACE_RAY_PARAMS, int level, real weight, real travelled,
                          int from)
{
    trace_rays r;
    rt_color col;
    if (trace_shade_rays(c, TRACE_RAY_PASS, level, weight, &travelled, from, &r, &col)) {
        if (r.cast_t)
            col = c3_madd_p(col, trace_ray(c, &r.p_in, &r.rd, level + 1, r.wt, travelled, r.from_t),
                            r.transmit);
        if (r.cast_r)
            col = c3_madd_p(
                col, trace_ray(c, &r.p_out, &r.rr, level + 1, r.wr, travelled, r.from_r), r.kr);
    }
    return col;
}
#endif

__attribute__((cold)) int rt_light_term(const rt_scene *s, rt_stats *st, rt_hit *h, int i,
                                        rt_color *term)
{
    trace_ctx c = {.scene = s, .stats = term ? NULL : st}; /* NULL: no shadow ray */
    rt_color col = v3(0, 0, 0);
    const int state = trace_light(&c, h, i, &col);
    if (term)
        *term = col;
    return state;
}

/* Shared by rt_trace_pixel_local and rt_trace_pixel_from: inlined into each (`pri` NULL in the
 * first). */
static inline __attribute__((always_inline)) void trace_point(const rt_scene *s, const rt_view *v,
                                                              const rt_params *p, int x, int y,
                                                              rt_stats *stats, rt_sample *out,
                                                              rt_primary *pri, const rt_local *loc)
{
    int at_eye = rt_scene_at_eye(s, v->eye);
    int eye_prepared = RT_COMPILED_PROBE && pri ? 2 : at_eye;
    /* adaptive and probe mode, from the prepared eye (the primary hit as ss_cells finds it
     * again, with rt_nearest_primary; trace_first finds it so too) */
    const int alt = at_eye && p->mode != RT_MODE_FULL;
    trace_ctx c = {.scene = s,
                   .stats = stats,
                   .sample = out,
                   .min_contrib = p->min_contrib,
                   .octaves = p->octaves,
                   .pixel = p->footprint ? v->pixel : 0,
                   .eye_prepared = eye_prepared,
                   .pri = pri,
                   .primary_cand = rt_view_candidates(v, x, y),
                   .mirror = at_eye ? v->mirror_plane : -1,
                   .mirror_cand = rt_view_mirror_candidates(v, x, y),
                   .alt = alt,
                   .local = loc};
    out->head = 0; /* nhits, lights, cell; flags, which the callers set after */
    out->alt_known = RT_ALT_NONE;
    dir3 d;
    if (RT_COMPILED_PROBE && pri) {
        if (pri->id == RT_PRIMARY_UNKNOWN)
            pri->d = rt_view_ray(v, x, y);
        d = pri->d;
    } else {
        d = rt_view_ray(v, x, y);
    }
    stats->rays_primary++;
    c.depth = p->depth < s->reach_depth ? p->depth : s->reach_depth;
    rt_color col = trace_ray(&c, TRACE_RAY_ARG(v->eye), TRACE_RAY_ARG(d), 0, R_ONE, 0, -1);
    if (out->alt_known) {
        if (out->alt_known == RT_ALT_TONE) /* the primary hit: a plane with a two-tone checker */
            trace_alt_end(out->alt, out, col);
        else if (out->nhits == 1) /* a noise texture, no secondary ray: B */
            trace_alt_end(out->hits[1].contrib, out, col);
        else
            out->alt_known = RT_ALT_NONE;
    }
    out->color = col;
}

void rt_trace_pixel_local(const rt_scene *s, const rt_view *v, const rt_params *p, int x, int y,
                          const rt_local *loc, rt_stats *stats, rt_sample *out)
{
    trace_point(s, v, p, x, y, stats, out, NULL, loc);
}

#if RT_COMPILED_PROBE
FX_BOARD_THUMB
void rt_trace_pixel_from(const rt_scene *s, const rt_view *v, const rt_params *p, int x, int y,
                         rt_primary *pri, rt_stats *stats, rt_sample *out)
{
    trace_point(s, v, p, x, y, stats, out, pri, NULL);
}
#endif
