/* subsample_shortcut.c: squares filled instead of split (ss_fill_instead): by checker cell, noise texture, one light's shadow, or a smooth centre. */
#include "subsample.h"

/* Pixel (x, y)'s primary ray and its hit on object `id` as the tracer forms them (rt_view_ray,
 * rt_nearest_primary, the point along the ray): 1 and the point in *at, its distance in *t, or 0
 * for a ray that misses the object (a corner's neighbour, by rounding); the ray's direction in
 * c->ray. */
static __attribute__((noinline)) int ss_hit_at(ss_ctx *c, int id, int x, int y, vec3 *at, real *t)
{
    const rt_view *v = c->view;
    c->ray = rt_view_ray(v, x, y);
#if RT_COMPILED_PROBE
    const rt_scene *s = c->scene;
    if (s->cull.plane_set >> id & 1 ? !rt_plane_primary(s, id, c->ray, t)
                                    : rt_nearest_primary(s, c->ray, (uint32_t)1 << id, t) != id)
        return 0; /* a plane: its test alone (rt_plane_primary), the same t */
#else
    if (rt_nearest_primary(c->scene, c->ray, (uint32_t)1 << id, t) != id)
        return 0;
#endif
    *at = v3_along_in(v->eye, c->ray, *t);
    return 1;
}

/* The cell (rt_sample.cell) of the checker of material m on plane `id` at pixel (x, y), where
 * its primary ray meets the plane (ss_hit_at), so the same cell as a full shade finds; 0 for a
 * ray that misses the plane. Counted in texture_pixels. */
static __attribute__((cold, noinline)) uint8_t ss_cell_at(ss_ctx *c, const rt_material *m, int id,
                                                          int x, int y)
{
    c->stats->texture_pixels++;
    vec3 at;
    real t;
    uint8_t cell = 0;
    if (ss_hit_at(c, id, x, y, &at, &t))
        rt_texture_color(m, at, 0, 0, c->stats, &cell);
    return cell;
}

int ss_cells_apart(ss_ctx *c, int id, int x0, int y0, int w, int h)
{
    const real scale = c->scene->materials[c->scene->objects[id].material].tex.scale;
    int32_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int n = 0; n < 4; n++) {
        vec3 at;
        real t;
        if (!ss_hit_at(c, id, x0 + (n & 1) * w, y0 + (n >> 1) * h, &at, &t))
            return 1;
        /* the cell's coordinates as rt_texture_color forms them */
        const int32_t q[3] = {r_mul_round_in(at.x, scale), r_mul_round_in(at.y, scale),
                              r_mul_round_in(at.z, scale)};
        for (int ax = 0; ax < 3; ax++) {
            lo[ax] = n && lo[ax] < q[ax] ? lo[ax] : q[ax];
            hi[ax] = n && hi[ax] > q[ax] ? hi[ax] : q[ax];
        }
    }
    return hi[0] - lo[0] > 3 || hi[1] - lo[1] > 3 || hi[2] - lo[2] > 3;
}

/* A square that rt_corners_differ would split for its primary object (RT_SPLIT_OBJECT), k[] its
 * corners (sm: its (0, 0) in the lattice): when the corners lie on one plane whose material is a
 * two-tone checker and differ only in their cells, the square is not split as long as the
 * corners agree for either tone: with each corner's cell made the same and its primary node's
 * contribution made its whole colour in that tone (its own colour, or rt_sample.alt for the
 * other tone), rt_corners_differ finds no difference (light states, ray tree, secondary
 * contributions, and those colours within the threshold). Shading is linear in the diffuse
 * colour, so each pixel then gets the bilinear interpolation (ss_fill) of the corners' colours
 * in the tone of its own cell, looked up where its primary ray meets the plane (ss_tone_at: a
 * ray and a plane test instead of a full shade). Returns 1 when it filled the pixels the square
 * owns (as ss_fill: `cols` x `rows`; points traced before keep their colour), 0 to split.
 * Out of line (off ss_square's path), compiled for speed on the board. */
__attribute__((noinline)) int ss_cells(ss_ctx *c, const rt_sample *sm, int x0, int y0, int w, int h,
                                       int own)
{
    const rt_scene *s = c->scene;
    const int id = sm->hits[0].object, cols = ss_cols(w, own), rows = ss_rows(h, own);
    if (id == RT_NO_OBJECT || !(s->cull.plane_set >> id & 1))
        return 0;
    /* tc[tone][corner]: the corners' colours in either tone, in [0, 1] */
    rt_color tc[2][4];
    rt_sample kk[4];
    const rt_sample *kp[4];
    for (int i = 0; i < 4; i++) {
        const rt_sample *q = sm + (i >> 1) * h * c->lstride + (i & 1) * w; /* corner i */
        if (q->alt_known != RT_ALT_TONE) /* its other tone's colour is known */
            return 0;
        int t = rt_cell_tone(q->cell);
        tc[t][i] = q->color;
        /* a byte b as the colour b / 255 (b 257 / 2^16 is within 2^-16 of it) */
        tc[!t][i] = v3(r_from_q16(q->alt[0] * 257), r_from_q16(q->alt[1] * 257),
                       r_from_q16(q->alt[2] * 257));
        kk[i] = *q;
        kk[i].cell = 1;
        kp[i] = &kk[i];
    }
    /* tone 0 into the frame, tone 1 aside (a split square's pixels are all written again by its
     * parts); each pixel then takes its own cell's */
    rt_px *dst = RT_PX(c->pixels, (long)(y0 - c->py0) * c->stride + x0);
    rt_px other[(RT_GRID_BUILD_MAX + 1) * (RT_GRID_BUILD_MAX + 1) * RT_PX_N];
    for (int t = 0; t < 2; t++) {
        const rt_color *kc[4];
        for (int i = 0; i < 4; i++) {
            uint32_t px = ss_pixel(&tc[t][i]);
            kk[i].hits[0].contrib[0] = (uint8_t)(px >> 16);
            kk[i].hits[0].contrib[1] = (uint8_t)(px >> 8);
            kk[i].hits[0].contrib[2] = (uint8_t)px;
            kc[i] = &tc[t][i];
        }
        if (rt_corners_differ(kp, c->thr8) != RT_SPLIT_NONE)
            return 0;
        ss_fill(t ? other : dst, t ? RT_GRID_BUILD_MAX + 1 : c->stride, w, h, cols, rows, kc);
    }
    /* Each pixel's cell, coarse to fine over the square's lattice (its pixels, and its right
     * column and bottom row for their neighbours): looked up at the points whose coordinates
     * are multiples of 4, then at the multiples of 2 and of 1 in turn only where the points a
     * step away on either side (left and right, above and below, or the four diagonal ones)
     * are not all in one cell. A cell is a convex square on the plane, and so is its image: a
     * point between two of its points lies in it. Cell ids repeat every four cells along each
     * axis: where the cells are so fine that two points with one id can lie in different cells
     * (ss_cells_apart), a cell is taken from its neighbours only at the steps the frame's
     * rt_view.cell_side allows, else looked up. Points traced before keep their colour and give
     * their cell. */
    const rt_material *m = &s->materials[s->objects[id].material];
    const int cs = RT_GRID_BUILD_MAX + 1;
    uint8_t cid[(RT_GRID_BUILD_MAX + 1) * (RT_GRID_BUILD_MAX + 1)];
    /* Where the cells are so fine that points 2 d apart can be in different cells of one id,
     * no cell is taken from the points a step d away: the largest such step (0: none) */
    int sure = 4;
    if (ss_cells_unsure(c, id, w, h) && ss_cells_apart(c, id, x0, y0, w, h))
        sure = c->view->cell_side[id] >> 1;
    for (int d = 4; d >= 1; d >>= 1)
        for (int j = 0; j <= h && (d > 1 || j < rows); j += d) {
            /* the row's points not done at a coarser step: every d-th, or (a row done at
             * the coarser step) the odd multiples of d; at step 1 only the square's own */
            const int dj = j & d & 3, fine = d < 4 && !dj; /* dj: d or 0 (step 4: 0) */
            const int mrow = j<rows, iend = d> 1 ? w : cols - 1;
            uint8_t *qrow = &cid[j * cs];
            const rt_sample *prow = sm + j * c->lstride;
            rt_px *drow = RT_PX(dst, (long)j * c->stride);
            const int step = d << fine;
            for (int i = fine ? d : 0; i <= iend; i += step) {
                const int mine = mrow && i < cols;
                uint8_t *q = &qrow[i];
                const rt_sample *pt = prow + i;
                if (pt->nhits) { /* a corner, or a point on the top or left edge */
                    *q = pt->hits[0].object == id ? pt->cell : 0;
                    if (mine)
                        rt_px_set(RT_PX(drow, i), ss_pixel(&pt->color));
                    continue;
                }
                int cell = 0;
                const int di = i & d; /* d or 0: the neighbours' offsets */
                if (d < 4 && d <= sure && i + di <= w && j + dj <= h) {
                    int a = q[-di - dj * cs], b = q[di + dj * cs];
                    if (di && dj && (q[di - dj * cs] != a || q[dj * cs - di] != a))
                        a = 0; /* the other diagonal */
                    cell = a == b ? a : 0;
                }
                if (!cell)
                    cell = ss_cell_at(c, m, id, x0 + i, y0 + j);
                *q = (uint8_t)cell;
                if (mine && cell && rt_cell_tone((uint8_t)cell))
                    rt_px_set(RT_PX(drow, i), rt_px_get(RT_PX(other, j * cs + i)));
            }
        }
    return 1;
}

/* A square that rt_corners_differ would split for a contribution (RT_SPLIT_CONTRIB: one object,
 * the same light states and ray tree), k[] its corners (sm: its (0, 0) in the lattice): when
 * every corner lies on a noise texture with its A and B kept (rt_sample.alt_known RT_ALT_NOISE: no
 * secondary ray) and they agree within the threshold on the part of their colour the texture
 * does not change, t A + B for one texture colour t (the corners' mean, sum (C - B) / sum A
 * clamped to [0, 1]; in bytes, multiplied out by sum A), the square is not split for the
 * texture's colour: each pixel gets b x A + B, A and B interpolated bilinearly from the corners'
 * (ss_fill, as bytes: A / 2 and B are within [0, 1]: A <= RT_NOISE_A_MAX) and b the texture at
 * the pixel's own hit (ss_hit_at: a ray and the object's test, no shading; the tracer's octave
 * rule). Returns 1 when it filled the pixels the square owns (as ss_fill:
 * `cols` x `rows`; points traced before keep their colour), 0 to split (also when a pixel's ray
 * misses the object: the split writes every pixel again). In integers: A in Q15 (byte x 257,
 * below 2), b and B in Q16.16, b x A below 2^32; the criterion's terms below 2^20. 1.2 kB of
 * stack, less than the nested shading it replaces. */
__attribute__((noinline)) int ss_noise(ss_ctx *c, const rt_sample *sm, const rt_sample *const k[4],
                                       int x0, int y0, int w, int h, int own)
{
    /* ab[corner]: A / 2 and B as colours (a byte b as b 257 / 2^16, within 2^-16 of b / 255) */
    rt_color ab[2][4];
    const rt_color *ka[4], *kb[4];
    int32_t num[3] = {0, 0, 0}, den[3] = {0, 0, 0};
    for (int i = 0; i < 4; i++) {
        const rt_sample *p = k[i];
        const uint8_t *a = p->alt, *b = p->hits[1].contrib;
        if (p->alt_known != RT_ALT_NOISE)
            return 0;
        const uint32_t px = ss_pixel(&p->color);
        for (int ch = 0; ch < 3; ch++) {
            num[ch] += (int32_t)(px >> (16 - 8 * ch) & 255) - b[ch];
            den[ch] += 2 * a[ch];
        }
        ab[0][i] = v3(r_from_q16(a[0] * 257), r_from_q16(a[1] * 257), r_from_q16(a[2] * 257));
        ab[1][i] = v3(r_from_q16(b[0] * 257), r_from_q16(b[1] * 257), r_from_q16(b[2] * 257));
        ka[i] = &ab[0][i];
        kb[i] = &ab[1][i];
    }
    for (int ch = 0; ch < 3; ch++) { /* d (t A + B) = n 2 A + d B with t = n / d */
        const int32_t d = den[ch] > 0 ? den[ch] : 1;
        int32_t n = num[ch] > 0 ? num[ch] : 0, lo = 1 << 30, hi = -lo;
        n = n < d ? n : d;
        for (int i = 0; i < 4; i++) {
            const int32_t v = 2 * n * k[i]->alt[ch] + d * k[i]->hits[1].contrib[ch];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        if (hi - lo > c->thr8 * d)
            return 0;
    }
    /* A / 2 aside and B into the frame, as ss_fill interpolates colours, as bytes; each pixel
     * then gets b x A + B from them */
    const int id = sm->hits[0].object, cols = ss_cols(w, own), rows = ss_rows(h, own),
              cs = RT_GRID_BUILD_MAX + 1;
    const rt_material *m = &c->scene->materials[c->scene->objects[id].material];
    const rt_params *p = c->params;
    const real tmax = r_muli(R_SCENE_MAX, 2);
    rt_px *dst = RT_PX(c->pixels, (long)(y0 - c->py0) * c->stride + x0);
    rt_px half_a[(RT_GRID_BUILD_MAX + 1) * (RT_GRID_BUILD_MAX + 1) * RT_PX_N];
    ss_fill(half_a, cs, w, h, cols, rows, ka);
    ss_fill(dst, c->stride, w, h, cols, rows, kb);
    for (int j = 0; j < rows; j++, dst = RT_PX(dst, c->stride))
        for (int i = 0; i < cols; i++) {
            const rt_sample *pt = sm + j * c->lstride + i;
            vec3 at;
            real t;
            if (pt->nhits) { /* a corner, or a point a neighbour traced */
                rt_px_set(RT_PX(dst, i), ss_pixel(&pt->color));
                continue;
            }
            c->stats->noise_pixels++;
            if (!ss_hit_at(c, id, x0 + i, y0 + j, &at, &t))
                return 0; /* a miss, by rounding */
            /* the texture as trace_ray finds it: its octaves, and with the footprint the view's
             * pixel times the distance, capped as trace_ray caps a path */
            const real fp = p->footprint ? r_mul(c->view->pixel, t < tmax ? t : tmax) : 0;
            uint8_t cell;
            const rt_color b = rt_texture_color(m, at, p->octaves, fp, c->stats, &cell);
            const uint32_t bq[3] = {(uint32_t)r_unit_to_q16(b.x), (uint32_t)r_unit_to_q16(b.y),
                                    (uint32_t)r_unit_to_q16(b.z)};
            const uint32_t ha = rt_px_get(RT_PX(half_a, j * cs + i)), bb = rt_px_get(RT_PX(dst, i));
            uint32_t px = 0;
            for (int ch = 0, sh = 16; ch < 3; ch++, sh -= 8) {
                /* b (Q16.16) x A (Q15: 2 byte / 255 as byte x 257) + B (Q16.16) */
                const int32_t v = (int32_t)((bq[ch] * ((ha >> sh & 255) * 257) + 0x4000u) >> 15) +
                    (int32_t)(bb >> sh & 255) * 257;
                px |= (uint32_t)SS_V(v < 65536 ? v : 65536) >> 16 << sh;
            }
            rt_px_set(RT_PX(dst, i), px);
        }
    return 1;
}

/* Shadow pixels: the largest square side filled so (ss_shadow; measured on the board: larger
 * squares cost more per pixel tested than their split). */
#define SS_SHADOW_MAX 4

/* Light i at pixel (x, y)'s primary hit on sm's primary object, a plane, found and formed as
 * trace_ray forms it (ss_hit_at; the plane's normal, d . n, the point lifted off the surface;
 * the diffuse colour, the material's or its checker's in sm's cell), seen by trace_light
 * (rt_light_term): with term
 * NULL its state as the pixel's full shade decides it, else its state and its term where nothing
 * would occlude it, in *term; -1 for a ray that misses the object or meets it from behind (where
 * trace_ray turns the normal). */
static __attribute__((noinline)) int ss_light(ss_ctx *c, const rt_sample *sm, int i, int x, int y,
                                              rt_color *term)
{
    const int id = sm->hits[0].object, cell = sm->cell;
    const rt_scene *s = c->scene;
    const rt_object *o = &s->objects[id];
    rt_hit h;
    real t;
    if (!ss_hit_at(c, id, x, y, &h.p, &t))
        return -1;
    h.d = c->ray;
    h.n = o->normal; /* a plane's (rt_shapes' plane normal) */
    h.dn = d3_dot(h.d, h.n);
    if (h.dn > 0)
        return -1;
    h.m = &s->materials[o->material];
    h.id = id;
    h.inside = 0;
    h.p_out = v3_along_in(h.p, h.n, R_EPS_OFFSET);
    h.base = cell && rt_cell_tone((uint8_t)cell) ? h.m->tex.color2 : h.m->diffuse;
    return rt_light_term(s, c->stats, &h, i, term);
}

/* Do colours k[0..3] (in [0, 1]) differ by more than lim (Q16.16) in some channel? */
static int ss_spread(const rt_color *const k[4], int32_t lim)
{
    for (int ch = 0; ch < 3; ch++) {
        int32_t lo = 65536, hi = 0;
        for (int n = 0; n < 4; n++) {
            const int32_t v = r_unit_to_q16(ch == 0 ? k[n]->x : ch == 1 ? k[n]->y : k[n]->z);
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        if (hi - lo > lim)
            return 1;
    }
    return 0;
}

/* A square of at most SS_SHADOW_MAX a side, not on the frame's last row or column, that
 * rt_corners_differ splits for its lights (RT_SPLIT_LIGHT), k[] its corners (k[0]: its (0, 0) in
 * the lattice): when the corners lie on a plane and differ only in light i, lit at some and
 * unlit at others, with no highlight at any corner, each corner's colour is C = D + s T: s 1
 * where light i lights it, T the light's term there as trace_light would add it if nothing
 * occluded the light (ss_light:
 * the corner's primary hit again, trace_light's Lambert and Phong terms, no shadow ray), D its
 * colour without it. Each corner gets its colour unlit, D, and lit, L = D + T: its own colour
 * for its own state, C - T or C + T in the other, within [0, 1] (a lit corner clamped at 1 gives
 * a D darker than its own: the range test below sees most of that). Where D and L each agree
 * within the threshold over the corners (as an unsplit square's contributions do;
 * rt_corners_differ found the same ray tree at every corner) and the light faces every corner,
 * the square is not split: D and L are interpolated as colours are (ss_fill: D into the frame,
 * L aside), and each pixel takes D or L as light i lights its own primary hit or not, decided
 * as its full shade decides it (ss_light: its ray, the object's test, trace_light with its
 * shadow ray). Returns 1 when it filled the w x h pixels the square owns (points traced before
 * keep their colour), 0 to split (also when a pixel's ray misses the object). Not on a noise
 * texture (its colour is not the corners' in between: ss_noise's) nor where the view's eye is
 * not the prepared one (ss_hit_at). Not on a sphere either: a sphere's lit and unlit corners
 * are nearly always either side of its terminator, where the light stops facing it, so nearly
 * every try there fails at the corners' terms (docs/tracer.md). 64 bytes of stack for the lit
 * colours. */
__attribute__((noinline)) int ss_shadow(ss_ctx *c, const rt_sample *const k[4], int x0, int y0,
                                        int w, int h)
{
    const rt_sample *sm = k[0];
    const unsigned l0 = k[0]->lights,
                   diff = (l0 ^ k[1]->lights) | (l0 ^ k[2]->lights) | (l0 ^ k[3]->lights);
    const int li = diff ? __builtin_ctz(diff) >> 1 : 0; /* the light that differs */
    /* exactly one light differs (one bit: lit or not), no highlight at any corner (at corner 0,
     * or where the bit that differs is a highlight's); rt_nearest_primary needs the prepared eye */
    const int id = sm->hits[0].object;
    const rt_material *m = &c->scene->materials[c->scene->objects[id].material];
    if (w > SS_SHADOW_MAX || diff != 1u << (2 * li) || (l0 & RT_LIGHTS_HIGHLIGHT) ||
        (m->tex.active && !sm->cell) || !(c->scene->cull.plane_set >> id & 1) ||
        !rt_scene_at_eye(c->scene, c->view->eye))
        return 0;
    rt_color dl[2][4]; /* D and L */
    const rt_color *kd[2][4];
    for (int n = 0; n < 4; n++) {
        const int lit = rt_light_state(k[n], li);
        rt_color t;
        if (ss_light(c, sm, li, x0 + (n & 1) * w, y0 + (n >> 1) * h, &t) != 1)
            return 0; /* a miss, a highlight, or a corner the light does not face */
        const int32_t cq[3] = {r_unit_to_q16(k[n]->color.x), r_unit_to_q16(k[n]->color.y),
                               r_unit_to_q16(k[n]->color.z)},
                      tq[3] = {r_unit_to_q16(t.x), r_unit_to_q16(t.y), r_unit_to_q16(t.z)};
        int32_t d[3], l[3];
        for (int ch = 0; ch < 3; ch++) {
            d[ch] = !lit ? cq[ch] : cq[ch] > tq[ch] ? cq[ch] - tq[ch] : 0;
            l[ch] = lit ? cq[ch] : cq[ch] < 65536 - tq[ch] ? cq[ch] + tq[ch] : 65536;
        }
        dl[0][n] = v3(r_from_q16(d[0]), r_from_q16(d[1]), r_from_q16(d[2]));
        dl[1][n] = v3(r_from_q16(l[0]), r_from_q16(l[1]), r_from_q16(l[2]));
        kd[0][n] = &dl[0][n];
        kd[1][n] = &dl[1][n];
    }
    /* D and L each within the threshold over the corners (a byte is 257 in Q16.16) */
    for (int j = 0; j < 2; j++)
        if (ss_spread(kd[j], c->thr8 * 257))
            return 0;
    const int cs = SS_SHADOW_MAX;
    rt_px *dst = RT_PX(c->pixels, (long)(y0 - c->py0) * c->stride + x0);
    rt_px lit_px[SS_SHADOW_MAX * SS_SHADOW_MAX * RT_PX_N];
    ss_fill(dst, c->stride, w, h, w, h, kd[0]);
    ss_fill(lit_px, cs, w, h, w, h, kd[1]);
    for (int j = 0; j < h; j++, dst = RT_PX(dst, c->stride))
        for (int i = 0; i < w; i++) {
            const rt_sample *pt = sm + j * c->lstride + i;
            if (pt->nhits) { /* a corner, or a point a neighbour traced */
                rt_px_set(RT_PX(dst, i), ss_pixel(&pt->color));
                continue;
            }
            c->stats->shadow_pixels++;
            const int lit = ss_light(c, sm, li, x0 + i, y0 + j, NULL);
            if (lit < 0)
                return 0; /* a miss, by rounding */
            if (lit)
                rt_px_set(RT_PX(dst, i), rt_px_get(RT_PX(lit_px, j * cs + i)));
        }
    return 1;
}

/* A 2x2 square that does not end the frame, split by rt_corners_differ for a contribution
 * (RT_SPLIT_CONTRIB: one object and cell, the same light states and ray tree), k[] its corners
 * (sm: its (0, 0) in the lattice): the centre test. Traces its centre, one of the five points
 * the split traces (as ss_quad traces it), and when rt_centre_smooth finds it of the corners'
 * shape with every contribution within half the threshold of both diagonals' means, the colour
 * varies smoothly there: fills the square's four pixels from its corners (ss_fill), the centre
 * and the points a neighbour traced (the middles of its top and left edges) showing their
 * traced colour as the fill shows a corner, takes the centre's record out of the lattice
 * (which holds nothing inside a square that is not split) and returns 1. Else 0: split (the
 * centre is kept for it). Half the threshold: where an edge cuts one corner off (the fill would
 * smear it over the edges' middles), that corner's step, more than the threshold (the split's
 * own reason), puts the centre more than half of it off that diagonal's mean, on either side of
 * the edge, so such a square always splits. Out of line and cold (for size). */
__attribute__((cold, noinline)) int ss_centre(ss_ctx *c, rt_sample *sm, const rt_sample *const k[4],
                                              int x0, int y0)
{
    const int ls = c->lstride, stride = c->stride;
    rt_sample *mid = sm + ls + 1;
    /* as ss_quad traces it; a split for a contribution: its points are shaded in full */
    ss_need(c, c->quad, NULL, x0 + 1, y0 + 1, mid);
    c->stats->centre_tests++;
    if (!rt_centre_smooth(k, mid, c->thr8 / 2))
        return 0;
    c->stats->contrib_kept++;
    rt_px *dst = RT_PX(c->pixels, (long)(y0 - c->py0) * stride + x0);
    const rt_color *const kc[4] = {&k[0]->color, &k[1]->color, &k[2]->color, &k[3]->color};
    ss_fill(dst, stride, 2, 2, 2, 2, kc);
    rt_px_set(RT_PX(dst, stride + 1), ss_pixel(&mid->color));
    if (sm[1].nhits)
        rt_px_set(RT_PX(dst, 1), ss_pixel(&sm[1].color));
    if (sm[ls].nhits)
        rt_px_set(RT_PX(dst, stride), ss_pixel(&sm[ls].color));
    mid->nhits = 0;
    return 1;
}
