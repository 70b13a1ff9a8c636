/* lsan_plant.c: a leak planted next to SDL2's own, to check that tests/lsan.supp hides only the libraries' leaks (tests/faults.sh). */
#include <SDL.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The planted leak: a block of a size no library allocates, lost when this returns. */
static void *plant_keep;
static void __attribute__((noinline)) plant_leak(void)
{
    plant_keep = malloc(4242);
    if (plant_keep)
        memset(plant_keep, 1, 4242);
    fprintf(stderr, "lsan_plant: planted 4242 bytes at %p\n", plant_keep);
    plant_keep = NULL;
}

int main(void)
{
    /* what rt play does with SDL: a window, a renderer, then everything closed */
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        fprintf(stderr, "lsan_plant: SDL_Init: %s\n", SDL_GetError());
        return 2;
    }
    SDL_Window *w = SDL_CreateWindow("lsan", 0, 0, 64, 48, 0);
    SDL_Renderer *r = w ? SDL_CreateRenderer(w, -1, SDL_RENDERER_SOFTWARE) : NULL;
    if (!r) {
        fprintf(stderr, "lsan_plant: %s\n", SDL_GetError());
        return 2;
    }
    SDL_RenderClear(r);
    SDL_RenderPresent(r);
    plant_leak();
    SDL_DestroyRenderer(r);
    SDL_DestroyWindow(w);
    SDL_Quit();
    return 0;
}
