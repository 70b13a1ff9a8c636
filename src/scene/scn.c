/* scn.c: the timeline: interpolates a scene description's tracks in integers and builds the rt_scene of one moment. */
#include <stddef.h>

#include "scn.h"

#define Q(x) ((int32_t)((x)*SCN_ONE))
#define SCN_COORD Q(4096) /* R_SCENE_MAX */

/* Ranges follow the numeric layer (see docs/scene-format.md): positions inside the scene
 * cube, colours and coefficients in [0, 1], light intensities small enough that a pixel's
 * colour sums stay far inside Q16.16 even at full recursion depth. */
const scn_param_info scn_params[SCN_P_COUNT] = {
    [SCN_P_BACKGROUND] = {"background", SCN_OWN_SCENE, 3, 0, Q(1)},
    [SCN_P_AMBIENT] = {"ambient", SCN_OWN_SCENE, 3, 0, Q(1)},
    [SCN_P_EYE] = {"eye", SCN_OWN_CAMERA, 3, -SCN_COORD, SCN_COORD},
    [SCN_P_AT] = {"at", SCN_OWN_CAMERA, 3, -SCN_COORD, SCN_COORD},
    [SCN_P_UP] = {"up", SCN_OWN_CAMERA, 3, -SCN_COORD, SCN_COORD},
    [SCN_P_FOV] = {"fov", SCN_OWN_CAMERA, 1, Q(10), Q(120)},
    [SCN_P_LIGHT_POS] = {"pos", SCN_OWN_LIGHT, 3, -SCN_COORD, SCN_COORD},
    [SCN_P_LIGHT_COLOR] = {"color", SCN_OWN_LIGHT, 3, 0, Q(16)},
    [SCN_P_CENTER] = {"center", SCN_OWN_SPHERE, 3, -SCN_COORD, SCN_COORD},
    [SCN_P_RADIUS] = {"radius", SCN_OWN_SPHERE, 1, SCN_ONE / 128, Q(2048)},
    [SCN_P_NORMAL] = {"normal", SCN_OWN_PLANE, 3, -SCN_COORD, SCN_COORD},
    [SCN_P_OFFSET] = {"offset", SCN_OWN_PLANE, 1, -SCN_COORD, SCN_COORD},
    [SCN_P_DIFFUSE] = {"diffuse", SCN_OWN_MATERIAL, 3, 0, Q(1)},
    [SCN_P_COLOR2] = {"color2", SCN_OWN_MATERIAL, 3, 0, Q(1)},
    [SCN_P_MAT_AMBIENT] = {"ambient", SCN_OWN_MATERIAL, 1, 0, Q(1)},
    [SCN_P_SPECULAR] = {"specular", SCN_OWN_MATERIAL, 1, 0, Q(1)},
    [SCN_P_REFLECT] = {"reflect", SCN_OWN_MATERIAL, 1, 0, Q(1)},
    [SCN_P_TRANSMIT] = {"transmit", SCN_OWN_MATERIAL, 1, 0, Q(1)},
    [SCN_P_IOR] = {"ior", SCN_OWN_MATERIAL, 1, Q(1), Q(3)},
    [SCN_P_SCALE] = {"scale", SCN_OWN_MATERIAL, 1, SCN_ONE / 256, Q(64)},
    [SCN_P_TURBULENCE] = {"turbulence", SCN_OWN_MATERIAL, 1, 0, Q(16)},
};

/* v / 65536 rounded half up, for any sign (no shift of a negative number). */
static int64_t scn_round16(int64_t v)
{
    v += 32768;
    return v >= 0 ? v / 65536 : -((-v + 65535) / 65536);
}

static int32_t scn_clamp(int64_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : (v > hi ? hi : (int32_t)v);
}

/* Hermite tangent at key b for the segment [b, c]: the slope from a to c, scaled to the
 * segment's length, so that the curve's speed is continuous at keys of uneven spacing. */
static int64_t scn_tangent(int64_t pa, int64_t pc, int32_t ta, int32_t tc, int32_t seg)
{
    if (tc == ta)
        return 0;
    return (pc - pa) * seg / (tc - ta);
}

void scn_track_value(const scn_desc *d, const scn_track *tr, int32_t t_ms, int32_t out[3])
{
    const scn_param_info *pi = &scn_params[tr->param];
    const scn_key *k = d->keys + tr->first;
    int n = tr->count;
    int i = 0; /* the segment [k[i], k[i + 1]] holds t */
    while (i + 1 < n && k[i + 1].time_ms <= t_ms)
        i++;
    if (t_ms <= k[0].time_ms || i + 1 >= n || k[i].interp == SCN_STEP) {
        const scn_key *h = t_ms <= k[0].time_ms ? &k[0] : &k[i];
        for (int c = 0; c < pi->arity; c++)
            out[c] = h->v[c];
        return;
    }
    const scn_key *a = &k[i], *b = &k[i + 1];
    int32_t seg = b->time_ms - a->time_ms; /* > 0: keys are in increasing time */
    int64_t u = ((int64_t)(t_ms - a->time_ms) * SCN_ONE) / seg; /* [0, 1) in Q16 */
    int64_t u2 = scn_round16(u * u), u3 = scn_round16(u2 * u);
    for (int c = 0; c < pi->arity; c++) {
        int64_t p1 = a->v[c], p2 = b->v[c], v;
        switch (a->interp) {
        case SCN_LINEAR: v = p1 + scn_round16((p2 - p1) * u); break;
        case SCN_SMOOTH: /* 3u^2 - 2u^3: starts and ends at rest */
            v = p1 + scn_round16((p2 - p1) * (3 * u2 - 2 * u3));
            break;
        default: { /* SCN_SPLINE: Catmull-Rom through the neighbours, as a cubic Hermite */
            const scn_key *a0 = i > 0 ? &k[i - 1] : a;
            const scn_key *b1 = i + 2 < n ? &k[i + 2] : b;
            int64_t m1 = scn_tangent(a0->v[c], p2, a0->time_ms, b->time_ms, seg);
            int64_t m2 = scn_tangent(p1, b1->v[c], a->time_ms, b1->time_ms, seg);
            int64_t h00 = 2 * u3 - 3 * u2 + SCN_ONE, h10 = u3 - 2 * u2 + u;
            int64_t h01 = 3 * u2 - 2 * u3, h11 = u3 - u2;
            v = scn_round16(h00 * p1 + h10 * m1 + h01 * p2 + h11 * m2);
            /* Keep the curve within the four keys it is shaped by: whatever the parser checked
             * on the keys then holds between them too. */
            int64_t lo = p1 < p2 ? p1 : p2, hi = p1 < p2 ? p2 : p1;
            lo = a0->v[c] < lo ? a0->v[c] : lo;
            hi = a0->v[c] > hi ? a0->v[c] : hi;
            lo = b1->v[c] < lo ? b1->v[c] : lo;
            hi = b1->v[c] > hi ? b1->v[c] : hi;
            v = v < lo ? lo : (v > hi ? hi : v);
            break;
        }
        }
        out[c] = scn_clamp(v, pi->lo, pi->hi);
    }
}

static vec3 scn_vec(const int32_t *v)
{
    return v3(r_from_q16(v[0]), r_from_q16(v[1]), r_from_q16(v[2]));
}

/* Writes one parameter's value into the scene. */
static void scn_set(rt_scene *s, int param, int item, const int32_t *v)
{
    /* item indexes the materials only for a material's parameters (an object's can be past
     * the last material: no pointer is formed for it) */
    rt_material *m = param >= SCN_P_DIFFUSE ? &s->materials[item] : NULL;
    real r = r_from_q16(v[0]);
    switch (param) {
    case SCN_P_BACKGROUND: s->background = scn_vec(v); break;
    case SCN_P_AMBIENT: s->ambient = scn_vec(v); break;
    case SCN_P_EYE: s->camera.eye = scn_vec(v); break;
    case SCN_P_AT: s->camera.at = scn_vec(v); break;
    case SCN_P_UP: s->camera.up = scn_vec(v); break;
    case SCN_P_FOV: s->camera.fov = r; break;
    case SCN_P_LIGHT_POS: s->lights[item].pos = scn_vec(v); break;
    case SCN_P_LIGHT_COLOR: s->lights[item].color = scn_vec(v); break;
    case SCN_P_CENTER: s->objects[item].center = scn_vec(v); break;
    case SCN_P_RADIUS: s->objects[item].radius = r; break;
    case SCN_P_NORMAL: s->objects[item].axis = scn_vec(v); break;
    case SCN_P_OFFSET: s->objects[item].offset = r; break;
    case SCN_P_DIFFUSE: m->diffuse = scn_vec(v); break;
    case SCN_P_COLOR2: m->tex.color2 = scn_vec(v); break;
    case SCN_P_MAT_AMBIENT: m->ambient = r; break;
    case SCN_P_SPECULAR: m->specular = r; break;
    case SCN_P_REFLECT: m->reflect = r; break;
    case SCN_P_TRANSMIT: m->transmit = r; break;
    case SCN_P_IOR: m->ior = r; break;
    case SCN_P_SCALE: m->tex.scale = r; break;
    case SCN_P_TURBULENCE: m->tex.turbulence = r; break;
    default: break;
    }
}

void scn_eval(const scn_desc *d, int32_t t_ms, rt_scene *s)
{
    *s = (rt_scene){0};
    s->depth = d->depth;
    s->nobjects = d->nobjects;
    s->nlights = d->nlights;
    s->nmaterials = d->nmaterials;
    scn_set(s, SCN_P_BACKGROUND, 0, d->background);
    scn_set(s, SCN_P_AMBIENT, 0, d->ambient);
    scn_set(s, SCN_P_EYE, 0, d->eye);
    scn_set(s, SCN_P_AT, 0, d->at);
    scn_set(s, SCN_P_UP, 0, d->up);
    scn_set(s, SCN_P_FOV, 0, &d->fov);
    for (int i = 0; i < d->nlights; i++) {
        scn_set(s, SCN_P_LIGHT_POS, i, d->lights[i].pos);
        scn_set(s, SCN_P_LIGHT_COLOR, i, d->lights[i].color);
    }
    for (int i = 0; i < d->nobjects; i++) {
        const scn_object *o = &d->objects[i];
        s->objects[i].kind = o->kind;
        s->objects[i].material = o->material;
        scn_set(s, SCN_P_CENTER, i, o->center);
        scn_set(s, SCN_P_RADIUS, i, &o->radius);
        scn_set(s, SCN_P_NORMAL, i, o->normal);
        scn_set(s, SCN_P_OFFSET, i, &o->offset);
    }
    for (int i = 0; i < d->nmaterials; i++) {
        const scn_material *m = &d->materials[i];
        rt_material *rm = &s->materials[i];
        rm->shininess = m->shininess;
        rm->tex.kind = m->texture;
        rm->tex.palette = m->palette;
        rm->tex.octaves = m->octaves;
        scn_set(s, SCN_P_DIFFUSE, i, m->diffuse);
        scn_set(s, SCN_P_COLOR2, i, m->color2);
        scn_set(s, SCN_P_MAT_AMBIENT, i, &m->ambient);
        scn_set(s, SCN_P_SPECULAR, i, &m->specular);
        scn_set(s, SCN_P_REFLECT, i, &m->reflect);
        scn_set(s, SCN_P_TRANSMIT, i, &m->transmit);
        scn_set(s, SCN_P_IOR, i, &m->ior);
        scn_set(s, SCN_P_SCALE, i, &m->scale);
        scn_set(s, SCN_P_TURBULENCE, i, &m->turbulence);
    }
    for (int t = 0; t < d->ntracks; t++) {
        int32_t v[3];
        scn_track_value(d, &d->tracks[t], t_ms, v);
        scn_set(s, d->tracks[t].param, d->tracks[t].item, v);
    }
    rt_scene_prepare(s);
}

/* Can material parameter `param` of material `item` be above zero at some moment? */
static int scn_may_be_positive(const scn_desc *d, int param, int item, int32_t base)
{
    if (base > 0)
        return 1;
    for (int t = 0; t < d->ntracks; t++) {
        const scn_track *tr = &d->tracks[t];
        if (tr->param != param || tr->item != item)
            continue;
        /* a spline between keys of zero swings below zero, never above it: clamped to 0 */
        for (int k = 0; k < tr->count; k++)
            if (d->keys[tr->first + k].v[0] > 0)
                return 1;
    }
    return 0;
}

unsigned scn_effects_union(const scn_desc *d)
{
    unsigned fx = 0;
    for (int i = 0; i < d->nobjects; i++) {
        int mi = d->objects[i].material;
        const scn_material *m = &d->materials[mi];
        if (d->nlights > 0 && scn_may_be_positive(d, SCN_P_SPECULAR, mi, m->specular))
            fx |= RT_FX_SPECULAR;
        if (scn_may_be_positive(d, SCN_P_TRANSMIT, mi, m->transmit))
            fx |= RT_FX_REFRACT | RT_FX_REFLECT;
        if (scn_may_be_positive(d, SCN_P_REFLECT, mi, m->reflect))
            fx |= RT_FX_REFLECT;
        if (m->texture != RT_TEX_NONE)
            fx |= RT_FX_TEXTURE;
        if (m->texture == RT_TEX_MARBLE || m->texture == RT_TEX_WOOD || m->texture == RT_TEX_NOISE)
            fx |= RT_FX_NOISE;
    }
    /* Two objects can shadow each other, and a sphere its own inside (seen through glass or
     * by a camera inside it). */
    int spheres = 0;
    for (int i = 0; i < d->nobjects; i++)
        spheres += d->objects[i].kind == RT_SPHERE;
    if (d->nlights > 0 && (d->nobjects > 1 || spheres > 0))
        fx |= RT_FX_SHADOW;
    return fx;
}
