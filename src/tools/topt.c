/* topt.c: the command-line grammar of the small tools (rt-cmp, rt-scenec), that of render's (src/app/cli.c). */
#include "topt.h"

#include <stdio.h>
#include <string.h>

#include "cli.h" /* CLI_VERSION_NAME */
#include "eline.h"

int topt_error(const char *prog, const char *option, const char *what, const char *value)
{
    if (value)
        eline_print("%s: %s: %s, got '%s' (see %s --help)", prog, option, what, value, prog);
    else
        eline_print("%s: %s: %s (see %s --help)", prog, option, what, prog);
    return 2;
}

void topt_version(FILE *f, const char *prog)
{
    fprintf(f, "%s (fixray) %s\n", prog, CLI_VERSION_NAME);
}

int topt_next(const char *prog, const topt *opts, int n, int argc, char **argv, int *i,
              unsigned *given, const char **val)
{
    const char *a = argv[*i], *eq = a[0] == '-' ? strchr(a, '=') : NULL;
    size_t len = eq ? (size_t)(eq - a) : strlen(a);
    *val = NULL;
    if (a[0] != '-' || !a[1])
        return TOPT_WORD;
    int k = 0;
    while (k < n && !(strlen(opts[k].name) == len && strncmp(a, opts[k].name, len) == 0) &&
           !(opts[k].alias && strlen(opts[k].alias) == len && strncmp(a, opts[k].alias, len) == 0))
        k++;
    if (k == n) {
        eline_print("%s: %.*s: unknown option (see %s --help)", prog, (int)len, a, prog);
        return TOPT_FAIL;
    }
    char name[32]; /* as given: "-o" or "--output" */
    snprintf(name, sizeof name, "%.*s", (int)len, a);
    if (opts[k].arg && !eq) {
        if (*i + 1 >= argc) {
            topt_error(prog, name, "needs a value", NULL);
            return TOPT_FAIL;
        }
        *val = argv[++*i];
    } else if (opts[k].arg) {
        *val = eq + 1;
    } else if (eq) {
        topt_error(prog, name, "takes no value", eq + 1);
        return TOPT_FAIL;
    }
    if (*val && !**val) {
        topt_error(prog, name, "needs a value, not an empty one", NULL);
        return TOPT_FAIL;
    }
    if (*given & (1u << k)) {
        topt_error(prog, name, "is given more than once", NULL);
        return TOPT_FAIL;
    }
    *given |= 1u << k;
    return k;
}
