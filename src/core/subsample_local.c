/* subsample_local.c: the local parts (ambient and light terms) of the points a split adds, interpolated from the square's corners where they allow. */
#include "subsample.h"

/* The local part of point (x, y) of the square a (rt_local), a point its split adds: its
 * corners' primary object, cell and light states, and their node-0 contributions interpolated
 * bilinearly at the point. It lies at 0, half or the whole of each side (ss_local_ok), so its
 * weights are equal over the corners they do not leave out (1, 2 or 4), and each channel is
 * their mean. In integers, the same in both builds: a byte b as b 257 / 2^16 in Q16.16 (within
 * 2^-16 of b / 255), a sum of 4 bytes times 257 (below 2^19) divided by 4, rounded. No other
 * tone is kept (RT_ALT_NONE): such points are hardly ever the corners of a texture square
 * (intro frames 0..1200 step 100: 3,200 texture squares instead of 3,207 with the other tone
 * interpolated too, for about 330 bytes more of the board's code). Out of line and cold: off
 * the usual path. */
__attribute__((cold, noinline)) const rt_local *ss_local(ss_ctx *c, const ss_area *a, int x, int y)
{
    rt_local *loc = &c->loc;
    const rt_sample *const *k = a->k;
    const int i = x - a->x0, j = y - a->y0;
    /* the columns ca..cb and rows ra..rb of the corners its weights keep; the four terms
     * p0..p3 repeat a corner once over for each side it is at the end of: their sum is 4 times
     * the mean */
    const int cb = i != 0, ca = cb && i == a->w, rb = j != 0, ra = rb && j == a->h;
    const uint8_t *p0 = k[2 * ra + ca]->hits[0].contrib, *p1 = k[2 * ra + cb]->hits[0].contrib,
                  *p2 = k[2 * rb + ca]->hits[0].contrib, *p3 = k[2 * rb + cb]->hits[0].contrib;
    int32_t q[3];
    for (int n = 0; n < 3; n++)
        q[n] = ((p0[n] + p1[n] + p2[n] + p3[n]) * 257 + 2) >> 2;
    loc->col = v3(r_from_q16(q[0]), r_from_q16(q[1]), r_from_q16(q[2]));
    loc->id = k[0]->hits[0].object;
    loc->cell = k[0]->cell;
    loc->lights = k[0]->lights;
    return loc;
}

/* The largest side of a square whose split's points take their local parts from its corners
 * (ss_local_ok). A point that takes its local part takes the corners' light states too, so no
 * square inside the split can see a highlight the corners do not: on a top-level square (8) a
 * highlight between its corners on a glossy mirror or glass sphere was lost whole (intro frame
 * 1012: 193 levels off, where the split had found it). At 4 the points are as close to a shaded
 * corner as in the squares adaptive mode leaves unsplit, whose colours are interpolated the
 * same way: frames 787, 1012, 1037 and 1100 then have the worst pixel they had before the local
 * parts (against --mode full --min-contrib 0; over8 the same or one more, PSNR 0.01 to 0.04 dB
 * lower), keeping about 90% of the local points there. */
#define SS_LOCAL_MAX 4

/* Adaptive and probe mode, a square split for its secondary rays (RT_SPLIT_SECONDARY: one
 * primary object and cell), k[] its corners, w x h its size: 1 when the local parts of the
 * points its split adds can be interpolated from the corners' (ss_local), as an unsplit square's
 * colours would be: its sides are at most SS_LOCAL_MAX, the corners agree on every light's state,
 * with no highlight (its peak can lie between them), their primary object has no noise texture,
 * the sides are 0 or powers of two (every square but some that end the frame: the points then
 * lie at 0, half or the whole of each side), and their node-0 contributions lie within the
 * threshold in every channel. Cold: off the usual path. */
__attribute__((cold, noinline)) int ss_local_ok(const ss_ctx *c, const rt_sample *const k[4], int w,
                                                int h)
{
    const unsigned id = k[0]->hits[0].object, lights = k[0]->lights;
    if (w > SS_LOCAL_MAX || h > SS_LOCAL_MAX || id == RT_NO_OBJECT ||
        (lights & RT_LIGHTS_HIGHLIGHT) || (w & (w - 1)) || (h & (h - 1)))
        return 0;
    const rt_texture *tx = &c->scene->materials[c->scene->objects[id].material].tex;
    if (tx->active && tx->kind != RT_TEX_CHECKER)
        return 0;
    for (int m = 1; m < 4; m++)
        if (k[m]->lights != lights)
            return 0;
    for (int ch = 0; ch < 3; ch++) {
        int lo = 255, hi = 0;
        for (int m = 0; m < 4; m++) {
            const int v = k[m]->hits[0].contrib[ch];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        if (hi - lo > c->thr8)
            return 0;
    }
    return 1;
}
