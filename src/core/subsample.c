/* subsample.c: adaptive subsampling: trace square corners, split squares whose corners disagree, interpolate the rest (probe mode: probe the points a split adds first, probe.c). */
#include <string.h>

#include "subsample.h"

/* Squares along a side of n pixels: corners at 0, g, 2g, ... and at the last pixel, n - 1
 * (so the last square may be narrower); at least one square, even for n = 1. */
static int ss_count(int n, int g)
{
    int k = (n - 1 + g - 1) / g;
    return k > 0 ? k : 1;
}

/* Pixel coordinate of corner i along a side of n pixels. */
static int ss_corner(int i, int g, int n)
{
    int c = i * g;
    return c < n - 1 ? c : n - 1;
}

FX_BOARD_THUMB unsigned long rt_render_work_size(const rt_params *p, int width)
{
    if (p->mode == RT_MODE_FULL)
        return 0;
    unsigned long row = (unsigned long)ss_count(width, p->grid) + 1;
    unsigned long side = (unsigned long)p->grid + 1;
    return (row + side * side) * sizeof(rt_sample);
}

FX_BOARD_THUMB int rt_render_band_count(const rt_params *p, int height)
{
    return p->mode != RT_MODE_FULL ? ss_count(height, p->grid) : height;
}

/* Adds `bit` to a point's byte of the traced map. Bands running at the same time both trace the
 * points on the edge between them, so the bit is added atomically: inline where the core has
 * byte atomics, through libatomic on a hosted system without them; plainly only on a
 * freestanding core without them (the ARM926 board, which renders on one thread). */
static inline void ss_mark(uint8_t *t, uint8_t bit)
{
#if (defined(__GCC_ATOMIC_CHAR_LOCK_FREE) && __GCC_ATOMIC_CHAR_LOCK_FREE == 2) || __STDC_HOSTED__
    __atomic_fetch_or(t, bit, __ATOMIC_RELAXED);
#else
    *t |= bit;
#endif
}

/* Shows a shaded point: clamps its colour (interpolate what is shown, as the pixel will be)
 * and adds `mark` to its byte of the traced map. */
static void ss_show(ss_ctx *c, int x, int y, rt_sample *out, uint8_t mark)
{
    out->color = v3(r_clamp(out->color.x, 0, R_ONE), r_clamp(out->color.y, 0, R_ONE),
                    r_clamp(out->color.z, 0, R_ONE));
    if (c->traced)
        ss_mark(&c->traced[(long)y * c->view->width + x], mark);
}

/* Marked RT_TRACED_FULL, or RT_TRACED_LOCAL where the point took its local part from the
 * square's corners. */
void ss_shade(ss_ctx *c, const rt_params *p, const ss_area *area, int x, int y, rt_sample *out)
{
    const rt_local *loc = NULL;
    uint32_t local0 = 0;
    if (area) {
        loc = ss_local(c, area, x, y);
        local0 = c->stats->local_points;
    }
    rt_trace_pixel_local(c->scene, c->view, p, x, y, loc, c->stats, out);
    out->flags = RT_COMPILED_PROBE && p->mode == RT_MODE_PROBE
        ? (uint8_t)rt_probe_opaque(&c->opaque, out)
        : 0;
    ss_show(c, x, y, out,
            loc && c->stats->local_points != local0 ? RT_TRACED_LOCAL : RT_TRACED_FULL);
}

/* Probe mode: the point (x, y) a split adds in the middle of an edge from a to b (at fraction
 * t, span pixels long), not decided yet (rt_probe_point); probed, and shaded in full only when
 * rt_probe_point cannot give its colour. */
FX_BOARD_THUMB
static __attribute__((noinline)) void ss_probe_new(ss_ctx *c, int x, int y, const rt_sample *a,
                                                   const rt_sample *b, real t, int span)
{
    rt_sample *sm = &c->lat[(y - c->sy) * c->lstride + (x - c->sx)];
    rt_primary pri;
    int r = rt_probe_point(c->scene, c->view, c->stats, c->thr8, x, y, a, b, t, span, &pri, sm);
    if (r > 0) {
        if (c->traced)
            ss_mark(&c->traced[(long)y * c->view->width + x], RT_TRACED_PROBE);
    } else if (r == 0) {
        /* in full, from the primary hit the probe found */
        rt_trace_pixel_from(c->scene, c->view, c->params, x, y, &pri, c->stats, sm);
        sm->flags = (uint8_t)rt_probe_opaque(&c->opaque, sm);
        ss_show(c, x, y, sm, RT_TRACED_FULL);
    } /* else not probed: shaded where the squares below need it (ss_need), as adaptive mode does */
}

/* Can an edge from a to b have a point worth probing (rt_probe_point)? Not when both ends are
 * opaque or they disagree on a light. */
static inline int ss_probe_edge(const rt_sample *a, const rt_sample *b)
{
    return !(a->flags & b->flags & RT_SAMPLE_OPAQUE) && a->lights == b->lights;
}

/* Probe mode: the points splitting the square (x0, y0, w, h) into nx by ny adds (k: its
 * corners) in the middles of the edges it halves, each against the ends of its edge. (Not its
 * centre: a probe there against the four corners measured dearer on the board than the shades
 * it saved, docs/probe.md; it is shaded where the squares below need it.) A point some square
 * added before is kept: it got its record from the same context (the ends of its edge), so the
 * frame does not depend on the order squares are visited in. */
static __attribute__((noinline)) void ss_probe_split(ss_ctx *c, int x0, int y0, int w, int h,
                                                     int nx, int ny, const rt_sample *const k[4])
{
    if (k[0]->flags & k[1]->flags & k[2]->flags & k[3]->flags & RT_SAMPLE_OPAQUE)
        return; /* every end opaque: no point is probed (ss_probe_edge) */
    /* the lattice at (x0, y0): a point already decided (nhits) is kept */
    const rt_sample *at = &c->lat[(y0 - c->sy) * c->lstride + (x0 - c->sx)];
    for (int j = 0; j < 2 && nx == 2; j++) /* top, bottom: k[0], k[1] and k[2], k[3] */
        if (!at[j * h * c->lstride + w / 2].nhits && ss_probe_edge(k[2 * j], k[2 * j + 1]))
            ss_probe_new(c, x0 + w / 2, y0 + j * h, k[2 * j], k[2 * j + 1], c->half[w], w);
    for (int i = 0; i < 2 && ny == 2; i++) /* left, right: k[0], k[2] and k[1], k[3] */
        if (!at[h / 2 * c->lstride + i * w].nhits && ss_probe_edge(k[i], k[i + 2]))
            ss_probe_new(c, x0 + i * w, y0 + h / 2, k[i], k[i + 2], c->half[h], h);
}

/* A split 2x2 square that does not end the frame (sm: its (0, 0) in the lattice): what its
 * four unit squares would do in ss_square, without the calls. They trace the five points
 * between the corners, in this order (as c->quad says, their local parts from `area`'s corners
 * where it is not NULL), and each shows its (0, 0) as the fill shows a corner. */
static void ss_quad(ss_ctx *c, rt_sample *sm, int x0, int y0, const ss_area *area)
{
    const int ls = c->lstride, stride = c->stride;
    rt_px *row = RT_PX(c->pixels, (long)(y0 - c->py0) * stride + x0);
    rt_sample *m = sm + ls;
    const rt_params *p = c->quad;
    ss_need(c, p, area, x0 + 1, y0, sm + 1);
    ss_need(c, p, area, x0, y0 + 1, m);
    ss_need(c, p, area, x0 + 1, y0 + 1, m + 1);
    ss_need(c, p, area, x0 + 2, y0 + 1, m + 2);
    ss_need(c, p, area, x0 + 1, y0 + 2, m + ls + 1);
    rt_px_set(row, ss_pixel_in(&sm->color));
    rt_px_set(RT_PX(row, 1), ss_pixel_in(&sm[1].color));
    rt_px_set(RT_PX(row, stride), ss_pixel_in(&m->color));
    rt_px_set(RT_PX(row, stride + 1), ss_pixel_in(&m[1].color));
}

/* The square with corners (x0, y0) and (x0 + w, y0 + h), at subdivision `level` (sm: its
 * (0, 0) in the lattice). It writes the pixels it owns: [x0, x0 + w) x [y0, y0 + h), plus its
 * right column and bottom row where it ends the frame (`own`: enum ss_own). Every pixel is
 * thus written once, whatever the order. Its corners not traced yet take their local parts
 * from `area` (the square whose split added them, ss_local_ok; NULL: shaded in full). */
static void ss_square(ss_ctx *c, rt_sample *sm, int x0, int y0, int w, int h, int level, int own,
                      const ss_area *area)
{
    const int ls = c->lstride;
    const rt_params *p = c->params;
    rt_sample *k2 = sm + h * ls;
    ss_need(c, p, area, x0, y0, sm);
    ss_need(c, p, area, x0 + w, y0, sm + w);
    ss_need(c, p, area, x0, y0 + h, k2);
    ss_need(c, p, area, x0 + w, y0 + h, k2 + w);
    if (w > 1 || h > 1) { /* some pixel is not a corner */
        int li = level < RT_GRID_LEVELS ? level : RT_GRID_LEVELS - 1;
        rt_stats *st = c->stats;
        st->squares[li]++;
        const rt_sample *k[4] = {sm, sm + w, k2, k2 + w};
        enum rt_split_reason why = rt_corners_differ(k, c->thr8);
        /* a small sphere (1) or a pool of light (2) between the corners: split, no shortcut
         * fills it */
        int small = 0;
        if (why == RT_SPLIT_NONE && c->view->small && ss_small_missed(c->view, k, x0, y0, w, h)) {
            why = RT_SPLIT_OBJECT;
            small = 1;
        }
        if (RT_FINE_DETAIL && c->view->pool && ss_pool_over(c->view, k, x0, y0, w, h)) {
            why = RT_SPLIT_OBJECT;
            small = 2; /* and no probe: a probe sees no light */
        }
        /* Corners in one checker cell, or whose other differences split them, where the cells
         * are so fine that one id can mean several cells between them: filled by the cell of
         * each pixel (ss_cells) or split, as corners in different cells are. */
        if ((why == RT_SPLIT_NONE || why == RT_SPLIT_CONTRIB || why == RT_SPLIT_LIGHT) &&
            sm->cell && ss_cells_unsure(c, sm->hits[0].object, w, h) &&
            ss_cells_apart(c, sm->hits[0].object, x0, y0, w, h))
            why = RT_SPLIT_OBJECT;
        /* a noise texture beyond the primary hit: split for the secondary rays (its points
         * take their local parts from the corners where they allow, ss_local_ok) */
        if (why == RT_SPLIT_NONE && w > 2 && c->noise_beyond && ss_noise_maybe(c, k[0]) &&
            ss_noise_seen(c, k))
            why = RT_SPLIT_SECONDARY;
        if (why != RT_SPLIT_NONE) {
            if (!small && ss_fill_instead(c, why, sm, k, x0, y0, w, h, own))
                return;
            st->split[li]++;
            st->split_by[why]++;
            c->split = 1;
            int nx = w >= 2 ? 2 : 1, ny = h >= 2 ? 2 : 1;
            if (RT_COMPILED_PROBE && p->mode == RT_MODE_PROBE && small != 2)
                ss_probe_split(c, x0, y0, w, h, nx, ny, k);
            /* the points it adds: their local parts interpolated where its corners allow */
            const ss_area here = {k, x0, y0, w, h};
            const ss_area *in = why == RT_SPLIT_SECONDARY && ss_local_ok(c, k, w, h) ? &here : NULL;
            if (w == 2 && h == 2 && !own) {
                ss_quad(c, sm, x0, y0, in);
                return;
            }
            int hw = w / 2, hh = h / 2;
            if (nx == 2 && ny == 2) { /* the four halves, row by row */
                rt_sample *sb = sm + hh * ls;
                ss_square(c, sm, x0, y0, hw, hh, level + 1, 0, in);
                ss_square(c, sm + hw, x0 + hw, y0, w - hw, hh, level + 1, own & SS_OWN_RIGHT, in);
                ss_square(c, sb, x0, y0 + hh, hw, h - hh, level + 1, own & SS_OWN_BOTTOM, in);
                ss_square(c, sb + hw, x0 + hw, y0 + hh, w - hw, h - hh, level + 1, own, in);
            } else if (nx == 2) { /* left and right halves of a square 0 or 1 high */
                ss_square(c, sm, x0, y0, hw, h, level + 1, own & SS_OWN_BOTTOM, in);
                ss_square(c, sm + hw, x0 + hw, y0, w - hw, h, level + 1, own, in);
            } else { /* top and bottom halves of a square 0 or 1 wide */
                rt_sample *sb = sm + hh * ls;
                ss_square(c, sm, x0, y0, w, hh, level + 1, own & SS_OWN_RIGHT, in);
                ss_square(c, sb, x0, y0 + hh, w, h - hh, level + 1, own, in);
            }
            return;
        }
    }
    int cols = ss_cols(w, own), rows = ss_rows(h, own);
    rt_px *dst = RT_PX(c->pixels, (long)(y0 - c->py0) * c->stride + x0);
    const rt_color *const kc[4] = {&sm->color, &sm[w].color, &k2->color, &k2[w].color};
    ss_fill(dst, c->stride, w, h, cols, rows, kc);
    /* Points a neighbour traced for its own decisions show their traced colour. They can only
     * lie on the edges this square shares with squares done before it: its top row and left
     * column (nothing is ever traced inside a square that is not split). */
    for (int i = 1; i < cols; i++)
        if (sm[i].nhits)
            rt_px_set(RT_PX(dst, i), rt_color_pixel(sm[i].color));
    for (int j = 1; j < rows; j++)
        if (sm[j * ls].nhits)
            rt_px_set(RT_PX(dst, (long)j * c->stride), rt_color_pixel(sm[j * ls].color));
}

/* Traces the top-level corners of row y into row[0..ncols]. */
static void ss_corner_row(ss_ctx *c, rt_sample *row, int ncols, int y)
{
    int g = c->params->grid, width = c->view->width;
    for (int i = 0; i <= ncols; i++) {
        int x = ss_corner(i, g, width);
        if (i > 0 && x == ss_corner(i - 1, g, width))
            row[i] = row[i - 1]; /* a one-pixel-wide frame */
        else
            ss_shade(c, c->params, NULL, x, y, &row[i]);
    }
}

/* ss_noise_seen's masks (ss_ctx): the objects on a noise texture, and those that cast secondary
 * rays showing what they meet at its scale, eye at `eye`: a plane, a sphere around the eye, a
 * sphere that transmits with index 1 (its refracted rays go straight on). noise_beyond stays 0
 * where there is no such object. */
static __attribute__((cold, noinline)) void ss_noise_masks(ss_ctx *c, const rt_scene *s, vec3 eye)
{
    uint32_t noise = 0, flat = 0;
    for (int i = 0; i < s->nobjects; i++) {
        const rt_object *o = &s->objects[i];
        const rt_material *m = &s->materials[o->material];
        if (m->tex.kind > RT_TEX_CHECKER)
            noise |= (uint32_t)1 << i;
        if ((m->reflect > 0 || m->transmit > 0) &&
            (o->kind == RT_PLANE || (m->transmit > 0 && m->ior == R_ONE) ||
             w_len2(v3_sub_in(o->center, eye)) < o->radius2))
            flat |= (uint32_t)1 << i;
    }
    c->flat_view = flat;
    c->noise_beyond = flat ? noise : 0;
}

/* The frame's context for band rows starting at pixel row py0 of `pixels`. */
static void ss_ctx_init(ss_ctx *c, const rt_scene *s, const rt_view *v, const rt_params *p,
                        uint32_t *pixels, int stride, int py0, rt_stats *stats, uint8_t *traced)
{
    *c = (ss_ctx){.scene = s,
                  .view = v,
                  .params = p,
                  .stats = stats,
                  .pixels = (rt_px *)pixels,
                  .stride = stride,
                  .py0 = py0,
                  .traced = traced,
                  .thr8 = r_to_byte(p->threshold),
                  .lstride = p->grid + 1,
                  .p_quad = *p};
    for (int n = 1; n <= p->grid; n++)
        c->half[n] = r_from_ratio(n / 2, n);
    if (p->mode != RT_MODE_FULL)
        c->p_quad.mode = RT_MODE_FULL;
    if (RT_COMPILED_PROBE && p->mode == RT_MODE_PROBE)
        c->opaque = rt_probe_masks_of(s);
    if (rt_scene_has(s, RT_FX_NOISE) && rt_scene_has(s, RT_FX_REFLECT))
        ss_noise_masks(c, s, v->eye);
}

unsigned long rt_render_edge_size(const rt_params *p, int width, int nbands)
{
    if (p->mode == RT_MODE_FULL || nbands < 1)
        return 0;
    return (unsigned long)(nbands + 1) * (unsigned long)(ss_count(width, p->grid) + 1) *
        sizeof(rt_sample);
}

void rt_render_edge(const rt_scene *s, const rt_view *v, const rt_params *p, rt_stats *stats,
                    void *edges, uint8_t *traced, int e, int nbands)
{
    if (p->mode == RT_MODE_FULL || nbands < 1 || e < 0 || e > nbands)
        return;
    const int g = p->grid, ncols = ss_count(v->width, g), nrows = ss_count(v->height, g);
    ss_ctx c;
    ss_ctx_init(&c, s, v, p, NULL, 0, 0, stats, traced);
    ss_corner_row(&c, (rt_sample *)edges + (long)e * (ncols + 1), ncols,
                  ss_corner((int)((long)nrows * e / nbands), g, v->height));
}

void rt_render_adaptive(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
                        int stride, rt_stats *stats, void *work, uint8_t *traced, int band,
                        int nbands, enum rt_band_memory mem, const void *edges)
{
    const int g = p->grid, width = v->width, height = v->height;
    int ncols = ss_count(width, g), nrows = ss_count(height, g);
    /* This band's rows of squares, and the pixel rows it owns. */
    int r0 = (int)((long)nrows * band / nbands), r1 = (int)((long)nrows * (band + 1) / nbands);
    if (r0 == r1 || (RT_GRID_BUILD_MAX < RT_GRID_MAX && g > RT_GRID_BUILD_MAX))
        return;
    ss_ctx c;
    ss_ctx_init(&c, s, v, p, pixels, stride, mem == RT_BAND_FRAME ? 0 : ss_corner(r0, g, height),
                stats, traced);
    /* the corner rows on the band's edges, traced once for every band (rt_render_edge) */
    const rt_sample *band_edge = edges ? (const rt_sample *)edges + (long)band * (ncols + 1) : NULL;
    const size_t row_bytes = (size_t)(ncols + 1) * sizeof(rt_sample);

    /* One row of corners: the top corners of the row of squares being rendered, each replaced by
     * the bottom one below it as the squares reach it. A square traces its bottom right corner
     * (the first square its bottom left one too); its other corners the lattice keeps from the
     * square before. The corners are shaded in full, so the order does not change them. After a
     * band, the row holds its bottom corners, where the band below finds them (RT_BAND_KEEP). */
    rt_sample *const corners = work;
    rt_sample *const lat = corners + ncols + 1;
    const int ls = c.lstride;
    c.lat = lat;
    if (band_edge)
        memcpy(corners, band_edge, row_bytes);
    else if (mem != RT_BAND_KEEP)
        ss_corner_row(&c, corners, ncols, ss_corner(r0, g, height));
    for (int r = r0; r < r1; r++) {
        int y0 = ss_corner(r, g, height), h = ss_corner(r + 1, g, height) - y0;
        /* the bottom corners given (rt_render_edge); none in a one-pixel-high frame (h 0: they
         * are the top ones, the lattice's row h its row 0) */
        const rt_sample *given = band_edge && r == r1 - 1 && h > 0 ? band_edge + ncols + 1 : NULL;
        c.sy = y0;
        int prev_w = -1;
        /* The lattice holds no traced point but its corners (the square before was not split
         * and its left edge held none): then only the corners move. */
        int clean = 0;
        for (int i = 0; i < ncols; i++) {
            int x0 = ss_corner(i, g, width), w = ss_corner(i + 1, g, width) - x0;
            c.sx = x0;
            rt_sample *row = lat, *hrow = lat + h * ls; /* the lattice's rows 0 and h */
            int edge = 0;                               /* traced points inside the left edge */
            if (clean && w == prev_w) {
                lat[0] = lat[w];
                hrow[0] = hrow[w];
            } else {
                for (int ly = 0; ly <= h; ly++, row += ls) {
                    /* The left edge is the square before's right edge: keep what it traced
                     * (its corners too). */
                    if (prev_w >= 0 && row[prev_w].nhits) {
                        row[0] = row[prev_w];
                        edge |= ly != 0 && ly != h;
                    } else {
                        row[0].nhits = 0;
                    }
                    rt_sample *q = row + 1, *e = row + w; /* columns 1..w, two at a time */
                    for (; q < e; q += 2) {
                        q[0].nhits = 0;
                        q[1].nhits = 0;
                    }
                    if (q == e)
                        q->nhits = 0;
                }
            }
            /* Its top corners into the lattice; then its bottom right one (the first square's
             * bottom left one too) into the row of corners, in place of the top one the lattice
             * now keeps, and into the lattice. (In a one-pixel-wide frame, w 0, the one corner
             * is corners[1]: corners[0] is left behind, and lat[w] is lat[0].) */
            if (prev_w < 0)
                lat[0] = corners[0];
            lat[w] = corners[i + 1];
            for (int k = prev_w < 0 ? 0 : w;; k = w) {
                rt_sample *b = &corners[i + (k == w)];
                if (given)
                    *b = given[i + (k == w)];
                else if (h > 0)
                    ss_shade(&c, c.params, NULL, x0 + k, y0 + h, b);
                if (h > 0)
                    hrow[k] = *b;
                if (k == w)
                    break;
            }
            c.split = 0;
            c.quad = w == g && h == g ? &c.p_quad : p;
            ss_square(&c, lat, x0, y0, w, h, 0,
                      (i == ncols - 1) * SS_OWN_RIGHT | (r == nrows - 1) * SS_OWN_BOTTOM, NULL);
            clean = !c.split && !edge;
            prev_w = w;
        }
    }
}

FX_BOARD_THUMB
void rt_render_band_rows(const rt_params *p, int height, int band, int nbands, int *y0, int *rows)
{
    *y0 = *rows = 0;
    if (nbands < 1 || band < 0 || band >= nbands || height < 1)
        return;
    int n = rt_render_band_count(p, height);
    int b0 = (int)((long)n * band / nbands), b1 = (int)((long)n * (band + 1) / nbands);
    if (b0 == b1)
        return;
    if (p->mode != RT_MODE_FULL) {
        /* rows of squares b0 .. b1 - 1: each owns its top row, the last one the frame's end */
        *y0 = ss_corner(b0, p->grid, height);
        *rows = (b1 == n ? height : ss_corner(b1, p->grid, height)) - *y0;
    } else {
        *y0 = b0;
        *rows = b1 - b0;
    }
}
