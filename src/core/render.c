/* render.c: whole frames or horizontal bands of them: every pixel traced (full mode), or adaptively subsampled. */
#include <string.h>

#include "rt.h"

/* Pixel rows [y0, y1) into `rows`, the memory of row y0. */
static void render_full(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *rows,
                        int stride, rt_stats *stats, uint8_t *traced, int y0, int y1)
{
    rt_sample sample;
    for (int y = y0; y < y1; y++) {
        uint32_t *row = rows + (long)(y - y0) * stride;
        for (int x = 0; x < v->width; x++) {
            rt_trace_pixel(s, v, p, x, y, stats, &sample);
            row[x] = rt_color_pixel(sample.color);
        }
        if (traced)
            for (int x = 0; x < v->width; x++)
                traced[(long)y * v->width + x] = 1;
    }
}

void rt_render_band(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
                    int stride, rt_stats *stats, void *work, uint8_t *traced, int band, int nbands)
{
    if (nbands < 1 || band < 0 || band >= nbands)
        return;
    if (p->mode == RT_MODE_ADAPTIVE)
        rt_render_adaptive(s, v, p, pixels, stride, stats, work, traced, band, nbands);
    else {
        int y0 = (int)((long)v->height * band / nbands),
            y1 = (int)((long)v->height * (band + 1) / nbands);
        render_full(s, v, p, pixels + (long)y0 * stride, stride, stats, traced, y0, y1);
    }
}

void rt_render_band_into(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *rows,
                         int stride, rt_stats *stats, void *work, int band, int nbands, int keep)
{
    if (p->mode == RT_MODE_ADAPTIVE) {
        rt_render_adaptive_into(s, v, p, rows, stride, stats, work, band, nbands, keep);
    } else {
        int y0, n;
        rt_render_band_rows(p, v->height, band, nbands, &y0, &n);
        render_full(s, v, p, rows, stride, stats, NULL, y0, y0 + n);
    }
}

void rt_render(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
               int stride, rt_stats *stats, void *work, uint8_t *traced)
{
    if (traced)
        memset(traced, 0, (size_t)v->width * (size_t)v->height);
    rt_render_band(s, v, p, pixels, stride, stats, work, traced, 0, 1);
}
