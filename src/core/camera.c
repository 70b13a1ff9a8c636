/* camera.c: the camera: the look-at frame and the primary ray through each pixel. */
#include "rt_local.h"

int rt_view_ok(const rt_camera *cam)
{
    return cam->eye.x != cam->at.x || cam->eye.y != cam->at.y || cam->eye.z != cam->at.z;
}

void rt_view_init(rt_view *v, const rt_camera *cam, int width, int height)
{
    v->eye = cam->eye;
    v->width = width;
    v->height = height;
    /* Keys keep eye and at apart and up non-zero, but animated tracks can cross between keys:
     * for that instant the camera looks down -z, and a zero up is parallel to anything. */
    vec3 view = v3_sub(cam->at, cam->eye);
    v->fwd = (dir3){0, 0, u_neg(U_ONE)};
    if (!v3_is_zero(view))
        v->fwd = d3_norm(view, 0);
    /* An up vector that is zero, or (nearly) parallel to the view, is replaced by another axis.
     * Tested on the cosine before crossing, so that no zero cross product is normalised: the
     * sine is below 2^-10 exactly when the squared cosine is above 1 - 2^-20 (exact in both
     * builds, so that both take the same branch; rt-fixed16, whose unit steps are 2^-16, uses
     * 1 - 2^-16, a sine below 2^-8: U_COS2_PARALLEL). */
    int up_zero = v3_is_zero(cam->up);
    dir3 up = up_zero ? v->fwd : d3_norm(cam->up, 0);
    unit c = d3_dot(v->fwd, up);
    if (up_zero || u_mul(c, c) > U_COS2_PARALLEL) {
        dir3 alt = {0, 0, U_ONE};
        if (v->fwd.z > U(0.5) || v->fwd.z < U(-0.5))
            alt = (dir3){U_ONE, 0, 0};
        v->right = d3_cross(v->fwd, alt, 0);
    } else {
        v->right = d3_cross(v->fwd, up, 0);
    }
    v->up = d3_cross(v->right, v->fwd, 0);
    unit sn, cs;
    u_sincos_deg(r_shr(cam->fov, 1), &sn, &cs);
    v->step = u_tan_step(sn, cs, height); /* tan(fov / 2) / height */
    v->pixel = r_div(r_muli(u_to_real(sn), 2), r_muli(u_to_real(cs), height));
    v->tan_half = r_div(u_to_real(sn), u_to_real(cs));
    /* the smallest tiles (powers of two, 4 pixels or more) that fit RT_VIEW_TILES a side */
    int k = 2;
    while (((width - 1) >> k) >= RT_VIEW_TILES || ((height - 1) >> k) >= RT_VIEW_TILES)
        k++;
    v->cull_shift = k;
    v->mirror_plane = -1;
    v->small = 0;
    for (int i = 0; i < RT_VIEW_TILES; i++)
        v->cull_cols[i] = v->cull_rows[i] = v->mirror_cols[i] = v->mirror_rows[i] = 0xFFFFFFFFu;
    for (int i = 0; i < RT_MAX_OBJECTS; i++)
        v->cell_side[i] = 255;
    v->pool = 0;
}

/* Once per frame: compiled for size (cold), off the image's hot path. */
#define VIEW_ONCE __attribute__((cold, noinline))

/* Clears `bit` in the tiles of one axis of the view's sets `cols`/`rows` (axis 0: cols, along
 * right; 1: rows, along -up, so that pixel y has ib = 2y + 1 - h as x has ia = 2x + 1 - w) where no
 * direction within the cone of sine sn around the unit vector l lies, given c = l . (right or
 * -up), z = l . fwd and zz = z^2 - sn^2 >= 1/4.
 *
 * A direction within the cone passes within sn of l, and projected on the plane of the axis
 * and fwd (which shortens distances), the line through the eye along (a, 1) passes within sn
 * of (c, z): (a z - c)^2 <= sn^2 (1 + a^2), so a lies between the roots
 * (c z -+ sn sqrt(c^2 + zz)) / zz. Formed in reals, each root is within 2^-12 + |a| 2^-15
 * (units in Q2.30 or Q16.16, zz >= 1/4 to divide by); the range is widened by
 * 2^-10 + |a| 2^-10, which also covers tan_half's rounding and the rays' own directions (within
 * 2^-15 of their pixel's in either build). Pixel x lies at a = (2x + 1 - w) tan_half / h: the
 * pixels of the range, and one more either side, are kept; the first and last of them go into
 * range[0] and range[1] (range[1] < range[0]: none in the frame). */
VIEW_ONCE static void view_keep(rt_view *v, uint32_t *cols, uint32_t *rows, int axis, unit c,
                                unit z, unit sn, unit zz, uint32_t bit, int16_t range[2])
{
    int n = axis ? v->height : v->width, h = v->height, k = v->cull_shift;
    uint32_t *set = axis ? rows : cols;
    real root = r_sqrt(u_to_real(u_add(u_mul(c, c), zz)));
    real mid = u_to_real(u_mul(c, z)), half = r_mul(u_to_real(sn), root), den = u_to_real(zz);
    real lim = r_add(r_from_ratio(n, h), R(2.0)); /* beyond the image by a height at least */
    int32_t px[2];
    for (int e = 0; e < 2; e++) {
        real a = r_div(e ? r_add(mid, half) : r_sub(mid, half), den);
        real m = r_add(R(0.0009765625), r_shr(r_abs(a), 10));
        a = r_clamp(r_div(e ? r_add(a, m) : r_sub(a, m), v->tan_half), r_neg(lim), lim);
        /* ia = a h in half pixels, rounded outward: floor for the low end, ceil for the high */
        int32_t ia;
        r_floor_split(e ? r_neg(r_muli(a, h)) : r_muli(a, h), &ia);
        px[e] = e ? ((n - ia) >> 1) + 1 : ((ia + n - 1) >> 1) - 1;
    }
    int lo = px[0] < 0 ? 0 : px[0], hi = px[1] >= n ? n - 1 : px[1];
    range[0] = (int16_t)lo;
    range[1] = (int16_t)hi;
    for (int i = 0; i <= (n - 1) >> k; i++)
        if (hi < lo || i < (lo >> k) || i > (hi >> k))
            set[i] &= ~bit;
}

/* Leaves `bit` out of the tiles of the sets `cols`/`rows` where no primary ray's direction lies
 * within the cone of sine `cone` around the direction of `axis` (from the eye), unless the cone
 * reaches 60 degrees off the view. Returns 1 and the pixels the cone covers, box[0..3] = x0, y0,
 * x1, y1 (inclusive; x1 < x0 or y1 < y0: none), where it bounds them, else 0. */
VIEW_ONCE static int view_cone(rt_view *v, uint32_t *cols, uint32_t *rows, vec3 axis, real cone,
                               uint32_t bit, int16_t box[4])
{
    dir3 l = d3_norm(axis, 0);
    unit z = d3_dot(l, v->fwd), sn = u_from_real(cone);
    unit zz = u_add(u_mul(z, z), u_neg(u_mul(sn, sn)));
    if (z <= 0 || zz < U(0.25))
        return 0; /* the cone reaches 60 degrees off the view: no bound */
    int16_t range[2][2];
    for (int a = 0; a < 2; a++)
        view_keep(v, cols, rows, a, d3_dot(l, a ? d3_neg(v->up) : v->right), z, sn, zz, bit,
                  range[a]);
    box[0] = range[0][0];
    box[1] = range[1][0];
    box[2] = range[0][1];
    box[3] = range[1][1];
    return 1;
}

/* rt_view.cell_side of plane i, whose material has a two-tone checker of `scale` cells per unit.
 * A cell id holds the cell's coordinates modulo 4: two points with one id lie in one cell when
 * their coordinates (q = p scale along each axis) differ by less than 3 cells. Along a primary
 * ray r = fwd + a right + b up (a = (2x + 1 - w) pixel / 2, b = (h - 2y - 1) pixel / 2) the
 * plane is met at p = eye + h r / g, with h = eye_num (offset - eye . n) and g = n . r, and
 * dp / dx = pixel h (right g - r (n . right)) / g^2 (dp / dy alike with -up): g and the
 * numerators are linear in x and y, so over the frame |g| is least, and each numerator largest,
 * at a corner of it. A square of side w thus spans at most w scale |h| pixel N / gmin^2 cells
 * along any axis (N: the largest |numerator| along x plus along y, over the axes): the side
 * returned is the largest power of two, up to 128, that keeps this below 2.5 (a margin for
 * rounding), 0 where even one pixel does not or the horizon crosses the frame (g takes both
 * signs), 255 where the frame does not see the plane. Bounds that would not fit a real give 0. */
VIEW_ONCE static int view_cell_side(const rt_view *v, const rt_scene *s, int i, real scale)
{
    const dir3 n = s->objects[i].normal;
    const real h = s->cull.eye_num[i], nr = u_to_real(d3_dot(n, v->right)),
               nu = u_to_real(d3_dot(n, v->up)), nf = u_to_real(d3_dot(n, v->fwd));
    if (h == 0)
        return 255; /* the eye on the plane: seen edge on */
    if (v->pixel > R(1.0))
        return 0;
    const real rv[3] = {u_to_real(v->fwd.x), u_to_real(v->fwd.y), u_to_real(v->fwd.z)},
               ri[3] = {u_to_real(v->right.x), u_to_real(v->right.y), u_to_real(v->right.z)},
               up[3] = {u_to_real(v->up.x), u_to_real(v->up.y), u_to_real(v->up.z)};
    real gmin = R(1024.0), nx[3] = {0, 0, 0}, ny[3] = {0, 0, 0};
    int seen = 0;
    for (int k = 0; k < 4; k++) {
        const int x = (k & 1) * (v->width - 1), y = (k >> 1) * (v->height - 1);
        const real a = r_shr(r_muli(v->pixel, 2 * x + 1 - v->width), 1),
                   b = r_shr(r_muli(v->pixel, v->height - 2 * y - 1), 1);
        const real g = r_add(nf, r_add(r_mul(a, nr), r_mul(b, nu)));
        if ((g > 0) == (h > 0) && g != 0)
            seen |= 1 << k;
        gmin = r_min(gmin, r_abs(g));
        for (int ax = 0; ax < 3; ax++) {
            const real r = r_add(rv[ax], r_add(r_mul(a, ri[ax]), r_mul(b, up[ax])));
            nx[ax] = r_max(nx[ax], r_abs(r_sub(r_mul(ri[ax], g), r_mul(r, nr))));
            ny[ax] = r_max(ny[ax], r_abs(r_sub(r_mul(up[ax], g), r_mul(r, nu))));
        }
    }
    if (!seen)
        return 255;
    if (seen != 15)
        return 0; /* the horizon in the frame */
    real nmax = 0;
    for (int ax = 0; ax < 3; ax++)
        nmax = r_max(nmax, r_add(nx[ax], ny[ax]));
    const real ah = r_abs(h);
    if (nmax > R(1024.0) || w_mul(scale, ah) > w_mul(R(30000.0), R(1.0)))
        return 0;
    /* the cells a side of w spans, w lw, against 2.5 gmin^2 */
    wide lw = w_mul(r_mul(v->pixel, nmax), r_mul(scale, ah));
    const wide lim = w_mul(r_mul(R(2.5), gmin), gmin);
    int side = 0;
    while (side < 128 && lw < lim) {
        side = side ? 2 * side : 1;
        lw = w_add(lw, lw);
    }
    return side;
}

/* The pixel coordinates (Q16.16, as reals) of point p in *px and *py: 1, or 0 for a point not
 * well in front of the eye. Within 4096 pixels of the frame's centre (clamped). */
VIEW_ONCE static int view_project(const rt_view *v, vec3 p, real *px, real *py)
{
    const vec3 d = v3_sub(p, v->eye);
    const real z = v3_dot_d(d, v->fwd), lim = r_muli(v->pixel, 4096);
    if (z < R(0.0009765625))
        return 0;
    /* 2x + 1 - w = 2 a / pixel, with a = (d . right) / z; y alike with up, downwards */
    real a = r_clamp(r_div(v3_dot_d(d, v->right), z), r_neg(lim), lim),
         b = r_clamp(r_div(v3_dot_d(d, v->up), z), r_neg(lim), lim);
    *px = r_add(r_div(a, v->pixel), r_from_ratio(v->width - 1, 2));
    *py = r_sub(r_from_ratio(v->height - 1, 2), r_div(b, v->pixel));
    return 1;
}

/* Light i over plane j (rt_view.pool): a light at height hl over a plane lights it, under it,
 * with n . l = hl / sqrt(hl^2 + rho^2) at distance rho from its foot, a peak that falls to a
 * quarter at rho = 4 hl: the disc of that radius, its image bounded by the images of the four
 * ends of two diameters (padded by 2 pixels). Seen at a grazing angle it is thinner than a
 * square, and corners on either side of it miss its peak: kept where the box is less than 16
 * pixels high or wide and the light and the eye are on the same side of the plane. */
VIEW_ONCE static void view_pool(rt_view *v, const rt_scene *s, int i, int j)
{
    const rt_object *o = &s->objects[j];
    const vec3 l = s->lights[i].pos;
    const real hl = r_sub(v3_dot_d(l, o->normal), o->offset);
    if (v->pool >> i & 1 || hl == 0 || (hl > 0) != (s->cull.eye_num[j] < 0) ||
        r_abs(hl) > R(1024.0))
        return;
    const dir3 n = o->normal;
    const dir3 ax = n.x > U(0.5) || n.x < U(-0.5) ? (dir3){0, U_ONE, 0} : (dir3){U_ONE, 0, 0};
    const dir3 u = d3_cross(n, ax, 0), w = d3_cross(n, u, 0);
    const vec3 foot = v3_along(l, n, r_neg(hl));
    const real r = r_muli(r_abs(hl), 4);
    real x0 = R(32767.0), y0 = R(32767.0), x1 = r_neg(x0), y1 = r_neg(y0);
    for (int k = 0; k < 4; k++) {
        real px, py;
        if (!view_project(v, v3_along(foot, k < 2 ? u : w, k & 1 ? r : r_neg(r)), &px, &py))
            return;
        x0 = r_min(x0, px);
        x1 = r_max(x1, px);
        y0 = r_min(y0, py);
        y1 = r_max(y1, py);
    }
    int32_t b[4];
    r_floor_split(r_sub(x0, R(2.0)), &b[0]);
    r_floor_split(r_sub(y0, R(2.0)), &b[1]);
    r_floor_split(r_add(x1, R(3.0)), &b[2]);
    r_floor_split(r_add(y1, R(3.0)), &b[3]);
    if ((b[2] - b[0] >= 16 && b[3] - b[1] >= 16) || b[2] < 0 || b[3] < 0 || b[0] >= v->width ||
        b[1] >= v->height)
        return;
    v->pool |= 1u << i;
    v->pool_plane[i] = (uint8_t)j;
    v->pool_box[i][0] = (int16_t)(b[0] < 0 ? 0 : b[0]);
    v->pool_box[i][1] = (int16_t)(b[1] < 0 ? 0 : b[1]);
    v->pool_box[i][2] = (int16_t)(b[2] >= v->width ? v->width - 1 : b[2]);
    v->pool_box[i][3] = (int16_t)(b[3] >= v->height ? v->height - 1 : b[3]);
}

VIEW_ONCE void rt_view_cull(rt_view *v, const rt_scene *s)
{
    v->mirror_plane = -1;
    v->small = 0;
    for (int i = 0; i < RT_VIEW_TILES; i++)
        v->cull_cols[i] = v->cull_rows[i] = v->mirror_cols[i] = v->mirror_rows[i] = 0xFFFFFFFFu;
    for (int i = 0; i < RT_MAX_OBJECTS; i++)
        v->cell_side[i] = 255;
    v->pool = 0;
    if (!rt_scene_at_eye(s, v->eye))
        return; /* rt_nearest_primary does not serve this view */
    for (int i = 0; i < s->nlights && RT_FINE_DETAIL; i++)
        for (int j = 0; j < s->nobjects; j++)
            if (s->objects[j].kind == RT_PLANE)
                view_pool(v, s, i, j);
    for (int i = 0; i < s->nobjects; i++) {
        const rt_texture *tx = &s->materials[s->objects[i].material].tex;
        if (RT_FINE_DETAIL && s->objects[i].kind == RT_PLANE && tx->active &&
            tx->kind == RT_TEX_CHECKER)
            v->cell_side[i] = (uint8_t)view_cell_side(v, s, i, tx->scale);
    }
    for (int i = 0; i < s->nobjects; i++) {
        real cone = s->cull.eye_cone[i];
        if (s->objects[i].kind != RT_SPHERE || cone <= 0 || s->cull.eye_cull[i] <= 0)
            continue;
        int16_t *b = v->box[i]; /* the sphere's pixels: small when both sides are short */
        if (view_cone(v, v->cull_cols, v->cull_rows, s->cull.eye_l[i], cone, (uint32_t)1 << i, b) &&
            b[0] <= b[2] && b[1] <= b[3] && b[2] - b[0] < RT_SMALL_MAX &&
            b[3] - b[1] < RT_SMALL_MAX)
            v->small |= (uint32_t)1 << i;
    }
    /* The reflections off the frame's mirror: each sphere's mirror cone (rt_scene_mirror_cone)
     * is the set of primary directions whose reflected ray can hit it; a plane stays in every
     * tile. */
    int pl = rt_scene_mirror(s);
    v->mirror_plane = pl;
    if (pl < 0)
        return;
    for (int i = 0; i < s->nobjects; i++) {
        vec3 l;
        real cone = rt_scene_mirror_cone(s, pl, i, &l);
        int16_t box[4]; /* not kept: small spheres are looked for among primary hits */
        if (cone > 0)
            view_cone(v, v->mirror_cols, v->mirror_rows, l, cone, (uint32_t)1 << i, box);
    }
}
