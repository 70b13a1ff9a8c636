/* test_stability.c: randomised properties of ray-sphere and ray-plane against double, and normalisation at the range ends.
 *
 * Usage: test_stability [RAYS]: RAYS random rays per shape (default 3,000,000; `make stress`
 * runs the -O2 builds with more). Seeds are fixed, so a failure reproduces; the worst case of
 * every measured error is printed with its inputs. Bounds (docs/numerics.md) per build:
 *   hit/miss agree unless the ray passes within BAND of tangency (|perp - r|) or, for planes,
 *     its cosine with the plane is within BAND_COS of the parallel limit or the hit within
 *     BAND_T of the ray's ends;
 *   the hit point lies within RADIAL(m) of the surface (what the secondary-ray offset must
 *     cover), m the largest of the ray's length, the point's and the sphere's coordinates;
 *   away from tangency (thc = sqrt(r^2 - perp^2) >= r/64) it is within ALONG(m, perp, thc)
 *     of the exact hit;
 *   the sphere normal is within 2|dp|/r + NORMAL_ABS of the exact one;
 *   a ray leaving from the hit point offset by R_EPS_OFFSET along the normal, into the open
 *     half-space (a mirror or shadow ray), never meets its own surface (float: within 2048).
 * Tests are not part of the fixed core, so the reference is computed here in double.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

#include "rt_local.h"

#if REAL_FIXED
static double to_d(real r) { return r / 65536.0; }
static real from_d(double x) { return (real)llround(x * 65536.0); }
static double u_to_d(unit u) { return u / 1073741824.0; }
/* Every bound is a few units of the last place of Q16.16 (1.5e-5) or Q2.30, independent of
 * the distance, except the tangency band, which grows with the direction's quantisation
 * (2^-30) times the distance. */
#define RADIAL(m) (1e-4 + 0 * (m))
/* along the ray: the rounding of tca (2^-17 per coordinate) moves |perp|^2, and the root
 * thc = sqrt(r^2 - perp^2) amplifies that by perp / thc */
#define ALONG(m, perp, thc) ((8e-5 + 0 * (m)) * (1 + (perp) / (thc)))
/* rays from the offset hit point never meet their own sphere, anywhere in range */
#define SELF_SAFE 1e9
#define NORMAL_ABS 4e-9
#define BAND(dist) (3e-5 + 4e-9 * (dist))
#define BAND_COS 2e-9
/* rays aimed within 2^-24 .. 2^-2 of tangency on purpose: how many may fall in the band */
#define DISAGREE_PER_MILLE 1
#define PLANE_PERP 4e-5
#else
static double to_d(real r) { return r; }
static real from_d(double x) { return (real)x; }
static double u_to_d(unit u) { return u; }
/* float: relative to the magnitude m of the ray's length and coordinates (a float's step is
 * 2^-24 of it; 4 steps) */
#define RADIAL(m) (1e-5 + 6e-7 * (m))
#define ALONG(m, perp, thc) ((1e-5 + 5e-7 * (m)) * (1 + (perp) / (thc)))
/* Beyond 2048 units (hit point coordinates or ray length) a float's step (2.4e-4 and up) is
 * no longer small against the offset (1/512): hit points there can land below the offset, and
 * a mirror ray can meet its own surface. Counted and printed, not failed: a limit of the
 * float build, see docs/numerics.md. */
#define SELF_SAFE 2048.0
#define NORMAL_ABS 4e-7
#define BAND(dist) (4e-3 + 4e-7 * (dist))
#define BAND_COS 2e-7
#define DISAGREE_PER_MILLE 10
#define PLANE_PERP 4e-3
#endif
#define BAND_T 0.02

static long n_rays = 3000000;

/* xorshift64*: fixed seeds, the same sequence on every machine */
static uint64_t rng = 0x9E3779B97F4A7C15ull;
static double rnd(double lo, double hi)
{
    rng ^= rng >> 12;
    rng ^= rng << 25;
    rng ^= rng >> 27;
    uint64_t v = rng * 2685821657736338717ull;
    return lo + (hi - lo) * ((double)(v >> 11) / 9007199254740992.0);
}

static void rnd_unit(double *v)
{
    double l;
    do {
        v[0] = rnd(-1, 1), v[1] = rnd(-1, 1), v[2] = rnd(-1, 1);
        l = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    } while (l > 1 || l < 1e-4);
    l = sqrt(l);
    v[0] /= l, v[1] /= l, v[2] /= l;
}

static vec3 vq(const double *p) { return v3(from_d(p[0]), from_d(p[1]), from_d(p[2])); }
static void dv(vec3 v, double *o) { o[0] = to_d(v.x), o[1] = to_d(v.y), o[2] = to_d(v.z); }
/* The build's direction as an exact unit vector in double: the ray the build traces. */
static void dd(dir3 d, double *o)
{
    o[0] = u_to_d(d.x), o[1] = u_to_d(d.y), o[2] = u_to_d(d.z);
    double l = sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
    o[0] /= l, o[1] /= l, o[2] /= l;
}
static double dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static double dist3(const double *a, const double *b)
{
    double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
    return sqrt(x * x + y * y + z * z);
}

/* The build's hit point o + d t (returned, and in double in pd) and the exact one (pt) at the
 * exact distance along the exact ray (o, e). */
static vec3 hit_points(vec3 org, dir3 d, real t, const double *o, const double *e, double t_true,
                       double *pd, double *pt)
{
    vec3 p = v3_along(org, d, t);
    dv(p, pd);
    for (int k = 0; k < 3; k++)
        pt[k] = o[k] + e[k] * t_true;
    return p;
}

/* The test builds count numeric events; the -O2 builds (make stress) do not. */
#if FX_COUNT_EVENTS
static void reset_events(void) { fx_events_reset(); }
static void no_events(const char *what)
{
    if (fx_event_count[FX_EV_OVERFLOW] || fx_event_count[FX_EV_DOMAIN] ||
        fx_event_count[FX_EV_NONFINITE])
        fail_msg("%s: numeric events: overflow %lu domain %lu nonfinite %lu", what,
                 fx_event_count[FX_EV_OVERFLOW], fx_event_count[FX_EV_DOMAIN],
                 fx_event_count[FX_EV_NONFINITE]);
}
#else
static void reset_events(void) {}
static void no_events(const char *what) { (void)what; }
#endif

/* A worst case: its value and a description of the inputs. */
typedef struct worst {
    double v;
    char what[200];
} worst;
static void note(worst *w, double v, const char *fmt, ...)
{
    if (v <= w->v)
        return;
    w->v = v;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(w->what, sizeof w->what, fmt, ap);
    va_end(ap);
}

static void test_sphere_properties(void **state)
{
    (void)state;
    rng = 0x5EED0001u;
    worst w_band = {0, ""}, w_rad = {0, ""}, w_along = {0, ""}, w_norm = {0, ""};
    long hits = 0, disagree = 0, self = 0, far_origin = 0, self_far = 0;
    double self_far_min = INFINITY;
    reset_events();
    for (long i = 0; i < n_rays; i++) {
        /* a sphere within the scene limits: centre in the cube, radius 1/128 .. 2048 (log) */
        double c[3] = {rnd(-4096, 4096), rnd(-4096, 4096), rnd(-4096, 4096)};
        double r = exp2(rnd(-7, 11));
        rt_object s = {.kind = RT_SPHERE, .center = vq(c), .radius = from_d(r)};
        s.radius2 = w_sq(s.radius);
        s.behind = rt_sphere_behind(s.radius);
        dv(s.center, c);
        r = to_d(s.radius);
        /* origin: in the cube (primary and secondary rays), or one ray length further out
         * (shadow rays leave from hit points up to R_T_MAX from the cube) */
        double o[3];
        if (i % 8 == 0) {
            double u[3];
            rnd_unit(u);
            double base[3] = {rnd(-4096, 4096), rnd(-4096, 4096), rnd(-4096, 4096)};
            double t = rnd(0, 16000);
            for (int k = 0; k < 3; k++)
                o[k] = base[k] + u[k] * t;
            far_origin++;
        } else {
            for (int k = 0; k < 3; k++)
                o[k] = rnd(-4096, 4096);
        }
        vec3 org = vq(o);
        dv(org, o);
        /* aim at a point beside the centre at a distance near r: many rays near tangency */
        double side[3], aim[3];
        rnd_unit(side);
        double off = i % 4 == 0 ? rnd(0, 1.5) : 1 + rnd(-1, 1) * exp2(rnd(-24, -2));
        for (int k = 0; k < 3; k++)
            aim[k] = c[k] + side[k] * r * off - o[k];
        dir3 d = d3_norm(v3(from_d(aim[0]), from_d(aim[1]), from_d(aim[2])), 0);
        if (d.x == 0 && d.y == 0 && d.z == 0)
            continue;
        double e[3];
        dd(d, e);
        /* exact answer for the ray the build traces */
        double l[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
        double tca = dot(l, e);
        double pp[3] = {l[0] - tca * e[0], l[1] - tca * e[1], l[2] - tca * e[2]};
        double perp = sqrt(dot(pp, pp));
        double t_true = -1;
        if (perp <= r) {
            double thc = sqrt(r * r - perp * perp);
            t_true = tca - thc > 0 ? tca - thc : (tca + thc > 0 ? tca + thc : -1);
        }
        int want = t_true > 0 && t_true < to_d(R_T_MAX);
        real tr;
        int got = rt_intersect(&s, org, d, R_T_MAX, &tr);
        double len = sqrt(dot(l, l));
        if (got != want) {
            double gap = fabs(perp - r);
            note(&w_band, gap / BAND(len),
                 "|perp - r| %.3g at distance %.6g (r %.6g): this build %s", gap, len, r,
                 got ? "hits" : "misses");
            if (gap > BAND(len) && fabs(t_true - to_d(R_T_MAX)) > BAND_T)
                fail_msg("sphere: hit/miss disagree %.3g from tangency (band %.3g): o (%.9g %.9g "
                         "%.9g) c (%.9g %.9g %.9g) r %.9g d (%.12g %.12g %.12g)",
                         gap, BAND(len), o[0], o[1], o[2], c[0], c[1], c[2], r, e[0], e[1], e[2]);
            disagree++;
            continue;
        }
        if (!got)
            continue;
        hits++;
        double pd[3], pt[3];
        vec3 p = hit_points(org, d, tr, o, e, t_true, pd, pt);
        double mag = fmax(fmax(t_true, r + fmax(fabs(c[0]), fmax(fabs(c[1]), fabs(c[2])))),
                          fmax(fabs(pd[0]), fmax(fabs(pd[1]), fabs(pd[2]))));
        double rad = fabs(dist3(pd, c) - r), rb = RADIAL(mag);
        note(&w_rad, rad / rb, "%.3g off a sphere of r %.6g at distance %.6g (bound %.3g)", rad, r,
             t_true, rb);
        if (rad > rb)
            fail_msg("sphere: hit point %.3g off the surface (bound %g): r %.9g t %.9g", rad, rb, r,
                     t_true);
        double thc = sqrt(fmax(r * r - perp * perp, 0));
        double dp = dist3(pd, pt);
        if (thc >= r / 64) {
            double ab = ALONG(mag, perp, thc);
            note(&w_along, dp / ab, "%.3g from the exact hit (bound %.3g), r %.6g t %.6g", dp, ab,
                 r, t_true);
            if (dp > ab)
                fail_msg("sphere: hit point %.3g from the exact one (bound %g): r %.9g t %.9g", dp,
                         ab, r, t_true);
        }
        /* normal at the build's hit point against the exact normal at the exact hit */
        dir3 n = rt_shapes[RT_SPHERE].normal(&s, p);
        double nd[3], nt[3];
        dd(n, nd);
        for (int k = 0; k < 3; k++)
            nt[k] = (pt[k] - c[k]) / r;
        double dn = dist3(nd, nt), nb = 2 * dp / r + NORMAL_ABS;
        note(&w_norm, dn / nb, "normal off by %.3g (bound %.3g), r %.6g", dn, nb, r);
        if (dn > nb)
            fail_msg("sphere: normal off by %.3g (bound %.3g), r %.9g", dn, nb, r);
        /* a mirror or shadow ray from the offset origin into the open side never meets this
         * sphere again (outside hits; from inside every ray meets it) */
        if (u_to_d(d3_dot(d, n)) < 0) {
            vec3 po = v3_along(p, n, R_EPS_OFFSET);
            for (int j = 0; j < 4; j++) {
                double v[3];
                rnd_unit(v);
                if (j == 0) { /* grazing: along the tangent plane */
                    double k = dot(v, nd);
                    for (int m = 0; m < 3; m++)
                        v[m] -= k * nd[m];
                    double vl = sqrt(dot(v, v));
                    for (int m = 0; m < 3; m++)
                        v[m] = v[m] / vl + nd[m] * 1e-6;
                }
                dir3 sd =
                    d3_norm(v3(from_d(v[0] * 1000), from_d(v[1] * 1000), from_d(v[2] * 1000)), 0);
                if (d3_dot(sd, n) <= 0)
                    sd = d3_neg(sd);
                if (d3_dot(sd, n) <= 0)
                    continue;
                real ts;
                if (rt_intersect(&s, po, sd, R_T_MAX, &ts)) {
                    double pm = fmax(t_true, fmax(fabs(pd[0]), fmax(fabs(pd[1]), fabs(pd[2]))));
                    if (pm > SELF_SAFE) { /* float only: see SELF_SAFE */
                        self_far++;
                        self_far_min = fmin(self_far_min, pm);
                        continue;
                    }
                    fail_msg("sphere: ray from its own offset hit point meets it again at t %.6g: "
                             "r %.9g, hit at distance %.9g",
                             to_d(ts), r, t_true);
                    self++;
                }
            }
        }
    }
    print_message("sphere properties: %ld rays (%ld from far origins), %ld hits, %ld hit/miss "
                  "disagreements, all within the tangency band\n",
                  n_rays, far_origin, hits, disagree);
    print_message("  worst disagreement / band: %.3g (%s)\n", w_band.v, w_band.what);
    print_message("  worst radial error / bound: %.3g (offset %g): %s\n", w_rad.v,
                  to_d(R_EPS_OFFSET), w_rad.what);
    print_message("  worst error along the ray away from tangency / bound: %.3g: %s\n", w_along.v,
                  w_along.what);
    print_message("  worst normal error / bound: %.3g: %s\n", w_norm.v, w_norm.what);
    if (self_far)
        print_message(
            "  float: %ld rays from hit points beyond %g units (nearest %.6g) met their own "
            "sphere again: the float hit point's error there reaches the offset\n",
            self_far, SELF_SAFE, self_far_min);
    assert_int_equal(self, 0);
    assert_true(disagree * 1000 < n_rays * DISAGREE_PER_MILLE);
    no_events("sphere properties");
}

static void test_plane_properties(void **state)
{
    (void)state;
    rng = 0x5EED0002u;
    worst w_perp = {0, ""}, w_along = {0, ""}, w_band = {0, ""};
    long hits = 0, disagree = 0, self_far = 0;
    double self_far_min = INFINITY;
    reset_events();
    for (long i = 0; i < n_rays; i++) {
        double a[3];
        rnd_unit(a);
        if (i % 4 == 0) /* axis-aligned or nearly so, as floors and walls are */
            a[i / 4 % 3] += 1000 * (1 + (i % 3));
        double scale = exp2(rnd(-6, 12));
        rt_object pl = {.kind = RT_PLANE,
                        .axis =
                            v3(from_d(a[0] * scale), from_d(a[1] * scale), from_d(a[2] * scale)),
                        .offset = from_d(rnd(-4096, 4096))};
        if (v3_is_zero(pl.axis))
            continue;
        pl.normal = d3_norm(pl.axis, 0);
        double n[3], off = to_d(pl.offset);
        dd(pl.normal, n);
        double o[3] = {rnd(-4096, 4096), rnd(-4096, 4096), rnd(-4096, 4096)};
        vec3 org = vq(o);
        dv(org, o);
        /* directions of every slope, many nearly parallel to the plane */
        double v[3];
        rnd_unit(v);
        if (i % 2 == 0) {
            double k = dot(v, n);
            double tilt = (i % 4 == 0 ? 1 : -1) * exp2(rnd(-16, -4));
            for (int m = 0; m < 3; m++)
                v[m] = v[m] - k * n[m] + tilt * n[m];
        }
        dir3 d = d3_norm(v3(from_d(v[0] * 1000), from_d(v[1] * 1000), from_d(v[2] * 1000)), 0);
        double e[3];
        dd(d, e);
        double den = dot(e, n), num = off - dot(o, n);
        double t_true = num / den;
        int want = fabs(den) >= to_d(R_ONE) * 1e-4 && t_true > 0 && t_true < to_d(R_T_MAX);
        real tr;
        int got = rt_intersect(&pl, org, d, R_T_MAX, &tr);
        if (got != want) {
            double near_cos = fabs(fabs(den) - 1e-4);
            double near_t = fmin(fabs(t_true), fabs(t_true - to_d(R_T_MAX)));
            note(&w_band, near_t, "cosine %.9g, t %.9g", den, t_true);
            if (near_cos > BAND_COS && near_t > BAND_T)
                fail_msg("plane: hit/miss disagree: cosine %.12g t %.9g", den, t_true);
            disagree++;
            continue;
        }
        if (!got)
            continue;
        hits++;
        double pd[3], pt[3];
        vec3 p = hit_points(org, d, tr, o, e, t_true, pd, pt);
        double perp = fabs(dot(pd, n) - off);
        note(&w_perp, perp, "%.3g off the plane at t %.6g, cosine %.3g", perp, t_true, den);
        if (perp > PLANE_PERP)
            fail_msg("plane: hit point %.3g off the plane (bound %g): t %.9g cosine %.9g", perp,
                     PLANE_PERP, t_true, den);
        /* along the ray the error is the perpendicular one over the cosine */
        double dp = dist3(pd, pt), ab = (PLANE_PERP + 1e-9 * t_true) / fabs(den);
        note(&w_along, dp * fabs(den), "%.3g from the exact hit at t %.6g, cosine %.3g", dp, t_true,
             den);
        if (dp > ab)
            fail_msg("plane: hit point %.3g from the exact one (bound %.3g): t %.9g cosine %.9g",
                     dp, ab, t_true, den);
        /* from the offset hit point, rays into the side the ray came from never meet it */
        dir3 nn = den < 0 ? pl.normal : d3_neg(pl.normal);
        vec3 po = v3_along(p, nn, R_EPS_OFFSET);
        double sv[3];
        rnd_unit(sv);
        dir3 sd = d3_norm(v3(from_d(sv[0] * 1000), from_d(sv[1] * 1000), from_d(sv[2] * 1000)), 0);
        if (d3_dot(sd, nn) < 0)
            sd = d3_neg(sd);
        real ts;
        if (d3_dot(sd, nn) > 0 && rt_intersect(&pl, po, sd, R_T_MAX, &ts)) {
            double pm = fmax(t_true, fmax(fabs(pd[0]), fmax(fabs(pd[1]), fabs(pd[2]))));
            if (pm > SELF_SAFE) { /* float only: see SELF_SAFE */
                self_far++;
                self_far_min = fmin(self_far_min, pm);
                continue;
            }
            fail_msg("plane: ray from its own offset hit point meets it again: t %.9g", to_d(ts));
        }
    }
    print_message("plane properties: %ld rays, %ld hits, %ld hit/miss disagreements, all at the "
                  "parallel limit or the ray's ends\n",
                  n_rays, hits, disagree);
    print_message("  worst distance off the plane: %.3g (bound %g): %s\n", w_perp.v, PLANE_PERP,
                  w_perp.what);
    print_message("  worst error along the ray x cosine: %.3g: %s\n", w_along.v, w_along.what);
    if (self_far)
        print_message(
            "  float: %ld rays from hit points beyond %g units (nearest %.6g) met their own "
            "plane again\n",
            self_far, SELF_SAFE, self_far_min);
    assert_true(disagree * 1000 < n_rays);
    no_events("plane properties");
}

/* Normalising vectors from one unit of the last place to the largest Q16.16 values, and the
 * length where it fits: direction to a few units of Q2.30, length to a unit of Q16.16. */
static void test_normalise_extremes(void **state)
{
    (void)state;
    rng = 0x5EED0003u;
    double worst_dir = 0, worst_len = 0;
    char wd[160] = "", wl[160] = "";
    reset_events();
    for (int i = 0; i < 200000; i++) {
        double mag = exp2(rnd(-16, 15)); /* 1.5e-5 .. 32768 */
        double v[3];
        rnd_unit(v);
        if (i % 3 == 0) /* one component dominant, the others tiny */
            v[i % 3 ? 1 : 0] *= 1e-4;
        vec3 q = v3(from_d(v[0] * mag), from_d(v[1] * mag), from_d(v[2] * mag));
        if (v3_is_zero(q))
            continue;
        double e[3];
        dv(q, e);
        double l = sqrt(dot(e, e));
        int with_len = l < 32767;
        real len = 0;
        dir3 d = d3_norm(q, with_len ? &len : NULL);
        double err = 0;
        double dr[3] = {u_to_d(d.x), u_to_d(d.y), u_to_d(d.z)};
        for (int k = 0; k < 3; k++)
            err = fmax(err, fabs(dr[k] - e[k] / l));
        if (err > worst_dir) {
            worst_dir = err;
            snprintf(wd, sizeof wd, "(%.9g, %.9g, %.9g)", e[0], e[1], e[2]);
        }
#if REAL_FIXED
        const double dir_tol = 3.0 / 1073741824.0, len_tol = 1.0 / 65536.0 + l / 536870912.0;
#else
        const double dir_tol = 3e-7, len_tol = 3e-7 * l;
#endif
        if (err > dir_tol)
            fail_msg("d3_norm (%.9g, %.9g, %.9g): direction off by %.3g", e[0], e[1], e[2], err);
        if (with_len) {
            double le = fabs(to_d(len) - l);
            if (le > worst_len) {
                worst_len = le;
                snprintf(wl, sizeof wl, "(%.9g, %.9g, %.9g)", e[0], e[1], e[2]);
            }
            if (le > len_tol)
                fail_msg("d3_norm (%.9g, %.9g, %.9g): length %.9g, want %.9g", e[0], e[1], e[2],
                         to_d(len), l);
        }
    }
    /* the extremes themselves */
    vec3 tiny = v3(R_LSB, 0, 0), huge = v3(R_MAX, R_MAX, -R_MAX);
    dir3 t = d3_norm(tiny, 0), h = d3_norm(huge, 0);
    assert_true(fabs(u_to_d(t.x) - 1) < 1e-6);
    assert_true(fabs(u_to_d(h.x) - 1 / sqrt(3.0)) < 1e-6 &&
                fabs(u_to_d(h.z) + 1 / sqrt(3.0)) < 1e-6);
    print_message("normalise: worst direction error %.3g at %s; worst length error %.3g at %s\n",
                  worst_dir, wd, worst_len, wl);
    no_events("normalise");
}

int main(int argc, char **argv)
{
    if (argc > 1) {
        char *end;
        n_rays = strtol(argv[1], &end, 10);
        if (*end || n_rays < 1) {
            fprintf(stderr, "usage: %s [RAYS]\n", argv[0]);
            return 2;
        }
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_normalise_extremes),
        cmocka_unit_test(test_sphere_properties),
        cmocka_unit_test(test_plane_properties),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
