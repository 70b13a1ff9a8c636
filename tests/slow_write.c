/* slow_write.c: an LD_PRELOAD shim for tests/suite/faults.sh: every fwrite first sleeps, so a test can catch an image while it is being written. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <time.h>

typedef size_t (*slow_fwrite_fn)(const void *, size_t, size_t, FILE *);

size_t fwrite(const void *ptr, size_t size, size_t n, FILE *f)
{
    static slow_fwrite_fn real;
    if (!real)
        *(void **)&real = dlsym(RTLD_NEXT, "fwrite");
    const struct timespec pause = {0, 20000000}; /* 20 ms */
    nanosleep(&pause, NULL);
    return real(ptr, size, n, f);
}
