/* scn_parse.c: the scene-file parser: integers only, so both builds read a file identically. */
#include "scn_parse.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "noise.h"
#include "scn_lex.h"

/* Where texture coordinates may reach before Q16.16 runs out: |point| x scale must stay below
 * this. The noise textures need headroom (the wood texture takes a hypotenuse of two such
 * coordinates: 20000 * sqrt 2 < 32767); the checker only adds 0.5 and rounds down. */
#define PS_TEXTURE_REACH 20000
#define PS_CHECKER_REACH 32000
/* How far from the origin a plane's visible points can lie: the camera inside the scene cube
 * plus the longest ray (R_SCENE_MAX + R_T_MAX). */
#define PS_PLANE_REACH (4096 + 16384)

/* Finds a name among the scene's items: sets *owner and *item, or returns -1. */
static int ps_lookup(const ps_state *ps, ps_tok t, int *owner, int *item)
{
    const scn_file *f = ps->f;
    for (int i = 0; i < f->desc.nobjects; i++)
        if (ps_is(t, f->object_names[i])) {
            *owner = f->desc.objects[i].kind == RT_SPHERE ? SCN_OWN_SPHERE : SCN_OWN_PLANE;
            *item = i;
            return 0;
        }
    for (int i = 0; i < f->desc.nlights; i++)
        if (ps_is(t, f->light_names[i])) {
            *owner = SCN_OWN_LIGHT;
            *item = i;
            return 0;
        }
    for (int i = 0; i < f->desc.nmaterials; i++)
        if (ps_is(t, f->material_names[i])) {
            *owner = SCN_OWN_MATERIAL;
            *item = i;
            return 0;
        }
    return -1;
}

static int ps_def_line(const ps_state *ps, int owner, int item)
{
    if (owner == SCN_OWN_LIGHT)
        return ps->light_line[item];
    if (owner == SCN_OWN_MATERIAL)
        return ps->material_line[item];
    return ps->object_line[item];
}

/* A new item's name: well-formed, not reserved, not taken. */
static int ps_new_name(ps_state *ps, ps_tok kw, ps_tok *t, char *dst)
{
    if (!ps_next(ps, t))
        return PS_FAIL(ps, kw.s, "'%.*s' needs a name", kw.len, kw.s);
    int ok = t->len <= SCN_MAX_NAME &&
        ((t->s[0] >= 'a' && t->s[0] <= 'z') || (t->s[0] >= 'A' && t->s[0] <= 'Z') ||
         t->s[0] == '_');
    for (int i = 1; ok && i < t->len; i++) {
        char c = t->s[i];
        ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
            c == '_' || c == '-';
    }
    if (!ok)
        return PS_FAIL(ps, t->s,
                       "'%.*s' is not a valid name (a letter or _, then letters, digits, _ "
                       "or -, at most %d characters)",
                       t->len, t->s, SCN_MAX_NAME);
    if (ps_is(*t, "camera") || ps_is(*t, "scene"))
        return PS_FAIL(ps, t->s, "'%.*s' is reserved and cannot name an item", t->len, t->s);
    int owner, item;
    if (ps_lookup(ps, *t, &owner, &item) == 0)
        return PS_FAIL(ps, t->s, "duplicate name '%.*s' (first defined at line %d)", t->len, t->s,
                       ps_def_line(ps, owner, item));
    memcpy(dst, t->s, (size_t)t->len);
    dst[t->len] = 0;
    return 0;
}

static const char *const ps_textures[RT_TEX_COUNT] = {"none", "checker", "marble", "wood", "noise"};
static const char *const ps_palettes[RT_PAL_COUNT] = {"marble", "wood", "lava", "sky"};

/* The statements that have properties. Scene-wide statements (duration, background, ...) are
 * the properties of PS_ST_SCENE, written without a statement word. */
enum ps_stmt { PS_ST_SCENE, PS_ST_CAMERA, PS_ST_LIGHT, PS_ST_MATERIAL, PS_ST_SPHERE, PS_ST_PLANE };
static const char *const ps_stmt_word[] = {"scene",    "camera", "light",
                                           "material", "sphere", "plane"};
/* as unknown properties name them: "unknown property 'x' of a light" */
static const char *const ps_stmt_what[] = {"the scene",  "the camera", "a light",
                                           "a material", "a sphere",   "a plane"};
#define PS_IN(stmt) (1u << (stmt))
#define PS_IN_OBJECT (PS_IN(PS_ST_SPHERE) | PS_IN(PS_ST_PLANE))

/* What a property's value is, and how it is read. */
enum ps_kind {
    PS_V_NUMBERS,  /* the numbers of scn_params[param], range-checked (ps_values) */
    PS_V_INT,      /* a whole number in lo .. hi */
    PS_V_TIME,     /* seconds, stored as milliseconds */
    PS_V_WORD,     /* one of words[0 .. nwords-1], stored as its index */
    PS_V_MATERIAL, /* the name of a material defined before, stored as its index */
};

/* One property of one or more statements: its name, its value, and where the value goes in the
 * statement's record (scn_desc for the scene and the camera, scn_light, scn_material,
 * scn_object). A statement's properties are listed in its rows' order in error messages. */
typedef struct ps_prop {
    const char *name;
    uint8_t stmts;            /* PS_IN() of the statements that take it */
    uint8_t kind;             /* enum ps_kind */
    uint8_t required;         /* the statement must give it */
    uint8_t param;            /* PS_V_NUMBERS: enum scn_param */
    uint16_t at;              /* offset of the field in the record */
    uint8_t size;             /* its size in bytes: 1, 2 or 4 (other kinds than PS_V_NUMBERS) */
    int32_t lo, hi;           /* PS_V_INT */
    const char *const *words; /* PS_V_WORD */
    uint8_t nwords;
} ps_prop;

/* offset and size of a field of a statement's record */
#define PS_AT(type, field) offsetof(type, field), sizeof(((type *)0)->field)
#define PS_OPTIONAL 0
#define PS_REQUIRED 1
/* the value's limits: none (PS_V_NUMBERS take scn_params'), lo .. hi, a list of words */
#define PS_NOTHING 0, 0, NULL, 0
#define PS_RANGE(lo, hi) lo, hi, NULL, 0
#define PS_LIST(words, n) 0, 0, words, n

static const ps_prop ps_props[] = {
    {"duration", PS_IN(PS_ST_SCENE), PS_V_TIME, PS_OPTIONAL, 0, PS_AT(scn_desc, duration_ms),
     PS_NOTHING},
    {"fps", PS_IN(PS_ST_SCENE), PS_V_INT, PS_OPTIONAL, 0, PS_AT(scn_desc, fps),
     PS_RANGE(1, SCN_MAX_FPS)},
    {"depth", PS_IN(PS_ST_SCENE), PS_V_INT, PS_OPTIONAL, 0, PS_AT(scn_desc, depth),
     PS_RANGE(0, RT_MAX_DEPTH)},
    {"background", PS_IN(PS_ST_SCENE), PS_V_NUMBERS, PS_OPTIONAL, SCN_P_BACKGROUND,
     PS_AT(scn_desc, background), PS_NOTHING},
    {"ambient", PS_IN(PS_ST_SCENE), PS_V_NUMBERS, PS_OPTIONAL, SCN_P_AMBIENT,
     PS_AT(scn_desc, ambient), PS_NOTHING},

    {"eye", PS_IN(PS_ST_CAMERA), PS_V_NUMBERS, PS_REQUIRED, SCN_P_EYE, PS_AT(scn_desc, eye),
     PS_NOTHING},
    {"at", PS_IN(PS_ST_CAMERA), PS_V_NUMBERS, PS_REQUIRED, SCN_P_AT, PS_AT(scn_desc, at),
     PS_NOTHING},
    {"up", PS_IN(PS_ST_CAMERA), PS_V_NUMBERS, PS_OPTIONAL, SCN_P_UP, PS_AT(scn_desc, up),
     PS_NOTHING},
    {"fov", PS_IN(PS_ST_CAMERA), PS_V_NUMBERS, PS_OPTIONAL, SCN_P_FOV, PS_AT(scn_desc, fov),
     PS_NOTHING},

    {"pos", PS_IN(PS_ST_LIGHT), PS_V_NUMBERS, PS_REQUIRED, SCN_P_LIGHT_POS, PS_AT(scn_light, pos),
     PS_NOTHING},
    {"color", PS_IN(PS_ST_LIGHT), PS_V_NUMBERS, PS_REQUIRED, SCN_P_LIGHT_COLOR,
     PS_AT(scn_light, color), PS_NOTHING},

    {"diffuse", PS_IN(PS_ST_MATERIAL), PS_V_NUMBERS, PS_OPTIONAL, SCN_P_DIFFUSE,
     PS_AT(scn_material, diffuse), PS_NOTHING},
    {"color2", PS_IN(PS_ST_MATERIAL), PS_V_NUMBERS, PS_OPTIONAL, SCN_P_COLOR2,
     PS_AT(scn_material, color2), PS_NOTHING},
    {"ambient", PS_IN(PS_ST_MATERIAL), PS_V_NUMBERS, PS_OPTIONAL, SCN_P_MAT_AMBIENT,
     PS_AT(scn_material, ambient), PS_NOTHING},
    {"specular", PS_IN(PS_ST_MATERIAL), PS_V_NUMBERS, PS_OPTIONAL, SCN_P_SPECULAR,
     PS_AT(scn_material, specular), PS_NOTHING},
    {"shininess", PS_IN(PS_ST_MATERIAL), PS_V_INT, PS_OPTIONAL, 0, PS_AT(scn_material, shininess),
     PS_RANGE(1, 1000)},
    {"reflect", PS_IN(PS_ST_MATERIAL), PS_V_NUMBERS, PS_OPTIONAL, SCN_P_REFLECT,
     PS_AT(scn_material, reflect), PS_NOTHING},
    {"transmit", PS_IN(PS_ST_MATERIAL), PS_V_NUMBERS, PS_OPTIONAL, SCN_P_TRANSMIT,
     PS_AT(scn_material, transmit), PS_NOTHING},
    {"ior", PS_IN(PS_ST_MATERIAL), PS_V_NUMBERS, PS_OPTIONAL, SCN_P_IOR, PS_AT(scn_material, ior),
     PS_NOTHING},
    {"texture", PS_IN(PS_ST_MATERIAL), PS_V_WORD, PS_OPTIONAL, 0, PS_AT(scn_material, texture),
     PS_LIST(ps_textures, RT_TEX_COUNT)},
    {"palette", PS_IN(PS_ST_MATERIAL), PS_V_WORD, PS_OPTIONAL, 0, PS_AT(scn_material, palette),
     PS_LIST(ps_palettes, RT_PAL_COUNT)},
    {"octaves", PS_IN(PS_ST_MATERIAL), PS_V_INT, PS_OPTIONAL, 0, PS_AT(scn_material, octaves),
     PS_RANGE(1, RT_NOISE_MAX_OCTAVES)},
    {"scale", PS_IN(PS_ST_MATERIAL), PS_V_NUMBERS, PS_OPTIONAL, SCN_P_SCALE,
     PS_AT(scn_material, scale), PS_NOTHING},
    {"turbulence", PS_IN(PS_ST_MATERIAL), PS_V_NUMBERS, PS_OPTIONAL, SCN_P_TURBULENCE,
     PS_AT(scn_material, turbulence), PS_NOTHING},

    {"material", PS_IN_OBJECT, PS_V_MATERIAL, PS_REQUIRED, 0, PS_AT(scn_object, material),
     PS_NOTHING},
    {"center", PS_IN(PS_ST_SPHERE), PS_V_NUMBERS, PS_REQUIRED, SCN_P_CENTER,
     PS_AT(scn_object, center), PS_NOTHING},
    {"radius", PS_IN(PS_ST_SPHERE), PS_V_NUMBERS, PS_REQUIRED, SCN_P_RADIUS,
     PS_AT(scn_object, radius), PS_NOTHING},
    {"normal", PS_IN(PS_ST_PLANE), PS_V_NUMBERS, PS_REQUIRED, SCN_P_NORMAL,
     PS_AT(scn_object, normal), PS_NOTHING},
    {"offset", PS_IN(PS_ST_PLANE), PS_V_NUMBERS, PS_REQUIRED, SCN_P_OFFSET,
     PS_AT(scn_object, offset), PS_NOTHING},
};
#define PS_NPROPS (int)(sizeof ps_props / sizeof *ps_props)
_Static_assert(PS_NPROPS <= PS_MAX_PROPS, "a statement's `seen` has one bit per row of ps_props");

/* The row of property `t` of statement `st`, or -1. */
static int ps_find(int st, ps_tok t)
{
    for (int k = 0; k < PS_NPROPS; k++)
        if ((ps_props[k].stmts & PS_IN(st)) && ps_is(t, ps_props[k].name))
            return k;
    return -1;
}

/* The value of property row `k` (given as token `prop`) into the record at `base`. */
static int ps_value(ps_state *ps, int k, ps_tok prop, char *base)
{
    const ps_prop *r = &ps_props[k];
    if (r->kind == PS_V_NUMBERS)
        return ps_values(ps, prop, r->param, (int32_t *)(void *)(base + r->at));
    ps_tok v;
    if (!ps_next(ps, &v))
        return r->kind == PS_V_MATERIAL
            ? PS_FAIL(ps, prop.s, "'material' needs a material name")
            : PS_FAIL(ps, prop.s, "'%.*s' needs a value", prop.len, prop.s);
    int32_t n = 0;
    if (r->kind == PS_V_INT && ps_int(ps, v, r->name, r->lo, r->hi, &n) != 0)
        return -1;
    if (r->kind == PS_V_TIME && ps_time(ps, v, r->name, &n) != 0)
        return -1;
    if (r->kind == PS_V_WORD && (n = ps_word(v, r->words, r->nwords)) < 0) {
        char list[80];
        ps_join(list, sizeof list, r->words, r->nwords, " or ");
        return PS_FAIL(ps, v.s, "unknown %s '%.*s' (expected %s)", r->name, v.len, v.s, list);
    }
    if (r->kind == PS_V_MATERIAL) {
        int owner = -1, item = 0;
        if (ps_lookup(ps, v, &owner, &item) != 0 || owner != SCN_OWN_MATERIAL)
            return PS_FAIL(ps, v.s,
                           "undefined material '%.*s' (materials are defined before the objects "
                           "that use them)",
                           v.len, v.s);
        n = item;
    }
    void *dst = base + r->at;
    if (r->size == 1)
        *(uint8_t *)dst = (uint8_t)n;
    else if (r->size == 2)
        *(uint16_t *)dst = (uint16_t)n;
    else
        *(int32_t *)dst = n;
    return 0;
}

/* The properties of statement `st` up to the end of the line, into the record at `base`; each
 * one given sets its row's bit in *seen. */
static int ps_properties(ps_state *ps, int st, char *base, unsigned *seen)
{
    ps_tok t, prev = {0};
    int prev_arity = 0;
    while (ps_next(ps, &t)) {
        int k = ps_find(st, t);
        if (k < 0) {
            const char *names[PS_NPROPS];
            int n = 0;
            for (int i = 0; i < PS_NPROPS; i++)
                if (ps_props[i].stmts & PS_IN(st))
                    names[n++] = ps_props[i].name;
            char expected[160];
            ps_join(expected, sizeof expected, names, n, ", ");
            return ps_bad_property(ps, t, ps_stmt_what[st], prev, prev_arity, expected);
        }
        if (ps_once(ps, t, seen, 1u << k) != 0 || ps_value(ps, k, t, base) != 0)
            return -1;
        prev = t;
        prev_arity = ps_props[k].kind == PS_V_NUMBERS ? scn_params[ps_props[k].param].arity : 1;
    }
    return 0;
}

/* The first required property of statement `st` that `seen` lacks, or NULL. */
static const char *ps_missing(int st, unsigned seen)
{
    for (int k = 0; k < PS_NPROPS; k++)
        if ((ps_props[k].stmts & PS_IN(st)) && ps_props[k].required && !(seen & (1u << k)))
            return ps_props[k].name;
    return NULL;
}

static int ps_camera(ps_state *ps, ps_tok kw)
{
    scn_desc *d = &ps->f->desc;
    if (ps->have_camera)
        return PS_FAIL(ps, kw.s, "a second camera (the first is at line %d)", ps->camera_line);
    ps->have_camera = 1;
    ps->camera_line = ps->line;
    unsigned seen = 0;
    if (ps_properties(ps, PS_ST_CAMERA, (char *)d, &seen) != 0)
        return -1;
    if (ps_missing(PS_ST_CAMERA, seen))
        return PS_FAIL(ps, kw.s, "the camera needs both 'eye' and 'at'");
    if (!memcmp(d->eye, d->at, sizeof d->eye))
        return PS_FAIL(ps, kw.s, "the camera's 'eye' and 'at' are the same point");
    return 0;
}

/* A named item's properties (light, material, sphere, plane), then those it lacks. */
static int ps_item(ps_state *ps, int st, ps_tok name, char *base)
{
    unsigned seen = 0;
    if (ps_properties(ps, st, base, &seen) != 0)
        return -1;
    const char *missing = ps_missing(st, seen);
    if (missing)
        return PS_FAIL(ps, name.s, "%s '%.*s' has no '%s'", ps_stmt_word[st], name.len, name.s,
                       missing);
    return 0;
}

static int ps_light(ps_state *ps, ps_tok kw)
{
    scn_desc *d = &ps->f->desc;
    if (d->nlights >= RT_MAX_LIGHTS)
        return PS_FAIL(ps, kw.s, "more than %d lights", RT_MAX_LIGHTS);
    ps_tok name;
    if (ps_new_name(ps, kw, &name, ps->f->light_names[d->nlights]) != 0 ||
        ps_item(ps, PS_ST_LIGHT, name, (char *)&ps->f->lights[d->nlights]) != 0)
        return -1;
    ps->light_line[d->nlights++] = ps->line;
    return 0;
}

static int ps_material(ps_state *ps, ps_tok kw)
{
    scn_desc *d = &ps->f->desc;
    if (d->nmaterials >= RT_MAX_MATERIALS)
        return PS_FAIL(ps, kw.s, "more than %d materials", RT_MAX_MATERIALS);
    ps_tok name;
    if (ps_new_name(ps, kw, &name, ps->f->material_names[d->nmaterials]) != 0)
        return -1;
    scn_material *m = &ps->f->materials[d->nmaterials];
    /* Defaults (docs/scene-format.md): a light grey matte surface. */
    *m = (scn_material){.diffuse = {SCN_ONE * 4 / 5, SCN_ONE * 4 / 5, SCN_ONE * 4 / 5},
                        .ambient = SCN_ONE,
                        .shininess = 20,
                        .ior = SCN_ONE,
                        .scale = SCN_ONE,
                        .turbulence = SCN_ONE,
                        .octaves = 4,
                        .palette = 0xFF};
    if (ps_item(ps, PS_ST_MATERIAL, name, (char *)m) != 0)
        return -1;
    if (m->palette == 0xFF) /* each noise texture has a palette of its own by default */
        m->palette = m->texture == RT_TEX_WOOD ? RT_PAL_WOOD
            : m->texture == RT_TEX_NOISE       ? RT_PAL_LAVA
                                               : RT_PAL_MARBLE;
    if ((int64_t)m->reflect + m->transmit > SCN_ONE)
        return PS_FAIL(ps, name.s, "material '%.*s': reflect + transmit must not exceed 1",
                       name.len, name.s);
    ps->material_line[d->nmaterials++] = ps->line;
    return 0;
}

static int ps_object(ps_state *ps, ps_tok kw, int kind)
{
    scn_desc *d = &ps->f->desc;
    if (d->nobjects >= RT_MAX_OBJECTS)
        return PS_FAIL(ps, kw.s, "more than %d objects", RT_MAX_OBJECTS);
    ps_tok name;
    if (ps_new_name(ps, kw, &name, ps->f->object_names[d->nobjects]) != 0)
        return -1;
    scn_object *o = &ps->f->objects[d->nobjects];
    *o = (scn_object){.kind = (uint8_t)kind};
    if (ps_item(ps, kind == RT_SPHERE ? PS_ST_SPHERE : PS_ST_PLANE, name, (char *)o) != 0)
        return -1;
    ps->object_line[d->nobjects++] = ps->line;
    return 0;
}

static const char *const ps_interps[SCN_INTERP_COUNT] = {"step", "linear", "smooth", "spline"};

/* key TARGET TIME INTERP VALUES... */
static int ps_key(ps_state *ps, ps_tok kw)
{
    scn_file *f = ps->f;
    scn_desc *d = &f->desc;
    ps_tok target, t;
    if (!ps_next(ps, &target))
        return PS_FAIL(ps, kw.s,
                       "'key' needs a track (such as camera.eye), a time, an "
                       "interpolation and values");
    const char *dot = memchr(target.s, '.', (size_t)target.len);
    if (!dot)
        return PS_FAIL(ps, target.s,
                       "'%.*s' is not a track: expected NAME.PARAMETER, such as "
                       "camera.eye",
                       target.len, target.s);
    ps_tok item_name = {target.s, (int)(dot - target.s)};
    ps_tok param_name = {dot + 1, target.len - item_name.len - 1};
    int owner, item = 0;
    if (ps_is(item_name, "camera"))
        owner = SCN_OWN_CAMERA;
    else if (ps_is(item_name, "scene"))
        owner = SCN_OWN_SCENE;
    else if (ps_lookup(ps, item_name, &owner, &item) != 0)
        return PS_FAIL(ps, target.s,
                       "unknown name '%.*s' in track '%.*s' (items are defined "
                       "before their keys)",
                       item_name.len, item_name.s, target.len, target.s);
    int param = -1;
    char have[160] = "";
    for (int p = 0; p < SCN_P_COUNT; p++) {
        if (scn_params[p].owner != owner)
            continue;
        if (ps_is(param_name, scn_params[p].name))
            param = p;
        strcat(have[0] ? strcat(have, ", ") : have, scn_params[p].name);
    }
    if (param < 0)
        return PS_FAIL(ps, param_name.s, "'%.*s' has no animatable parameter '%.*s' (it has: %s)",
                       item_name.len, item_name.s, param_name.len, param_name.s, have);
    scn_key key = {0};
    if (!ps_next(ps, &t))
        return PS_FAIL(ps, target.s, "key '%.*s' needs a time in seconds", target.len, target.s);
    ps_tok time_tok = t;
    int32_t time_ms;
    if (ps_time(ps, t, "key time", &time_ms) != 0)
        return -1;
    key.time_ms = time_ms;
    if (!ps_next(ps, &t))
        return PS_FAIL(ps, target.s,
                       "key '%.*s' needs an interpolation (step, linear, smooth or "
                       "spline)",
                       target.len, target.s);
    int interp = ps_word(t, ps_interps, SCN_INTERP_COUNT);
    if (interp < 0)
        return PS_FAIL(ps, t.s,
                       "unknown interpolation '%.*s' (expected step, linear, smooth or "
                       "spline)",
                       t.len, t.s);
    key.interp = (unsigned)interp;
    if (ps_values(ps, target, param, key.v) != 0 || ps_end(ps) != 0)
        return -1;

    /* Its track: found, or appended. Keys of a track are kept together, in time order. */
    int tr = 0;
    while (tr < d->ntracks && !(f->tracks[tr].param == param && f->tracks[tr].item == item))
        tr++;
    if (tr == d->ntracks) {
        if (d->ntracks >= SCN_MAX_TRACKS)
            return PS_FAIL(ps, target.s, "more than %d animated parameters", SCN_MAX_TRACKS);
        f->tracks[tr] = (scn_track){(uint8_t)param, (uint8_t)item, 0, 0};
        int total = 0;
        for (int i = 0; i < tr; i++)
            total += f->tracks[i].count;
        f->tracks[tr].first = (uint16_t)total;
        d->ntracks++;
    } else {
        const scn_key *last = &f->keys[f->tracks[tr].first + f->tracks[tr].count - 1];
        if (key.time_ms <= last->time_ms)
            return PS_FAIL(ps, time_tok.s,
                           "key at %.*s s is not after the previous key of '%.*s' "
                           "(line %d)",
                           time_tok.len, time_tok.s, target.len, target.s, ps->track_line[tr]);
    }
    int total = 0;
    for (int i = 0; i < d->ntracks; i++)
        total += f->tracks[i].count;
    if (total >= SCN_MAX_KEYS)
        return PS_FAIL(ps, kw.s, "more than %d keys", SCN_MAX_KEYS);
    int at = f->tracks[tr].first + f->tracks[tr].count;
    memmove(&f->keys[at + 1], &f->keys[at], (size_t)(total - at) * sizeof f->keys[0]);
    f->keys[at] = key;
    f->tracks[tr].count++;
    for (int i = 0; i < d->ntracks; i++)
        if (i != tr && f->tracks[i].first >= at)
            f->tracks[i].first++;
    ps->track_line[tr] = ps->line;
    ps->track_col[tr] = (int)(time_tok.s - ps->ls) + 1;
    return 0;
}

static int ps_statement(ps_state *ps)
{
    ps_tok kw;
    if (!ps_next(ps, &kw))
        return 0; /* blank or comment */
    if (ps_is(kw, "camera"))
        return ps_camera(ps, kw);
    if (ps_is(kw, "light"))
        return ps_light(ps, kw);
    if (ps_is(kw, "material"))
        return ps_material(ps, kw);
    if (ps_is(kw, "sphere"))
        return ps_object(ps, kw, RT_SPHERE);
    if (ps_is(kw, "plane"))
        return ps_object(ps, kw, RT_PLANE);
    if (ps_is(kw, "key"))
        return ps_key(ps, kw);
    /* the statements of the whole scene (duration, fps, ...), each allowed once */
    int k = ps_find(PS_ST_SCENE, kw);
    if (k < 0)
        return PS_FAIL(ps, kw.s,
                       "unknown statement '%.*s' (expected duration, fps, depth, background, "
                       "ambient, camera, light, material, sphere, plane or key)",
                       kw.len, kw.s);
    if (ps->global_line[k])
        return PS_FAIL(ps, kw.s, "a second '%s' (the first is at line %d)", ps_props[k].name,
                       ps->global_line[k]);
    ps->global_line[k] = ps->line;
    return ps_value(ps, k, kw, (char *)&ps->f->desc) != 0 ? -1 : ps_end(ps);
}

/* Largest value of component c of (param, item) over its base value and its keys. */
static int64_t ps_max_abs(const scn_desc *d, int param, int item, const int32_t *base, int arity)
{
    int64_t m = 0;
    for (int c = 0; c < arity; c++)
        m = base[c] > m ? base[c] : (-(int64_t)base[c] > m ? -(int64_t)base[c] : m);
    for (int t = 0; t < d->ntracks; t++) {
        const scn_track *tr = &d->tracks[t];
        if (tr->param != param || tr->item != item)
            continue;
        for (int k = 0; k < tr->count; k++)
            for (int c = 0; c < arity; c++) {
                int64_t v = d->keys[tr->first + k].v[c];
                v = v < 0 ? -v : v;
                m = v > m ? v : m;
            }
    }
    return m;
}

/* Checks that need the whole file: required statements, key times, limits across keys. */
static int ps_finish(ps_state *ps)
{
    scn_desc *d = &ps->f->desc;
    int last = ps->line > 1 ? ps->line - 1 : 1;
    if (!ps->have_camera)
        return ps_fail_at(ps, last, 1,
                          "the scene has no camera (a line such as 'camera eye 0 2 8 "
                          "at 0 1 0')");
    if (d->nobjects == 0)
        return ps_fail_at(ps, last, 1, "the scene has no sphere or plane");
    for (int t = 0; t < d->ntracks; t++) {
        const scn_track *tr = &d->tracks[t];
        int32_t end = d->keys[tr->first + tr->count - 1].time_ms;
        if (end > d->duration_ms)
            return ps_fail_at(
                ps, ps->track_line[t], ps->track_col[t],
                "key at %ld.%03ld s is past the end of the scene (duration %ld.%03ld s)",
                (long)end / 1000, (long)end % 1000, (long)d->duration_ms / 1000,
                (long)d->duration_ms % 1000);
    }
    for (int i = 0; i < d->nmaterials; i++) {
        const scn_material *m = &d->materials[i];
        int64_t r = ps_max_abs(d, SCN_P_REFLECT, i, &m->reflect, 1);
        int64_t tr = ps_max_abs(d, SCN_P_TRANSMIT, i, &m->transmit, 1);
        if (r + tr > SCN_ONE)
            return ps_fail_at(ps, ps->material_line[i], 1,
                              "material '%s': reflect + transmit "
                              "exceeds 1 in its keys",
                              ps->f->material_names[i]);
    }
    for (int i = 0; i < d->nobjects; i++) {
        const scn_object *o = &d->objects[i];
        const scn_material *m = &d->materials[o->material];
        if (m->texture == RT_TEX_NONE)
            continue;
        int64_t reach = PS_PLANE_REACH;
        if (o->kind == RT_SPHERE)
            reach = (ps_max_abs(d, SCN_P_CENTER, i, o->center, 3) +
                     ps_max_abs(d, SCN_P_RADIUS, i, &o->radius, 1) + SCN_ONE - 1) /
                SCN_ONE;
        int64_t scale = ps_max_abs(d, SCN_P_SCALE, o->material, &m->scale, 1);
        int limit = m->texture == RT_TEX_CHECKER ? PS_CHECKER_REACH : PS_TEXTURE_REACH;
        if (scale * reach > (int64_t)limit * SCN_ONE) {
            char s[16];
            scn_format_q16((int32_t)scale, s);
            return ps_fail_at(ps, ps->object_line[i], 1,
                              "%s '%s': texture scale %s of material "
                              "'%s' takes its points %lld units out, beyond the %d that Q16.16 "
                              "%s textures allow",
                              o->kind == RT_SPHERE ? "sphere" : "plane", ps->f->object_names[i], s,
                              ps->f->material_names[o->material],
                              (long long)(scale * reach / SCN_ONE), limit,
                              m->texture == RT_TEX_CHECKER ? "checker" : "noise");
        }
    }
    d->tracks = ps->f->tracks;
    d->keys = ps->f->keys;
    return 0;
}

int scn_parse(const char *path, const char *text, size_t len, scn_file *f, char *err, size_t errlen)
{
    static ps_state ps;
    memset(&ps, 0, sizeof ps);
    ps.path = path;
    ps.err = err;
    ps.errlen = errlen;
    ps.f = f;
    memset(f, 0, sizeof *f);
    scn_desc *d = &f->desc;
    /* Defaults (docs/scene-format.md). */
    d->fps = 25;
    d->depth = 5;
    d->up[1] = SCN_ONE;
    d->fov = 50 * SCN_ONE;
    d->ambient[0] = d->ambient[1] = d->ambient[2] = SCN_ONE / 10;
    d->objects = f->objects;
    d->lights = f->lights;
    d->materials = f->materials;
    d->tracks = f->tracks;
    d->keys = f->keys;

    const char *s = text, *end = text + len;
    for (ps.line = 1; s < end; ps.line++) {
        const char *nl = memchr(s, '\n', (size_t)(end - s));
        const char *le = nl ? nl : end;
        ps.ls = ps.p = s;
        if (le - s > SCN_MAX_LINE)
            return ps_fail_at(&ps, ps.line, SCN_MAX_LINE + 1, "line longer than %d characters",
                              SCN_MAX_LINE);
        if (le > s && le[-1] == '\r')
            le--;
        ps.le = le;
        for (const char *c = s; c < le; c++) {
            unsigned char ch = (unsigned char)*c;
            if (ch == '#') {
                ps.le = c;
                break;
            }
            if ((ch < 32 && ch != '\t') || ch >= 127)
                return PS_FAIL(&ps, c,
                               "unexpected character 0x%02x (scene files are plain ASCII "
                               "text)",
                               ch);
        }
        if (ps_statement(&ps) != 0)
            return -1;
        s = nl ? nl + 1 : end;
    }
    return ps_finish(&ps);
}

int scn_load(const char *path, scn_file *f, char *err, size_t errlen)
{
    FILE *fp = fopen(path, "rb");
    if (!fp) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    char *buf = malloc((size_t)SCN_MAX_FILE_BYTES + 1);
    if (!buf) {
        fclose(fp);
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    size_t n = fread(buf, 1, (size_t)SCN_MAX_FILE_BYTES + 1, fp);
    int bad = ferror(fp);
    fclose(fp);
    int rc = -1;
    if (bad)
        snprintf(err, errlen, "%s: cannot read (is it a directory?)", path);
    else if (n > (size_t)SCN_MAX_FILE_BYTES)
        snprintf(err, errlen, "%s: larger than %ld bytes: not a scene file", path,
                 SCN_MAX_FILE_BYTES);
    else
        rc = scn_parse(path, buf, n, f, err, errlen);
    free(buf);
    return rc;
}
