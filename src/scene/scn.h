/* scn.h: scene descriptions with a keyed timeline, in integers: the form scene files parse to and scenes compile to.
 *
 * A description holds every scene value as a Q16.16 integer (65536 = 1.0) and every time in
 * milliseconds, in both builds: the parser never touches floating point, so the fixed and the
 * float build accept and reject exactly the same files and start from exactly the same numbers.
 * scn_eval turns the description at one moment into an rt_scene of the build's own numbers.
 *
 * The timeline is a set of tracks; each animates one parameter (scn_param) of one scene item
 * through keys. A key holds a value and the kind of interpolation towards the next key (Rocket's
 * model): step holds, linear and smooth (ease in and out) blend the two keys, spline follows a
 * Catmull-Rom curve through the neighbouring keys so that a path flows through its keys without
 * stopping. Before the first key a track holds the first value, after the last key the last.
 * Descriptions point at their objects, lights, materials, tracks and keys, so a compiled scene is
 * constant data of just the size it needs.
 */
#ifndef FIXRAY_SCN_H
#define FIXRAY_SCN_H

#include <stdint.h>

#include "rt.h"

#define SCN_ONE 65536 /* 1.0 in a description's Q16.16 values */

/* Longest timeline, and the frame rates a scene may ask for. */
#define SCN_MAX_DURATION_MS (3600 * 1000)
#define SCN_MAX_FPS 240

enum scn_interp { SCN_STEP, SCN_LINEAR, SCN_SMOOTH, SCN_SPLINE, SCN_INTERP_COUNT };

/* Animatable parameters. */
enum scn_param {
    SCN_P_BACKGROUND, /* scene: colour of rays that leave the scene */
    SCN_P_AMBIENT,    /* scene: ambient light colour */
    SCN_P_EYE,        /* camera position */
    SCN_P_AT,         /* camera: point looked at */
    SCN_P_UP,         /* camera: up direction (any length) */
    SCN_P_FOV,        /* camera: vertical field of view, degrees */
    SCN_P_LIGHT_POS,  /* light position */
    SCN_P_LIGHT_COLOR,
    SCN_P_CENTER,  /* sphere */
    SCN_P_RADIUS,  /* sphere */
    SCN_P_NORMAL,  /* plane: normal (any length) */
    SCN_P_OFFSET,  /* plane: distance from the origin along the unit normal */
    SCN_P_DIFFUSE, /* material colours and coefficients */
    SCN_P_COLOR2,
    SCN_P_MAT_AMBIENT,
    SCN_P_SPECULAR,
    SCN_P_REFLECT,
    SCN_P_TRANSMIT,
    SCN_P_IOR,
    SCN_P_SCALE,
    SCN_P_TURBULENCE,
    SCN_P_COUNT
};

/* What a parameter belongs to. */
enum scn_owner {
    SCN_OWN_SCENE,
    SCN_OWN_CAMERA,
    SCN_OWN_LIGHT,
    SCN_OWN_SPHERE,
    SCN_OWN_PLANE,
    SCN_OWN_MATERIAL
};

/* A parameter's name (as written after the dot in a track name), owner, number of components
 * and range: every value, given or interpolated, is clamped into [lo, hi]; the parser rejects
 * given values outside it. */
typedef struct scn_param_info {
    const char *name;
    uint8_t owner;
    uint8_t arity;
    int32_t lo, hi;
} scn_param_info;

extern const scn_param_info scn_params[SCN_P_COUNT];

/* 16 bytes: the time and the interpolation share a word (a scene holds hundreds of keys, and
 * the compiled ones count against the 64 KiB images). */
typedef struct scn_key {
    signed int time_ms : 29; /* 0 .. SCN_MAX_DURATION_MS (< 2^28) */
    unsigned int interp : 3; /* enum scn_interp, towards the next key */
    int32_t v[3];
} scn_key;
_Static_assert(SCN_MAX_DURATION_MS < (1 << 28) && SCN_INTERP_COUNT <= 8,
               "scn_key's bit-fields hold every key time and interpolation");

typedef struct scn_track {
    uint8_t param;  /* enum scn_param */
    uint8_t item;   /* index of the light, object or material (0 for scene and camera) */
    uint16_t first; /* its keys: keys[first .. first + count - 1], in increasing time */
    uint16_t count;
} scn_track;

typedef struct scn_material {
    int32_t diffuse[3], color2[3];
    int32_t ambient, specular, reflect, transmit, ior, scale, turbulence;
    uint16_t shininess;
    uint8_t texture, palette, octaves; /* enum rt_texture_kind, enum rt_palette_id */
} scn_material;

typedef struct scn_object {
    uint8_t kind;              /* enum rt_shape_kind */
    uint8_t material;          /* index into materials */
    int32_t center[3], radius; /* sphere */
    int32_t normal[3], offset; /* plane */
} scn_object;

typedef struct scn_light {
    int32_t pos[3], color[3];
} scn_light;

typedef struct scn_desc {
    int32_t duration_ms;
    int32_t fps;
    int32_t depth; /* recursion limit, 0..RT_MAX_DEPTH */
    int32_t background[3], ambient[3];
    int32_t eye[3], at[3], up[3], fov;
    int nobjects, nlights, nmaterials, ntracks;
    /* nobjects objects, nlights lights, nmaterials materials: arrays of just that length in a
     * compiled scene (NULL when empty), the parser's storage (scn_file) in a parsed one. */
    const scn_object *objects;
    const scn_light *lights;
    const scn_material *materials;
    const scn_track *tracks;
    const scn_key *keys;
} scn_desc;

/* The built-in intro: scenes/intro.scene compiled by rt-scenec (scn_write_c) into
 * build/gen/scene_intro.c, which every program but the tools links. */
extern const scn_desc scn_intro;

/* Value of track `tr` at time t (ms), clamped into its parameter's range: out[0..arity-1]. */
void scn_track_value(const scn_desc *d, const scn_track *tr, int32_t t_ms, int32_t out[3]);

/* The scene at time t (ms): base values, then every track, converted to the build's numbers
 * and prepared (rt_scene_prepare: derived data and effects on demand). */
void scn_eval(const scn_desc *d, int32_t t_ms, rt_scene *s);

/* Effects the scene can need at any moment of its timeline (RT_FX_* bits): what a program
 * with this scene compiled in must contain. A superset of rt_scene.effects at every frame. */
unsigned scn_effects_union(const scn_desc *d);

#endif
