/* sdl.c: the desktop display through SDL2: a resizable window (or full screen) that shows frames scaled to fit, and the player's keys. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <SDL.h>

#include "platform.h"

static SDL_Window *sdl_window;
static SDL_Renderer *sdl_renderer;
static SDL_Texture *sdl_texture;
static int sdl_width, sdl_height;

int plat_display_open(int width, int height, const char *title)
{
    /* Without an X or Wayland display SDL would fall back to an invisible (offscreen or dummy)
     * driver and "play" to nobody: that is an error, unless SDL_VIDEODRIVER asks for it. */
    int chosen = getenv("SDL_VIDEODRIVER") != NULL;
    if (!chosen && !getenv("DISPLAY") && !getenv("WAYLAND_DISPLAY")) {
        fprintf(stderr, "%s: no display to play on (neither DISPLAY nor WAYLAND_DISPLAY is set)\n",
                plat_program());
        return -1;
    }
    if (!chosen) /* only the drivers of the display there is (no noise from probing others) */
        SDL_SetHint(SDL_HINT_VIDEODRIVER, getenv("WAYLAND_DISPLAY") ? "wayland,x11" : "x11");
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        fprintf(stderr, "%s: no display to play on: %s\n", plat_program(), SDL_GetError());
        return -1;
    }
    const char *driver = SDL_GetCurrentVideoDriver();
    if (!chosen && driver && (strcmp(driver, "offscreen") == 0 || strcmp(driver, "dummy") == 0)) {
        fprintf(stderr, "%s: no display to play on (SDL found only its '%s' driver)\n",
                plat_program(), driver);
        SDL_Quit();
        return -1;
    }
    /* Scaled frames are smoothed; the picture keeps its aspect ratio, with bars around it. */
    SDL_SetHint(SDL_HINT_RENDER_SCALE_QUALITY, "linear");
    sdl_window = SDL_CreateWindow(title, SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, width,
                                  height, SDL_WINDOW_RESIZABLE);
    if (sdl_window)
        sdl_renderer = SDL_CreateRenderer(sdl_window, -1, 0);
    if (sdl_renderer && SDL_RenderSetLogicalSize(sdl_renderer, width, height) == 0)
        sdl_texture = SDL_CreateTexture(sdl_renderer, SDL_PIXELFORMAT_RGB888,
                                        SDL_TEXTUREACCESS_STREAMING, width, height);
    if (!sdl_texture) {
        fprintf(stderr, "%s: cannot open a %dx%d window: %s\n", plat_program(), width, height,
                SDL_GetError());
        plat_display_close();
        return -1;
    }
    sdl_width = width;
    sdl_height = height;
    return 0;
}

int plat_display_show(const plat_frame *f)
{
    if (!sdl_texture || f->width != sdl_width || f->height != sdl_height) {
        fprintf(stderr, "%s: no open display for a %dx%d frame\n", plat_program(), f->width,
                f->height);
        return -1;
    }
    /* SDL_PIXELFORMAT_RGB888 is 0x00RRGGBB in a 32-bit word: the tracer's own pixels. */
    if (SDL_UpdateTexture(sdl_texture, NULL, f->pixels, f->stride * (int)sizeof *f->pixels) != 0 ||
        SDL_RenderClear(sdl_renderer) != 0 ||
        SDL_RenderCopy(sdl_renderer, sdl_texture, NULL, NULL) != 0) {
        fprintf(stderr, "%s: cannot show a frame: %s\n", plat_program(), SDL_GetError());
        return -1;
    }
    SDL_RenderPresent(sdl_renderer);
    return 0;
}

static void sdl_toggle_fullscreen(void)
{
    int full = (SDL_GetWindowFlags(sdl_window) & SDL_WINDOW_FULLSCREEN_DESKTOP) != 0;
    if (SDL_SetWindowFullscreen(sdl_window, full ? 0 : SDL_WINDOW_FULLSCREEN_DESKTOP) != 0)
        fprintf(stderr, "%s: warning: cannot toggle full screen: %s\n", plat_program(),
                SDL_GetError());
}

int plat_display_poll(int wait_ms)
{
    SDL_Event e;
    while (wait_ms > 0 ? SDL_WaitEventTimeout(&e, wait_ms) : SDL_PollEvent(&e)) {
        if (e.type == SDL_QUIT)
            return PLAT_KEY_QUIT;
        if (e.type == SDL_WINDOWEVENT &&
            (e.window.event == SDL_WINDOWEVENT_EXPOSED ||
             e.window.event == SDL_WINDOWEVENT_SIZE_CHANGED))
            return PLAT_KEY_REDRAW;
        if (e.type != SDL_KEYDOWN)
            continue;
        switch (e.key.keysym.sym) {
        case SDLK_ESCAPE:
        case SDLK_q: return PLAT_KEY_QUIT;
        case SDLK_SPACE: return PLAT_KEY_PAUSE;
        case SDLK_f:
            sdl_toggle_fullscreen(); /* the window's own business: scaling follows */
            break;
        case SDLK_s: return PLAT_KEY_SAMPLES;
        case SDLK_LEFT: return PLAT_KEY_BACK;
        case SDLK_RIGHT: return PLAT_KEY_FORWARD;
        case SDLK_g: return PLAT_KEY_GRID;
        default: break;
        }
    }
    return PLAT_KEY_NONE;
}

void plat_display_status(const char *text)
{
    if (sdl_window)
        SDL_SetWindowTitle(sdl_window, text);
}

void plat_display_close(void)
{
    if (sdl_texture)
        SDL_DestroyTexture(sdl_texture);
    if (sdl_renderer)
        SDL_DestroyRenderer(sdl_renderer);
    if (sdl_window)
        SDL_DestroyWindow(sdl_window);
    sdl_texture = NULL;
    sdl_renderer = NULL;
    sdl_window = NULL;
    SDL_Quit();
}
