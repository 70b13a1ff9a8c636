/* render.c: whole frames: every pixel traced, colours turned into pixels. */
#include "rt.h"

uint32_t rt_color_pixel(rt_color c)
{
    return (uint32_t)r_to_byte(c.x) << 16 | (uint32_t)r_to_byte(c.y) << 8 | r_to_byte(c.z);
}

void rt_render_full(const rt_scene *s, const rt_view *v, int depth, uint32_t *pixels, int width,
                    int height, int stride, rt_stats *stats)
{
    rt_sample sample;
    for (int y = 0; y < height; y++) {
        uint32_t *row = pixels + (long)y * stride;
        for (int x = 0; x < width; x++) {
            rt_trace_pixel(s, v, x, y, depth, stats, &sample);
            row[x] = rt_color_pixel(sample.color);
        }
    }
}
