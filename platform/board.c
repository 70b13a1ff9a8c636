/* board.c: the bare-metal boards' shared half: semihosting files, arguments and exit, the UART log, the RAM report (board.h). */
#include "board.h"

#include <stdint.h>

#include "platform.h"

#define BOARD_OPEN_WB 5                 /* fopen mode "wb" */
#define BOARD_EXIT_APPLICATION 0x20026u /* ADP_Stopped_ApplicationExit */

/* From the board's link.ld. */
extern uint32_t __data_start[], __data_end[], __bss_start[], __bss_end[];
extern uint32_t __stack_bottom[], __stack_top[];
/* The stack's paint pattern is a link-script symbol: its address is the value start.S stores. */
extern const char BOARD_STACK_PAINT[];
#define BOARD_PAINT ((uint32_t)(uintptr_t)BOARD_STACK_PAINT)

uint32_t board_strlen(const char *s)
{
    uint32_t n = 0;
    while (s[n])
        n++;
    return n;
}

void board_puts(const char *s)
{
    while (*s)
        board_putc(*s++);
}

void plat_log(const char *line)
{
    board_puts(line);
    board_putc('\n');
}

void board_log_file(const char *a, const char *file, const char *b)
{
    board_puts(a);
    board_puts(file);
    plat_log(b);
}

uint32_t board_dec(char *buf, uint32_t v)
{
    char d[10];
    uint32_t k = 0, n = 0;
    do {
        d[k++] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    while (k)
        buf[n++] = d[--k];
    return n;
}

int board_file_write(board_file *f, const void *buf, uint32_t n)
{
    uint32_t a[3] = {(uint32_t)f->fd, (uint32_t)(uintptr_t)buf, n};
    return board_semi(BOARD_SYS_WRITE, a) == 0 ? 0 : -1;
}

int board_file_open(board_file *f, const char *dest, int width, int height)
{
    f->fd = -1;
    f->dest = dest;
    uint32_t len = board_strlen(dest);
    if (len + 5 > sizeof f->tmp) {
        board_log_file("error: ", dest, ": path too long");
        return -1;
    }
    for (uint32_t i = 0; i < len; i++)
        f->tmp[i] = dest[i];
    for (uint32_t i = 0; i < 5; i++)
        f->tmp[len + i] = ".tmp"[i];
    uint32_t open_args[3] = {(uint32_t)(uintptr_t)f->tmp, BOARD_OPEN_WB, len + 4};
    f->fd = board_semi(BOARD_SYS_OPEN, open_args);
    if (f->fd < 0) {
        board_log_file("error: ", f->tmp, ": cannot create (semihosting open failed)");
        return -1;
    }
    char head[32];
    uint32_t n = 0;
    head[n++] = 'P';
    head[n++] = '6';
    head[n++] = '\n';
    n += board_dec(head + n, (uint32_t)width);
    head[n++] = ' ';
    n += board_dec(head + n, (uint32_t)height);
    for (const char *s = "\n255\n"; *s; s++)
        head[n++] = *s;
    if (board_file_write(f, head, n) != 0)
        return board_file_end(f, 0);
    return 0;
}

int board_file_end(board_file *f, int ok)
{
    if (f->fd < 0)
        return 0;
    uint32_t len = board_strlen(f->dest);
    uint32_t close_args[1] = {(uint32_t)f->fd};
    f->fd = -1;
    ok &= board_semi(BOARD_SYS_CLOSE, close_args) == 0;
    uint32_t rename_args[4] = {(uint32_t)(uintptr_t)f->tmp, len + 4, (uint32_t)(uintptr_t)f->dest,
                               len};
    if (ok && board_semi(BOARD_SYS_RENAME, rename_args) == 0)
        return 0;
    uint32_t remove_args[2] = {(uint32_t)(uintptr_t)f->tmp, len + 4};
    board_semi(BOARD_SYS_REMOVE, remove_args);
    board_log_file("error: ", f->dest, ": write failed");
    return -1;
}

void board_exit(int status)
{
    uint32_t args[2] = {BOARD_EXIT_APPLICATION, (uint32_t)status};
    board_semi(BOARD_SYS_EXIT_EXTENDED, args);
    for (;;)
        ;
}

void board_fault(const char *what, const char *reg, uint32_t value)
{
    board_puts("error: CPU exception: ");
    board_puts(what);
    board_puts(" (");
    board_puts(reg);
    board_puts("=0x");
    for (int i = 28; i >= 0; i -= 4)
        board_putc("0123456789abcdef"[(value >> i) & 15]);
    plat_log(")");
    board_exit(3);
}

/* Logs "ram: ..." with the bytes of .data, .bss and the deepest stack use seen; 1 when the
 * stack reached the bottom of its reserve. */
static int board_report_ram(void)
{
    const uint32_t *w = __stack_bottom;
    while (w < __stack_top && *w == BOARD_PAINT)
        w++;
    uint32_t data = (uint32_t)((__data_end - __data_start) * 4);
    uint32_t bss = (uint32_t)((__bss_end - __bss_start) * 4);
    uint32_t stack = (uint32_t)((__stack_top - w) * 4);
    uint32_t v[4] = {data, bss, stack, data + bss + stack};
    static const char *const names[4] = {"ram: data=", " bss=", " stack_peak=", " total="};
    for (int i = 0; i < 4; i++) {
        char d[10];
        board_puts(names[i]);
        for (uint32_t k = 0, n = board_dec(d, v[i]); k < n; k++)
            board_putc(d[k]);
    }
    plat_log(" bytes");
    if (w == __stack_bottom) {
        plat_log("error: the stack reached the bottom of its reserve (overflow)");
        return 1;
    }
    return 0;
}

/* Logs "error: " + a + the decimal n + b and exits with status 2. */
static __attribute__((noreturn)) void board_refuse(const char *a, uint32_t n, const char *b)
{
    char d[11];
    d[board_dec(d, n)] = '\0';
    board_puts(a);
    board_puts(d);
    plat_log(b);
    board_exit(2);
}

void board_run(char *cmdline, uint32_t size, char **argv, int maxargs)
{
    int argc = 0;
    uint32_t args[2] = {(uint32_t)(uintptr_t)cmdline, size};
    if (board_semi(BOARD_SYS_GET_CMDLINE, args) != 0)
        board_refuse("error: the argument list does not fit in ", size, " bytes");
    for (char *s = cmdline; *s;) {
        while (*s == ' ')
            *s++ = '\0';
        if (!*s)
            break;
        if (argc == maxargs - 1)
            board_refuse("error: more than ", (uint32_t)maxargs - 1, " arguments");
        argv[argc++] = s;
        while (*s && *s != ' ')
            s++;
    }
    argv[argc] = 0;
    int status = app_main(argc, argv);
    if (board_report_ram() != 0 && status == 0)
        status = 1;
    board_exit(status);
}
