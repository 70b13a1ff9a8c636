/* scn_lex.h: private to the scene parser: its state, tokens, number syntax and error reports. */
#ifndef FIXRAY_SCN_LEX_H
#define FIXRAY_SCN_LEX_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "scn_parse.h"

typedef struct ps_tok {
    const char *s;
    int len;
} ps_tok;

#define PS_MAX_PROPS 32 /* rows of ps_props: a bit each in a statement's `seen` */

typedef struct ps_state {
    const char *path;
    char *err;
    size_t errlen;
    scn_file *f;
    int line;       /* current line, 1-based */
    const char *ls; /* start of the current line */
    const char *p;  /* cursor in the current line */
    const char *le; /* end of its content (before a comment) */
    int have_camera;
    int global_line[PS_MAX_PROPS]; /* of each scene-wide statement, by its row of ps_props */
    int camera_line;
    int object_line[RT_MAX_OBJECTS], light_line[RT_MAX_LIGHTS], material_line[RT_MAX_MATERIALS];
    int track_line[SCN_MAX_TRACKS], track_col[SCN_MAX_TRACKS]; /* of the latest key */
} ps_state;

/* Writes "path:line:col: " and the message into ps->err; returns -1. */
int ps_fail_at(ps_state *ps, int line, int col, const char *fmt, ...);

/* An error at a point of the current line. */
#define PS_FAIL(ps, at, ...) ps_fail_at((ps), (ps)->line, (int)((at) - (ps)->ls) + 1, __VA_ARGS__)

/* Whether token t is exactly `word`. */
static inline int ps_is(ps_tok t, const char *word)
{
    return (size_t)t.len == strlen(word) && memcmp(t.s, word, (size_t)t.len) == 0;
}

int ps_next(ps_state *ps, ps_tok *t);
int ps_number(ps_state *ps, ps_tok t, const char *what, int32_t *out);
int ps_int(ps_state *ps, ps_tok t, const char *what, long lo, long hi, int32_t *out);
int ps_time(ps_state *ps, ps_tok t, const char *what, int32_t *ms);
int ps_values(ps_state *ps, ps_tok prop, int param, int32_t out[3]);
int ps_end(ps_state *ps);
int ps_bad_property(ps_state *ps, ps_tok t, const char *stmt, ps_tok prev, int prev_arity,
                    const char *expected);
int ps_once(ps_state *ps, ps_tok t, unsigned *seen, unsigned bit);
int ps_word(ps_tok t, const char *const *words, int n);
void ps_join(char *buf, size_t size, const char *const *words, int n, const char *last_sep);

#endif
