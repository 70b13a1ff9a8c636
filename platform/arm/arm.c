/* arm.c: the bare-metal ARM926 backend (QEMU versatilepb): PL110 framebuffer, PL011 UART log, 24 MHz counter, semihosting files, arguments and exit.
 *
 * Register addresses and QEMU's quirks are those of ../shared/docs/platform-facts.md. The image
 * runs from RAM at 64 KiB (link.ld); the two framebuffers sit at 1 MiB, outside the program's
 * RAM budget. Nothing here needs interrupts: the UART and the counter are polled.
 */
#include <stdint.h>

#include "platform.h"

#define ARM_W 320
#define ARM_H 240

/* PL110 colour LCD controller. In QEMU's versatile variant CONTROL is at +0x18. */
#define ARM_CLCD 0x10120000u
#define ARM_CLCD_TIMING0 (*(volatile uint32_t *)(ARM_CLCD + 0x00))
#define ARM_CLCD_TIMING1 (*(volatile uint32_t *)(ARM_CLCD + 0x04))
#define ARM_CLCD_UPBASE (*(volatile uint32_t *)(ARM_CLCD + 0x10))
#define ARM_CLCD_CONTROL (*(volatile uint32_t *)(ARM_CLCD + 0x18))
/* enable, 24 bpp in 32-bit words (5 << 1), TFT, BGR (pixels are 0x00RRGGBB), power */
#define ARM_CLCD_ON (1u | 5u << 1 | 1u << 5 | 1u << 8 | 1u << 11)

/* PL011 UART0: data register, and the flag register's transmit-FIFO-full bit. */
#define ARM_UART_DR (*(volatile uint32_t *)0x101f1000u)
#define ARM_UART_FR (*(volatile uint32_t *)0x101f1018u)
#define ARM_UART_TXFF (1u << 5)

/* The system controller's free-running 24 MHz counter. */
#define ARM_SYS_24MHZ (*(volatile uint32_t *)0x1000005cu)

/* Semihosting operations (ARM's semihosting specification), trapped by `svc 0x123456`. */
enum {
    ARM_SYS_OPEN = 0x01,
    ARM_SYS_CLOSE = 0x02,
    ARM_SYS_WRITE = 0x05,
    ARM_SYS_REMOVE = 0x0e,
    ARM_SYS_RENAME = 0x0f,
    ARM_SYS_GET_CMDLINE = 0x15,
    ARM_SYS_EXIT_EXTENDED = 0x20
};
#define ARM_OPEN_WB 5                 /* fopen mode "wb" */
#define ARM_EXIT_APPLICATION 0x20026u /* ADP_Stopped_ApplicationExit */

/* From link.ld. */
extern uint32_t __fb_start[], __data_start[], __data_end[], __bss_start[], __bss_end[];
extern uint32_t __stack_bottom[], __stack_top[];
/* The stack's paint pattern is link.ld's symbol: its address is the value start.S stores. */
extern const char ARM_STACK_PAINT[];
#define ARM_PAINT ((uint32_t)(uintptr_t)ARM_STACK_PAINT)

static int arm_back; /* framebuffer the next frame is drawn into */
static int arm_display_on;

static int arm_semi(uint32_t op, void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register void *r1 __asm__("r1") = arg;
    __asm__ volatile("svc 0x123456" : "+r"(r0) : "r"(r1) : "memory", "lr");
    return (int)r0;
}

static uint32_t arm_strlen(const char *s)
{
    uint32_t n = 0;
    while (s[n])
        n++;
    return n;
}

static void arm_putc(char c)
{
    while (ARM_UART_FR & ARM_UART_TXFF)
        ;
    ARM_UART_DR = (uint32_t)(unsigned char)c;
}

void plat_log(const char *line)
{
    while (*line)
        arm_putc(*line++);
    arm_putc('\n');
}

/* Logs "a" + the file name + "b" as one line. */
static void arm_log_file(const char *a, const char *file, const char *b)
{
    while (*a)
        arm_putc(*a++);
    while (*file)
        arm_putc(*file++);
    plat_log(b);
}

uint64_t plat_time_ns(void)
{
    /* The 32-bit counter wraps every 179 s; frames take far less, so one wrap at most is seen
     * between two calls. */
    static uint32_t last;
    static uint64_t high;
    uint32_t t = ARM_SYS_24MHZ;
    if (t < last)
        high += (uint64_t)1 << 32;
    last = t;
    return (high | t) * 125u / 3u;
}

static uint32_t *arm_buffer(int i) { return __fb_start + (uint32_t)i * ARM_W * ARM_H; }

static void arm_show(const uint32_t *pixels)
{
    ARM_CLCD_UPBASE = (uint32_t)(uintptr_t)pixels;
    if (!arm_display_on) {
        ARM_CLCD_TIMING0 = ((ARM_W / 16) - 1) << 2;
        ARM_CLCD_TIMING1 = ARM_H - 1;
        ARM_CLCD_CONTROL = ARM_CLCD_ON;
        arm_display_on = 1;
    }
}

int plat_frame_acquire(plat_frame *f, int width, int height)
{
    if (width < 1 || height < 1 || width > ARM_W || height > ARM_H) {
        plat_log("error: frames on this board are at most 320x240");
        return -1;
    }
    f->pixels = arm_buffer(arm_back);
    f->width = width;
    f->height = height;
    f->stride = ARM_W;
    return 0;
}

void plat_frame_release(plat_frame *f) { f->pixels = 0; }

/* Writes n bytes to a semihosting handle; 0 when all were written. */
static int arm_write(int fd, const void *buf, uint32_t n)
{
    uint32_t a[3] = {(uint32_t)fd, (uint32_t)(uintptr_t)buf, n};
    return arm_semi(ARM_SYS_WRITE, a) == 0 ? 0 : -1;
}

/* v in decimal at buf; returns the number of digits. */
static uint32_t arm_dec(char *buf, uint32_t v)
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

/* "P6\nW H\n255\n" into buf; returns its length. */
static uint32_t arm_ppm_header(char *buf, int w, int h)
{
    uint32_t n = 0;
    int v[2] = {w, h};
    buf[n++] = 'P';
    buf[n++] = '6';
    for (int i = 0; i < 2; i++) {
        buf[n++] = i ? ' ' : '\n';
        n += arm_dec(buf + n, (uint32_t)v[i]);
    }
    for (const char *s = "\n255\n"; *s; s++)
        buf[n++] = *s;
    return n;
}

static int arm_save_ppm(const plat_frame *f, const char *dest)
{
    static char tmp[160];
    static uint8_t row[ARM_W * 3];
    uint32_t len = arm_strlen(dest);
    if (len + 5 > sizeof tmp) {
        arm_log_file("error: ", dest, ": path too long");
        return -1;
    }
    for (uint32_t i = 0; i < len; i++)
        tmp[i] = dest[i];
    for (uint32_t i = 0; i < 5; i++)
        tmp[len + i] = ".tmp"[i];
    uint32_t open_args[3] = {(uint32_t)(uintptr_t)tmp, ARM_OPEN_WB, len + 4};
    int fd = arm_semi(ARM_SYS_OPEN, open_args);
    if (fd < 0) {
        arm_log_file("error: ", tmp, ": cannot create (semihosting open failed)");
        return -1;
    }
    char head[32];
    int bad = arm_write(fd, head, arm_ppm_header(head, f->width, f->height));
    for (int y = 0; y < f->height && !bad; y++) {
        const uint32_t *p = f->pixels + y * f->stride;
        for (int x = 0; x < f->width; x++) {
            row[3 * x] = (uint8_t)(p[x] >> 16);
            row[3 * x + 1] = (uint8_t)(p[x] >> 8);
            row[3 * x + 2] = (uint8_t)p[x];
        }
        bad = arm_write(fd, row, (uint32_t)f->width * 3);
    }
    uint32_t close_args[1] = {(uint32_t)fd};
    bad |= arm_semi(ARM_SYS_CLOSE, close_args) != 0;
    uint32_t rename_args[4] = {(uint32_t)(uintptr_t)tmp, len + 4, (uint32_t)(uintptr_t)dest, len};
    if (bad || arm_semi(ARM_SYS_RENAME, rename_args) != 0) {
        uint32_t remove_args[2] = {(uint32_t)(uintptr_t)tmp, len + 4};
        arm_semi(ARM_SYS_REMOVE, remove_args);
        arm_log_file("error: ", dest, ": write failed");
        return -1;
    }
    return 0;
}

int plat_frame_present(const plat_frame *f, const char *dest)
{
    arm_show(f->pixels);
    arm_back ^= 1;
    return dest ? arm_save_ppm(f, dest) : 0;
}

/* Bands: the framebuffer holds the whole frame, so a band is a window into it, and the frame is
 * presented once its last row has come. */
static plat_frame arm_band;
static const char *arm_band_dest;
static int arm_band_end; /* the row after the last band's */

int plat_band_begin(plat_frame *f, int width, int height, const char *dest)
{
    if (plat_frame_acquire(&arm_band, width, height) != 0)
        return -1;
    *f = arm_band;
    arm_band_dest = dest;
    arm_band_end = 0;
    return 0;
}

uint32_t *plat_band_rows(int y0, int rows)
{
    arm_band_end = y0 + rows;
    return arm_band.pixels + y0 * arm_band.stride;
}

int plat_band_present(void)
{
    if (arm_band_end < arm_band.height)
        return 0;
    int rc = plat_frame_present(&arm_band, arm_band_dest);
    plat_frame_release(&arm_band);
    return rc;
}

/* Logs "ram: ..." with the bytes of .data, .bss and the deepest stack use seen. */
static int arm_report_ram(void)
{
    const uint32_t *w = __stack_bottom;
    while (w < __stack_top && *w == ARM_PAINT)
        w++;
    uint32_t data = (uint32_t)((__data_end - __data_start) * 4);
    uint32_t bss = (uint32_t)((__bss_end - __bss_start) * 4);
    uint32_t stack = (uint32_t)((__stack_top - w) * 4);
    uint32_t v[4] = {data, bss, stack, data + bss + stack};
    static const char *const names[4] = {"ram: data=", " bss=", " stack_peak=", " total="};
    for (int i = 0; i < 4; i++) {
        for (const char *s = names[i]; *s; s++)
            arm_putc(*s);
        char d[10];
        for (uint32_t k = 0, n = arm_dec(d, v[i]); k < n; k++)
            arm_putc(d[k]);
    }
    plat_log(" bytes");
    if (w == __stack_bottom) {
        plat_log("error: the stack reached the bottom of its reserve (overflow)");
        return 1;
    }
    return 0;
}

static void arm_exit(int status)
{
    uint32_t args[2] = {ARM_EXIT_APPLICATION, (uint32_t)status};
    arm_semi(ARM_SYS_EXIT_EXTENDED, args);
    for (;;)
        ;
}

/* Called by start.S's exception vectors in supervisor mode: logs the exception and where it
 * happened, and ends the run with status 3. */
void arm_fault(uint32_t lr, uint32_t kind);
void arm_fault(uint32_t lr, uint32_t kind)
{
    static const char *const names[8] = {
        "reset", "undefined instruction", "SVC", "prefetch abort", "data abort", "reserved", "IRQ",
        "FIQ"};
    const char *s = "error: CPU exception: ";
    while (*s)
        arm_putc(*s++);
    for (s = names[kind & 7]; *s; s++)
        arm_putc(*s);
    for (s = " (lr=0x"; *s; s++)
        arm_putc(*s);
    for (int i = 28; i >= 0; i -= 4)
        arm_putc("0123456789abcdef"[(lr >> i) & 15]);
    plat_log(")");
    arm_exit(3);
}

/* Called by start.S with a clear .bss and a painted stack. */
void arm_main(void);
void arm_main(void)
{
    static char cmdline[1024];
    static char *argv[128];
    int argc = 0, status = 2;
    uint32_t args[2] = {(uint32_t)(uintptr_t)cmdline, sizeof cmdline};
    if (arm_semi(ARM_SYS_GET_CMDLINE, args) != 0) {
        plat_log("error: the argument list does not fit in 1024 bytes");
        arm_exit(status);
    }
    for (char *s = cmdline; *s;) {
        while (*s == ' ')
            *s++ = '\0';
        if (!*s)
            break;
        if (argc == (int)(sizeof argv / sizeof *argv) - 1) {
            plat_log("error: more than 127 arguments");
            arm_exit(status);
        }
        argv[argc++] = s;
        while (*s && *s != ' ')
            s++;
    }
    argv[argc] = 0;
    status = app_main(argc, argv);
    if (arm_report_ram() != 0 && status == 0)
        status = 1;
    arm_exit(status);
}
