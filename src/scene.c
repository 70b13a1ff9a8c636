/* scene.c: derived scene data and the camera: look-at frame and primary rays. */
#include "rt.h"

void rt_scene_prepare(rt_scene *s)
{
    for (int i = 0; i < s->nobjects; i++) {
        rt_object *o = &s->objects[i];
        if (o->kind == RT_SPHERE) {
            o->radius2 = w_sq(o->radius);
        } else {
            /* A plane is given by any normal vector and the offset along the unit normal. */
            o->normal = d3_norm(o->axis, 0);
        }
    }
    for (int i = 0; i < s->nmaterials; i++) {
        rt_material *m = &s->materials[i];
        m->ior_inv = r_div(R_ONE, m->ior);
    }
}

void rt_view_init(rt_view *v, const rt_camera *cam, int width, int height)
{
    v->eye = cam->eye;
    v->width = width;
    v->height = height;
    v->fwd = d3_norm(v3_sub(cam->at, cam->eye), 0);
    real sin_up;
    v->right = d3_cross(v->fwd, d3_norm(cam->up, 0), &sin_up);
    if (sin_up < R(0.001)) {
        /* The up vector is (nearly) parallel to the view: any other axis will do. */
        dir3 alt = {0, 0, U_ONE};
        if (v->fwd.z > U(0.5) || v->fwd.z < U(-0.5))
            alt = (dir3){U_ONE, 0, 0};
        v->right = d3_cross(v->fwd, alt, 0);
    }
    v->up = d3_cross(v->right, v->fwd, 0);
    unit sn, cs;
    u_sincos_deg(r_shr(cam->fov, 1), &sn, &cs);
    v->step = u_divi(u_div(sn, cs), height); /* tan(fov / 2) / height */
}

dir3 rt_view_ray(const rt_view *v, int x, int y)
{
    return d3_ray(v->fwd, v->right, v->up, v->step, 2 * x + 1 - v->width,
                  v->height - 2 * y - 1);
}
