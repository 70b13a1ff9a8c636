/* render.c: whole frames: every pixel traced (full mode), or adaptively subsampled; pixel colours. */
#include "rt.h"

static void render_full(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
                        int stride, rt_stats *stats, uint8_t *traced)
{
    rt_sample sample;
    for (int y = 0; y < v->height; y++) {
        uint32_t *row = pixels + (long)y * stride;
        for (int x = 0; x < v->width; x++) {
            rt_trace_pixel(s, v, p, x, y, stats, &sample);
            row[x] = rt_color_pixel(sample.color);
        }
        if (traced)
            for (int x = 0; x < v->width; x++)
                traced[(long)y * v->width + x] = 1;
    }
}

void rt_render(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
               int stride, rt_stats *stats, void *work, uint8_t *traced)
{
    if (p->mode == RT_MODE_ADAPTIVE)
        rt_render_adaptive(s, v, p, pixels, stride, stats, work, traced);
    else
        render_full(s, v, p, pixels, stride, stats, traced);
}
