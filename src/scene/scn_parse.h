/* scn_parse.h: reading scene files (docs/scene-format.md) into scene descriptions, and writing descriptions as C. */
#ifndef FIXRAY_SCN_PARSE_H
#define FIXRAY_SCN_PARSE_H

#include <stddef.h>
#include <stdio.h>

#include "scn.h"

#define SCN_MAX_TRACKS 256
#define SCN_MAX_KEYS 4096
#define SCN_MAX_NAME 31
#define SCN_MAX_FILE_BYTES (1L << 20)
#define SCN_MAX_LINE 1024

/* A parsed scene: the description and the storage its objects, lights, materials, tracks and
 * keys point into, plus the names of its items (for messages and statistics). About 100 kB: keep
 * one static (and do not copy it: the description points into it). */
typedef struct scn_file {
    scn_desc desc;
    scn_object objects[RT_MAX_OBJECTS];
    scn_light lights[RT_MAX_LIGHTS];
    scn_material materials[RT_MAX_MATERIALS];
    scn_track tracks[SCN_MAX_TRACKS];
    scn_key keys[SCN_MAX_KEYS];
    char object_names[RT_MAX_OBJECTS][SCN_MAX_NAME + 1];
    char light_names[RT_MAX_LIGHTS][SCN_MAX_NAME + 1];
    char material_names[RT_MAX_MATERIALS][SCN_MAX_NAME + 1];
} scn_file;

/* Parses the scene text (len bytes; need not end in NUL). Returns 0, or -1 with one line
 * "PATH:LINE:COL: what is wrong" (no newline) in err. `path` only names the text in messages. */
int scn_parse(const char *path, const char *text, size_t len, scn_file *f, char *err,
              size_t errlen);

/* Reads and parses the scene file at path. Returns 0, or -1 with a one-line message in err. */
int scn_load(const char *path, scn_file *f, char *err, size_t errlen);

/* Writes d as C source that defines `const scn_desc <name>` (includes "scn.h"). Returns 0, or
 * -1 when the stream fails. */
int scn_write_c(FILE *out, const scn_desc *d, const char *name, const char *source_path);

/* Writes the decimal form of a Q16.16 value (shortest that reads back to it, up to 6
 * decimals) into buf (at least 16 bytes). */
void scn_format_q16(int32_t v, char *buf);

#endif
