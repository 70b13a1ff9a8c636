/* render.c: whole frames or horizontal bands of them: every pixel traced (full mode), or adaptively subsampled. */
#include <string.h>

#include "rt_local.h"

/* `pixels` is the memory of the frame's pixel row py0 (0 for a whole frame). */
static void render_full(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
                        int py0, int stride, rt_stats *stats, uint8_t *traced, int band, int nbands)
{
    rt_sample sample;
    int y0 = (int)((long)v->height * band / nbands),
        y1 = (int)((long)v->height * (band + 1) / nbands);
    for (int y = y0; y < y1; y++) {
        rt_px *row = RT_PX((rt_px *)pixels, (long)(y - py0) * stride);
        for (int x = 0; x < v->width; x++) {
            rt_trace_pixel(s, v, p, x, y, stats, &sample);
            rt_px_set(RT_PX(row, x), rt_color_pixel(sample.color));
        }
        if (traced)
            for (int x = 0; x < v->width; x++)
                traced[(long)y * v->width + x] = RT_TRACED_FULL;
    }
}

static void render_band(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
                        int stride, rt_stats *stats, void *work, uint8_t *traced, int band,
                        int nbands, enum rt_band_memory mem, const void *edges)
{
    if (nbands < 1 || band < 0 || band >= nbands)
        return;
    if (p->mode != RT_MODE_FULL)
        rt_render_adaptive(s, v, p, pixels, stride, stats, work, traced, band, nbands, mem, edges);
    else
        render_full(s, v, p, pixels,
                    mem == RT_BAND_FRAME ? 0 : (int)((long)v->height * band / nbands), stride,
                    stats, traced, band, nbands);
}

void rt_render_band(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
                    int stride, rt_stats *stats, void *work, uint8_t *traced, int band, int nbands)
{
    render_band(s, v, p, pixels, stride, stats, work, traced, band, nbands, RT_BAND_FRAME, NULL);
}

void rt_render_band_edges(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
                          int stride, rt_stats *stats, void *work, const void *edges,
                          uint8_t *traced, int band, int nbands)
{
    render_band(s, v, p, pixels, stride, stats, work, traced, band, nbands, RT_BAND_FRAME, edges);
}

void rt_render_band_into(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *rows,
                         int stride, rt_stats *stats, void *work, uint8_t *traced, int band,
                         int nbands, int keep)
{
    render_band(s, v, p, rows, stride, stats, work, traced, band, nbands,
                keep ? RT_BAND_KEEP : RT_BAND_ONLY, NULL);
}

void rt_render(const rt_scene *s, const rt_view *v, const rt_params *p, uint32_t *pixels,
               int stride, rt_stats *stats, void *work, uint8_t *traced)
{
    if (traced)
        memset(traced, 0, (size_t)v->width * (size_t)v->height);
    rt_render_band(s, v, p, pixels, stride, stats, work, traced, 0, 1);
}
