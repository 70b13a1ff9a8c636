/* null.c: the null display, for the desktop programs that never open a window (rt-edges and the other tools): the display calls of platform.h without SDL2. */
#include <stdio.h>

#include "platform.h"

int plat_display_open(int width, int height, const char *title)
{
    (void)width, (void)height, (void)title;
    fprintf(stderr, "%s: this program has no display (built with platform/null.c)\n",
            plat_program());
    return -1;
}

int plat_display_show(const plat_frame *f)
{
    (void)f;
    return -1;
}

int plat_display_poll(int wait_ms)
{
    (void)wait_ms;
    return PLAT_KEY_QUIT;
}

void plat_display_status(const char *text) { (void)text; }

void plat_display_close(void) {}
