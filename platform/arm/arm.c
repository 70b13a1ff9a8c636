/* arm.c: the bare-metal ARM926 backend (QEMU versatilepb): PL110 framebuffer, PL011 UART, 24 MHz counter; files, arguments and exit through board.c.
 *
 * Register addresses and QEMU's quirks are those of ../shared/docs/platform-facts.md. The image
 * runs from RAM at 64 KiB (link.ld); the two framebuffers sit at 1 MiB, outside the program's
 * RAM budget. Nothing here needs interrupts: the UART and the counter are polled.
 */
#include <stdint.h>

#include "board.h"
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

/* From link.ld. */
extern uint32_t __fb_start[];

static int arm_back; /* framebuffer the next frame is drawn into */
static int arm_display_on;

/* ARM code in this Thumb file (ARM_COLD_SRCS): the semihosting call is ARM's SVC 0x123456. */
__attribute__((target("arm"))) int board_semi(uint32_t op, void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register void *r1 __asm__("r1") = arg;
    __asm__ volatile("svc 0x123456" : "+r"(r0) : "r"(r1) : "memory", "lr");
    return (int)r0;
}

void board_putc(char c)
{
    while (ARM_UART_FR & ARM_UART_TXFF)
        ;
    ARM_UART_DR = (uint32_t)(unsigned char)c;
}

/* ARM code at -O2 in this Thumb file, as the rendering that runs between its two reads of a
 * frame (the count of a frame takes in part of each call). */
__attribute__((target("arm"), optimize("O2"))) uint64_t plat_time_ns(void)
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

static int arm_save_ppm(const plat_frame *f, const char *dest)
{
    static board_file file;
    static uint8_t row[ARM_W * 3];
    if (board_file_open(&file, dest, f->width, f->height) != 0)
        return -1;
    int bad = 0;
    for (int y = 0; y < f->height && !bad; y++) {
        const uint32_t *p = f->pixels + y * f->stride;
        for (int x = 0; x < f->width; x++) {
            row[3 * x] = (uint8_t)(p[x] >> 16);
            row[3 * x + 1] = (uint8_t)(p[x] >> 8);
            row[3 * x + 2] = (uint8_t)p[x];
        }
        bad = board_file_write(&file, row, (uint32_t)f->width * 3);
    }
    return board_file_end(&file, !bad);
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

/* Called by start.S's exception vectors in supervisor mode: logs the exception and where it
 * happened, and ends the run with status 3. */
void arm_fault(uint32_t lr, uint32_t kind);
void arm_fault(uint32_t lr, uint32_t kind)
{
    static const char *const names[8] = {
        "reset", "undefined instruction", "SVC", "prefetch abort", "data abort", "reserved", "IRQ",
        "FIQ"};
    board_fault(names[kind & 7], "lr", lr);
}

/* Called by start.S with a clear .bss and a painted stack. */
void arm_main(void);
void arm_main(void)
{
    static char cmdline[1024];
    static char *argv[128];
    board_run(cmdline, sizeof cmdline, argv, (int)(sizeof argv / sizeof *argv));
}
