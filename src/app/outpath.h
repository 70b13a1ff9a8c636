/* outpath.h: checks, before any work is done, that an output file can be created where it is asked for. */
#ifndef FIXRAY_OUTPATH_H
#define FIXRAY_OUTPATH_H

#include <stddef.h>

/* 0 when `path` names a file that can be created or replaced: not a folder, in an existing
 * folder this process may write to. Otherwise -1 with a one-line reason naming the path in
 * err. (Writes still go through a temporary file and a rename, and can still fail, e.g. on a
 * full disk; this only refuses what is bound to fail before a frame is rendered.) */
int outpath_check(const char *path, char *err, size_t errlen);

#endif
