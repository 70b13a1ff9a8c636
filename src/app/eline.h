/* eline.h: an error message on standard error as one line, for the programs' command lines. */
#ifndef FIXRAY_ELINE_H
#define FIXRAY_ELINE_H

#include <stdarg.h>
#include <stdio.h>

/* Prints the message and a newline on standard error. A control character in it (a newline or
 * a tab from a word of the command line) is written as '?', so the message stays one line. */
static inline void eline_print(const char *fmt, ...)
{
    char line[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    for (char *c = line; *c; c++)
        if ((unsigned char)*c < ' ' || *c == 0x7f)
            *c = '?';
    fprintf(stderr, "%s\n", line);
}

#endif
