/* camera.c: the camera: the look-at frame and the primary ray through each pixel. */
#include "rt.h"

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
}

dir3 rt_view_ray(const rt_view *v, int x, int y)
{
    return d3_ray(v->fwd, v->right, v->up, v->step, 2 * x + 1 - v->width, v->height - 2 * y - 1);
}
