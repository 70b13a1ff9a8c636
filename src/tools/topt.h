/* topt.h: the command-line grammar of the small tools (rt-cmp, rt-scenec), that of render's (src/app/cli.c): --opt value or --opt=value, each option once, no empty value, --help and --version. */
#ifndef FIXRAY_TOPT_H
#define FIXRAY_TOPT_H

#include <stdio.h>

/* One option of a tool: its name, an alias ("-o" for "--output", or NULL), and whether it
 * takes a value. */
typedef struct topt {
    const char *name, *alias;
    int arg;
} topt;

#define TOPT_WORD (-1) /* argv[*i] is no option: a file name or the like */
#define TOPT_FAIL (-2) /* the error is printed: exit with status 2 */
#define TOPT_MAX 16    /* options of one tool, at most */

/* Reads the argument argv[*i] of program `prog` against opts[0 .. n-1] (n <= TOPT_MAX).
 * Returns the option's index, with *val its value (`--opt=value`, or the next argument:
 * then *i is advanced) or NULL for an option without one; TOPT_WORD for an argument not
 * starting with '-' (or "-" alone); or TOPT_FAIL after printing one line on stderr
 * ("PROG: --opt: ... (see PROG --help)") for an unknown option, a missing or empty value, a
 * value given to an option that takes none, or an option given twice (*given keeps one bit
 * per option, 0 before the first call). */
int topt_next(const char *prog, const topt *opts, int n, int argc, char **argv, int *i,
              unsigned *given, const char **val);

/* Prints "PROG (fixray) VERSION" on f, as render's --version does. */
void topt_version(FILE *f, const char *prog);

/* The one-line error "PROG: OPTION: WHAT, got 'VALUE' (see PROG --help)" (value NULL: without
 * the "got"). Returns 2, the exit status. */
int topt_error(const char *prog, const char *option, const char *what, const char *value);

#endif
