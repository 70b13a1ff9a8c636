/* subsample.h: adaptive subsampling's own interface between its files (subsample*.c), the core's only.
 *
 * subsample.c: the band driver, the recursion over squares and the shading of their points
 * (probe mode's part included); subsample_split.c: whether a square's corners disagree;
 * subsample_fill.c: the integer bilinear fills; subsample_shortcut.c: the squares filled
 * instead of split (ss_fill_instead); subsample_local.c: the local parts of a split's points.
 */
#ifndef FIXRAY_SUBSAMPLE_H
#define FIXRAY_SUBSAMPLE_H

#include <stddef.h>

#include "rt_local.h"

/* The pixels a square writes besides [x0, x0 + w) x [y0, y0 + h) where it ends the frame (its
 * `own` bits): its right column, its bottom row. Every pixel is thus written once. */
enum ss_own { SS_OWN_RIGHT = 1, SS_OWN_BOTTOM = 2 };

/* The columns and rows of pixels a w x h square with `own` writes. */
static inline int ss_cols(int w, int own) { return w + (own & SS_OWN_RIGHT); }
static inline int ss_rows(int h, int own) { return h + (own >> 1 & 1); }

/* One frame's adaptive rendering state. */
typedef struct ss_ctx {
    const rt_scene *scene;
    const rt_view *view;
    const rt_params *params;
    rt_stats *stats;
    rt_px *pixels; /* pixel row py0 of the frame */
    int stride;
    int py0;
    uint8_t *traced;
    int thr8;       /* contribution threshold in 1/255 steps */
    rt_sample *lat; /* samples of the current square, (grid + 1)^2, row-major */
    int lstride;    /* grid + 1 */
    int sx, sy;     /* pixel of the lattice's (0, 0) */
    int split;      /* set when a square of the lattice is split (its points traced) */
    /* How the points inside a split 2x2 square are traced (ss_quad, ss_centre): in adaptive and
     * probe mode, within a top-level square of the full grid, as full mode traces them (p_quad,
     * without the other tone of a checker, rt_sample.alt), since no square ever has one of them
     * as a corner: they lie at odd offsets, where every square split further has its corners
     * at even ones (sizes are powers of two); else as the others (params). */
    const rt_params *quad;
    rt_params p_quad;
    rt_probe_masks opaque; /* probe mode: what rt_probe_opaque tests */
    /* ss_noise_seen: the objects on a noise texture (none where no object of flat_view casts
     * secondary rays), and the objects that show what their secondary rays meet at its scale */
    uint32_t noise_beyond, flat_view;
    dir3 ray;                         /* ss_hit_at: the last primary ray's direction */
    real half[RT_GRID_BUILD_MAX + 1]; /* half[n] = (n / 2) / n: a probed edge's middle */
    rt_local loc;                     /* ss_local's result for the point traced */
} ss_ctx;

/* A square split for its secondary rays whose points' local parts are interpolated (ss_local_ok):
 * its corners k[] ((0, 0), (w, 0), (0, h), (w, h)) and its (0, 0) at pixel (x0, y0). */
typedef struct ss_area {
    const rt_sample *const *k;
    int x0, y0, w, h;
} ss_area;

/* subsample.c: shades the point (x, y) in full into *out, traced with params p, taking its
 * local part from the corners of `area` where it is not NULL; clamps its colour, marks it in the
 * traced map, and in probe mode sets its flags. */
void ss_shade(ss_ctx *c, const rt_params *p, const ss_area *area, int x, int y, rt_sample *out);

/* The sample sm of the current square's lattice, the point (x, y): traced on first use. */
static inline void ss_need(ss_ctx *c, const rt_params *p, const ss_area *area, int x, int y,
                           rt_sample *sm)
{
    if (sm->nhits == 0)
        ss_shade(c, p, area, x, y, sm);
}

/* The fills' pixels (subsample_fill.c). The byte of a channel v (Q16.16) is r_to_byte's: v
 * clamped to [0, 65536], then (v 255 + 2^15) >> 16. The fill keeps each channel as
 * V = v 255 + 2^15 instead (SS_V): for -128 <= v <= 65664, V lies in [128, 2^24 - 128], and its
 * bits 16..23 are that byte (v <= 0: V < 2^16, so 0; v >= 65536: V >= 255 2^16, so 255; else
 * the formula itself), so a pixel is three masks and shifts (ss_pack), with no clamp. Every V
 * the fill packs is within that range (ss_fill says why). */
#define SS_V(v) ((v)*255 + 0x8000)

static inline uint32_t ss_pack(int32_t r, int32_t g, int32_t b)
{
    return ((uint32_t)r & 0xFF0000u) | ((uint32_t)g >> 16) << 8 | (uint32_t)b >> 16;
}

/* The pixel of a colour in [0, 1] as the fill gives a corner: r_to_byte of each channel's
 * r_unit_to_q16 (rt_color_pixel's, in the fixed-point build). */
static inline uint32_t ss_pixel_in(const rt_color *c)
{
    return ss_pack(SS_V(r_unit_to_q16(c->x)), SS_V(r_unit_to_q16(c->y)), SS_V(r_unit_to_q16(c->z)));
}

/* ss_pixel_in out of line (subsample_fill.c), for the fills and shortcuts: inlined there it
 * measured larger and no faster on the board. ss_quad, on the usual path, inlines it. */
uint32_t ss_pixel(const rt_color *c);

/* subsample_fill.c: bilinear fill of `cols` x `rows` pixels from dst (stride pixels per row;
 * cols <= w + 1, rows <= h + 1) from the colours of the corners k[]: (0, 0), (w, 0), (0, h),
 * (w, h), each in [0, 1]. */
void ss_fill(rt_px *dst, int stride, int w, int h, int cols, int rows, const rt_color *const k[4]);

/* subsample_local.c: 1 when the local parts of the points a split of the square (corners k[],
 * w x h) adds can be interpolated from its corners'. */
int ss_local_ok(const ss_ctx *c, const rt_sample *const k[4], int w, int h);

/* subsample_local.c: the local part of point (x, y) of the square `area`, a point its split adds
 * (in c->loc). */
const rt_local *ss_local(ss_ctx *c, const ss_area *area, int x, int y);

/* subsample_shortcut.c: the squares filled instead of split. Each returns 1 when it filled the
 * pixels the square owns, 0 to split it. */
int ss_cells(ss_ctx *c, const rt_sample *sm, int x0, int y0, int w, int h, int own);
int ss_noise(ss_ctx *c, const rt_sample *sm, const rt_sample *const k[4], int x0, int y0, int w,
             int h, int own);
int ss_shadow(ss_ctx *c, const rt_sample *const k[4], int x0, int y0, int w, int h);
int ss_centre(ss_ctx *c, rt_sample *sm, const rt_sample *const k[4], int x0, int y0);

/* subsample_shortcut.c: can two points of the square (x0, y0, w, h), whose corners lie on plane
 * id's two-tone checker, have one cell id (rt_sample.cell) in different cells? 1 when the cells
 * of its corners' primary hits are 4 or more apart along an axis (the points between lie within
 * their range), or a corner's ray misses the plane. Only for squares wider than the frame's
 * rt_view.cell_side of the plane allows (ss_cells_unsure). */
__attribute__((noinline)) int ss_cells_apart(ss_ctx *c, int id, int x0, int y0, int w, int h);

/* Must the square (x0, y0, w, h), its corners on object id, test its cell ids (ss_cells_apart)? */
static inline int ss_cells_unsure(const ss_ctx *c, int id, int w, int h)
{
    return RT_FINE_DETAIL && c->view->cell_side[id] < (w > h ? w : h);
}

/* Does a small sphere (rt_view.small) overlap the square (x0, y0, w, h) with none of its corners
 * k on it, its box no wider than about 1.5 times the square (a wider one always has a corner of
 * the square's lattice on it)? It can lie between the corners, unseen by every criterion: the
 * square is split (as for an object) until a corner finds it or no pixel is left. Out of line,
 * called only for squares whose corners agree in a frame with small spheres. */
__attribute__((noinline)) int ss_small_missed(const rt_view *v, const rt_sample *const k[4], int x0,
                                              int y0, int w, int h);

/* subsample_split.c: a square whose corners agree (RT_SPLIT_NONE), corners k[]: 1 when a node
 * below the primary hit, whose parent is an object of c->flat_view, lies on a noise texture
 * (c->noise_beyond) with a contribution over twice the threshold at some corner. The texture
 * varies between any two pixels, so the corners' agreement says nothing of the pixels between
 * them, and a pixel's contribution there can lie anywhere from 0 to about the corners': about
 * half of it off the interpolated one. (At the primary hit the noise pixels, ss_noise, take each
 * pixel's own texture; no record holds the hit beyond.) Only where the parent is flat (a plane,
 * a sphere around the eye, a lens of index 1): a convex mirror or lens shows the texture smaller
 * than a pixel, where full mode aliases too. The square is then split, down to 2x2 squares. */
__attribute__((noinline)) int ss_noise_seen(const ss_ctx *c, const rt_sample *const k[4]);

/* ss_noise_seen's quick test, inline: can corner a's tree hold a node on a noise texture below
 * its primary hit? Not where its one node there is on another object (most corners on a mirror). */
static inline int ss_noise_maybe(const ss_ctx *c, const rt_sample *a)
{
    const unsigned id = a->hits[1].object;
    return a->nhits > 2 || (a->nhits == 2 && id < RT_MAX_OBJECTS && (c->noise_beyond >> id & 1));
}

/* Does a pool of light (rt_view.pool) overlap the square (x0, y0, w, h) with a corner k on its
 * plane? Its peak can lie between the corners: the square is split (as for an object) down to
 * its pixels. Out of line, called only in a frame with such pools. */
__attribute__((noinline)) int ss_pool_over(const rt_view *v, const rt_sample *const k[4], int x0,
                                           int y0, int w, int h);

/* The one place that decides whether a square rt_corners_differ splits (for reason `why`; sm:
 * its (0, 0) in the lattice, k[] its corners, `own` as ss_square's) is filled instead: by the
 * cell of each pixel (checker cells), each pixel's texture (noise), its own test of one light
 * (a shadow edge) or from a smooth centre (contributions). 1 when the square was filled (its
 * stats counted), 0 to split it. Inline: the usual square is split at once. */
static inline int ss_fill_instead(ss_ctx *c, enum rt_split_reason why, rt_sample *sm,
                                  const rt_sample *const k[4], int x0, int y0, int w, int h,
                                  int own)
{
    rt_stats *st = c->stats;
    if (why == RT_SPLIT_OBJECT && sm->cell && ss_cells(c, sm, x0, y0, w, h, own)) {
        st->texture_squares++;
        return 1;
    }
    if ((RT_COMPILED_EFFECTS & RT_FX_NOISE) && why == RT_SPLIT_CONTRIB &&
        sm->alt_known == RT_ALT_NOISE && ss_noise(c, sm, k, x0, y0, w, h, own)) {
        st->noise_squares++;
        return 1;
    }
    if (why == RT_SPLIT_CONTRIB && w == 2 && h == 2 && !own && ss_centre(c, sm, k, x0, y0))
        return 1; /* ss_centre counts its own */
    if (why == RT_SPLIT_LIGHT && !own && ss_shadow(c, k, x0, y0, w, h)) {
        st->shadow_squares++;
        return 1;
    }
    return 0;
}

#endif
