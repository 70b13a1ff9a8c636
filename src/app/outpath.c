/* outpath.c: checks, before any work is done, that an output file can be created where it is asked for. */
#define _POSIX_C_SOURCE 200809L
#include "outpath.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Room the temporary file's name takes beyond the file's: ".tmp-XXXXXX" (image.c) or
 * ".tmp-<pid>" (scenec.c). */
#define OUTPATH_TMP_SUFFIX 16

int outpath_check(const char *path, char *err, size_t errlen)
{
    struct stat st;
    if (!path[0]) {
        snprintf(err, errlen, "the output file name is empty");
        return -1;
    }
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    if (strlen(path) + OUTPATH_TMP_SUFFIX >= PATH_MAX ||
        strlen(base) + OUTPATH_TMP_SUFFIX > NAME_MAX) {
        snprintf(err, errlen, "%.64s...: the file name is too long", path);
        return -1;
    }
    if (!base[0] || (stat(path, &st) == 0 && S_ISDIR(st.st_mode))) {
        snprintf(err, errlen, "%s: is a folder, not a file name", path);
        return -1;
    }
    /* The folder the file (and its temporary file) goes to. */
    char dir[PATH_MAX];
    size_t n = slash ? (size_t)(slash - path) : 0;
    if (!slash)
        strcpy(dir, ".");
    else if (n == 0)
        strcpy(dir, "/");
    else {
        memcpy(dir, path, n);
        dir[n] = 0;
    }
    if (stat(dir, &st) != 0) {
        snprintf(err, errlen, "%s: cannot write: folder %s: %s", path, dir, strerror(errno));
        return -1;
    }
    if (!S_ISDIR(st.st_mode)) {
        snprintf(err, errlen, "%s: cannot write: %s is not a folder", path, dir);
        return -1;
    }
    if (access(dir, W_OK | X_OK) != 0) {
        snprintf(err, errlen, "%s: cannot write: folder %s: %s", path, dir, strerror(errno));
        return -1;
    }
    return 0;
}
