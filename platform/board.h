/* board.h: what the bare-metal boards (platform/arm/, platform/m3/, platform/m0/) share: semihosting files, arguments and exit, the UART log, the RAM report.
 *
 * Each board provides board_semi (its semihosting trap: `svc 0x123456` in ARM state, `bkpt
 * 0xab` on a Cortex-M) and board_putc (its UART); platform/board.c builds the rest on them,
 * including plat_log. Both link scripts name the same symbols: __data_start/__data_end,
 * __bss_start/__bss_end, __stack_bottom/__stack_top and BOARD_STACK_PAINT.
 */
#ifndef FIXRAY_BOARD_H
#define FIXRAY_BOARD_H

#include <stdint.h>

/* Semihosting operations (ARM's semihosting specification). */
enum {
    BOARD_SYS_OPEN = 0x01,
    BOARD_SYS_CLOSE = 0x02,
    BOARD_SYS_WRITE = 0x05,
    BOARD_SYS_REMOVE = 0x0e,
    BOARD_SYS_RENAME = 0x0f,
    BOARD_SYS_GET_CMDLINE = 0x15,
    BOARD_SYS_EXIT_EXTENDED = 0x20
};

/* The board's semihosting trap: operation op with its argument block; returns r0. */
int board_semi(uint32_t op, void *arg);

/* One character to the board's UART (the log). */
void board_putc(char c);

uint32_t board_strlen(const char *s);
void board_puts(const char *s);

/* Logs "a" + the file name + "b" as one line. */
void board_log_file(const char *a, const char *file, const char *b);

/* v in decimal at buf (at least 10 bytes); returns the number of digits. */
uint32_t board_dec(char *buf, uint32_t v);

/* A PPM file on the host, written through dest + ".tmp" and renamed when complete, so no
 * half-written file is ever left under its name. */
typedef struct board_file {
    int fd; /* semihosting handle, -1 when none is open */
    const char *dest;
    char tmp[128];
} board_file;

/* Opens f for a width x height PPM named dest and writes its header. Returns 0, or -1 after
 * logging one line (f is then closed). */
int board_file_open(board_file *f, const char *dest, int width, int height);

/* Writes n bytes; 0, or -1 when the host took fewer. */
int board_file_write(board_file *f, const void *buf, uint32_t n);

/* Closes f (nothing when it is not open). With ok, renames it to its name and returns 0; else,
 * or when that fails, removes it, logs "error: DEST: write failed" and returns -1. */
int board_file_end(board_file *f, int ok);

/* Logs "error: CPU exception: WHAT (REG=0x...)" and ends the run with status 3. */
__attribute__((noreturn)) void board_fault(const char *what, const char *reg, uint32_t value);

/* ---- the Cortex-M boards' bands (platform/band.c) ------------------------------------------
 * plat_band_* over one buffer of BOARD_BAND_ROWS rows of BOARD_W pixels (frames of at most
 * BOARD_W x BOARD_H); the board calls board_band_init once before any frame and provides
 * board_band_show: rows y0 .. y0 + rows - 1 of the frame, `width` pixels of each, `stride`
 * apart, on its display (or nowhere), before the band is written to the file. */
void board_band_init(void);
void board_band_show(const uint32_t *px, int stride, int width, int y0, int rows);
/* (With RT_PIXEL_RGB24, px holds 3 bytes a pixel, R, G, B: the M0's, which has no display.) */

/* ---- the Cortex-M boards' start and clock (platform/cortexm.S, platform/cortexm.c) --------
 * cortexm.S calls board_main (the board's own: its devices, cm_clock_start of cortexm.h, then
 * board_run) with .data copied, .bss clear and the stack painted; cortexm.c gives board_semi
 * (bkpt 0xab), plat_time_ns from the SysTick and the faults' report. */
void board_main(void);

/* Ends the run: QEMU exits with `status`. */
__attribute__((noreturn)) void board_exit(int status);

/* Reads the argument list through semihosting into cmdline (size bytes) and argv (at most
 * maxargs - 1 arguments), runs app_main, logs the RAM report ("ram: data=.. bss=..
 * stack_peak=.. total=N bytes", from the painted stack) and exits with app_main's status (1
 * when it was 0 but the stack reached the bottom of its reserve). */
__attribute__((noreturn)) void board_run(char *cmdline, uint32_t size, char **argv, int maxargs);

#endif
