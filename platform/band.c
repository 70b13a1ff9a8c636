/* band.c: the Cortex-M boards' bands (platform/m3/, platform/m0/): a frame handed over a few rows at a time through one small buffer, each band shown by the board and written to the host's file as it comes; no frame is ever in RAM.
 *
 * The band memory holds BOARD_BAND_ROWS rows of BOARD_W pixels (the Makefile sets both): a row of
 * the grid's squares at the intro's 64 rows (grid 8: rows 8 k .. 8 k + 7, the last band ending at
 * row 63). The board shows each band (board_band_show: the M3's OLED; nothing on the M0) before
 * its rows become RGB bytes in place for the file; a build whose renderer writes RGB bytes itself
 * (RT_PIXEL_RGB24, the M0's) keeps 3 bytes a pixel and writes its rows as they are.
 */
#include <stdint.h>

#include "board.h"
#include "platform.h"
#include "rt.h"

#if RT_PIXEL_RGB24
#define BAND_WORDS (BOARD_BAND_ROWS * BOARD_W * 3 / 4)
_Static_assert(BOARD_W % 4 == 0, "a band's RGB rows must fill whole words");
#else
#define BAND_WORDS (BOARD_BAND_ROWS * BOARD_W)
#endif
static uint32_t band_px[BAND_WORDS];
static struct {
    int width, height; /* of the frame begun */
    int y0, rows;      /* the band last given out */
} band_frame;
static board_file band_file; /* the frame's PPM, while one is written (fd >= 0) */

#define BAND_STR2(x) #x
#define BAND_STR(x) BAND_STR2(x)

void board_band_init(void) { band_file.fd = -1; }

int plat_band_begin(plat_frame *f, int width, int height, const char *dest)
{
    if (width < 1 || height < 1 || width > BOARD_W || height > BOARD_H || height % 2) {
        plat_log(
            "error: frames on this board are at most " BAND_STR(BOARD_W) "x" BAND_STR(BOARD_H));
        return -1;
    }
    board_file_end(&band_file, 0); /* a frame left unfinished */
    band_frame.width = width;
    band_frame.height = height;
    band_frame.y0 = band_frame.rows = 0;
    f->pixels = band_px;
    f->width = width;
    f->stride = BOARD_W;
    f->height = BOARD_BAND_ROWS < height ? BOARD_BAND_ROWS : height;
    return dest ? board_file_open(&band_file, dest, width, height) : 0;
}

/* A band is a row of grid squares (at most the grid's rows, the frame's height being even: its
 * last corner row is odd, so no square is a row longer) or one pixel row, and the board renders
 * grids up to RT_GRID_BUILD_MAX: the band memory holds every band of its frames. */
_Static_assert(BOARD_BAND_ROWS >= RT_GRID_BUILD_MAX && BOARD_H % 2 == 0,
               "a band of the board's largest grid must fit the band memory");
uint32_t *plat_band_rows(int y0, int rows)
{
    band_frame.y0 = y0;
    band_frame.rows = rows;
    return band_px;
}

int plat_band_present(void)
{
    int y0 = band_frame.y0, rows = band_frame.rows, w = band_frame.width;
    if (rows < 1 || rows > BOARD_BAND_ROWS || y0 < 0 || y0 + rows > band_frame.height) {
        plat_log("error: a band outside the frame, or larger than the band memory");
        board_file_end(&band_file, 0);
        return -1;
    }
    board_band_show(band_px, BOARD_W, w, y0, rows);
#if RT_PIXEL_RGB24
    for (int y = 0; y < rows && band_file.fd >= 0; y++)
        if (board_file_write(&band_file, (const uint8_t *)band_px + y * BOARD_W * 3,
                             (uint32_t)w * 3) != 0)
            return board_file_end(&band_file, 0);
#else
    if (band_file.fd >= 0) {
        /* Each row becomes its 3 w bytes of RGB in place (the band has been shown): byte 3 x + 2
         * lies within pixel x, read before it is overwritten. */
        for (int y = 0; y < rows; y++) {
            const uint32_t *p = band_px + y * BOARD_W;
            uint8_t *rgb = (uint8_t *)(band_px + y * BOARD_W);
            for (int x = 0; x < w; x++) {
                uint32_t v = p[x];
                rgb[3 * x] = (uint8_t)(v >> 16);
                rgb[3 * x + 1] = (uint8_t)(v >> 8);
                rgb[3 * x + 2] = (uint8_t)v;
            }
            if (board_file_write(&band_file, rgb, (uint32_t)w * 3) != 0)
                return board_file_end(&band_file, 0);
        }
    }
#endif
    return y0 + rows == band_frame.height ? board_file_end(&band_file, 1) : 0;
}
