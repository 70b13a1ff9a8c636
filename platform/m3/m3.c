/* m3.c: the bare-metal Cortex-M3 backend (QEMU lm3s6965evb): SSD0323 OLED over SSI, bands instead of a frame, UART log, the 50 MHz clock; semihosting, the SysTick and faults from platform/cortexm.c, files, arguments and exit from platform/board.c.
 *
 * The Stellaris LM3S6965 has 64 KiB of SRAM and its evaluation board a 128x64 OLED with 16 grey
 * levels behind an SSD0323 controller, which keeps the picture itself: frames come here band by
 * band (plat_band_*, platform/band.c), each band is turned into grey and sent over the SSI (PL022) bus, and with a
 * file name its colours also go to the host through semihosting. No frame is ever held in RAM.
 * What QEMU's models do (hw/display/ssd0323.c, hw/arm/stellaris.c, hw/ssi/pl022.c): the OLED
 * takes column (0x15) and row (0x75) windows, 64 bytes a row, the left pixel in the high nibble,
 * and ignores geometry and brightness commands; GPIO C7 low = command, high = data; GPIO D0 high
 * selects the OLED (and deselects the SD card); the PL022 stops sending while its receive FIFO is
 * full, so every byte received is read back. The system clock is set to the board's 50 MHz
 * (PLL 200 MHz / 4), 20 ns a SysTick step.
 */
#include <stdint.h>

#include "board.h"
#include "cortexm.h"
#include "platform.h"

#define M3_W 128

#define M3_REG(a) (*(volatile uint32_t *)(a))

/* System control: run-mode clock gating, the clock configuration and the PLL-lock flag. */
#define M3_RIS M3_REG(0x400fe050u)
#define M3_RCC M3_REG(0x400fe060u)
#define M3_RCGC1 M3_REG(0x400fe104u)
#define M3_RCGC2 M3_REG(0x400fe108u)
#define M3_RCC_SYSDIV(n) ((uint32_t)(n) << 23) /* the PLL's 200 MHz / (n + 1) */
#define M3_RCC_SYSDIV_MASK (15u << 23)
#define M3_RCC_USESYSDIV (1u << 22)
#define M3_RCC_PWRDN (1u << 13)
#define M3_RCC_BYPASS (1u << 11)
#define M3_RCC_XTAL_MASK (15u << 6)
#define M3_RCC_XTAL_8MHZ (14u << 6)
#define M3_RCC_OSCSRC_MASK (3u << 4)
#define M3_PLL_LOCKED (1u << 6)

/* GPIO ports (PL061): DATA is addressed through a mask in address bits 9:2. */
#define M3_GPIO_A 0x40004000u
#define M3_GPIO_C 0x40006000u
#define M3_GPIO_D 0x40007000u
#define M3_GPIO_DATA(port, pins) M3_REG((port) + ((uint32_t)(pins) << 2))
#define M3_GPIO_DIR(port) M3_REG((port) + 0x400u)
#define M3_GPIO_AFSEL(port) M3_REG((port) + 0x420u)
#define M3_GPIO_DEN(port) M3_REG((port) + 0x51cu)
#define M3_OLED_DC (1u << 7) /* port C: low command, high data */
#define M3_SD_CS (1u << 0)   /* port D: high keeps the SD card off the bus, the OLED on it */
#define M3_SSI_PINS (1u << 2 | 1u << 3 | 1u << 5) /* port A: clock, frame, transmit */

/* SSI0 (PL022). */
#define M3_SSI_CR0 M3_REG(0x40008000u)
#define M3_SSI_CR1 M3_REG(0x40008004u)
#define M3_SSI_DR M3_REG(0x40008008u)
#define M3_SSI_SR M3_REG(0x4000800cu)
#define M3_SSI_CPSR M3_REG(0x40008010u)
#define M3_SSI_TNF (1u << 1)
#define M3_SSI_RNE (1u << 2)
#define M3_SSI_BSY (1u << 4)

/* UART0 (PL011), 115200 baud at 50 MHz. */
#define M3_UART_DR M3_REG(0x4000c000u)
#define M3_UART_FR M3_REG(0x4000c018u)
#define M3_UART_IBRD M3_REG(0x4000c024u)
#define M3_UART_FBRD M3_REG(0x4000c028u)
#define M3_UART_LCRH M3_REG(0x4000c02cu)
#define M3_UART_CTL M3_REG(0x4000c030u)
#define M3_UART_TXFF (1u << 5)

void board_putc(char c)
{
    while (M3_UART_FR & M3_UART_TXFF)
        ;
    M3_UART_DR = (uint32_t)(unsigned char)c;
}

/* ---- the OLED ------------------------------------------------------------------------------ */

/* Waits until the bus is idle, reading back what the controller returned. */
static void m3_ssi_drain(void)
{
    while (M3_SSI_SR & (M3_SSI_BSY | M3_SSI_RNE))
        (void)M3_SSI_DR;
}

static void m3_ssi_put(uint32_t byte)
{
    while (!(M3_SSI_SR & M3_SSI_TNF))
        ;
    M3_SSI_DR = byte;
    while (M3_SSI_SR & M3_SSI_RNE)
        (void)M3_SSI_DR;
}

/* Sends n bytes as commands (data 0) or pixel data (data 1). */
static void m3_oled_send(const uint8_t *b, int n, int data)
{
    m3_ssi_drain();
    M3_GPIO_DATA(M3_GPIO_C, M3_OLED_DC) = data ? M3_OLED_DC : 0;
    for (int i = 0; i < n; i++)
        m3_ssi_put(b[i]);
    m3_ssi_drain();
}

static void m3_oled_init(void)
{
    /* display off, horizontal address increment (remap: COM split and remap), contrast,
     * normal display, display on */
    static const uint8_t init[] = {0xae, 0xa0, 0x50, 0x81, 0x70, 0xa4, 0xaf};
    m3_oled_send(init, (int)sizeof init, 0);
}

/* Rows y0 .. y0 + rows - 1 of the band buffer to the OLED, each pixel at 4 bits of grey. */
static void m3_oled_rows(const uint32_t *px, int stride, int y0, int rows)
{
    const uint8_t window[6] = {0x15, 0, M3_W / 2 - 1, 0x75, (uint8_t)y0, (uint8_t)(y0 + rows - 1)};
    m3_oled_send(window, 6, 0);
    uint8_t line[M3_W / 2];
    for (int y = 0; y < rows; y++) {
        const uint32_t *p = px + y * stride;
        for (int i = 0; i < M3_W / 2; i++)
            line[i] = (uint8_t)(plat_grey4(p[2 * i]) << 4 | plat_grey4(p[2 * i + 1]));
        m3_oled_send(line, M3_W / 2, 1);
    }
}

/* ---- bands (platform/band.c) --------------------------------------------------------------- */

/* The band on the OLED when the frame is the display's width. */
void board_band_show(const uint32_t *px, int stride, int width, int y0, int rows)
{
    if (width == M3_W)
        m3_oled_rows(px, stride, y0, rows);
}

/* ---- start-up, the end of a run ------------------------------------------------------------ */

/* 50 MHz from the PLL (8 MHz crystal, 200 MHz / 4), the way the chip's manual orders it. */
static void m3_clock_init(void)
{
    uint32_t rcc = (M3_RCC | M3_RCC_BYPASS) & ~M3_RCC_USESYSDIV;
    M3_RCC = rcc;
    rcc = (rcc & ~(M3_RCC_XTAL_MASK | M3_RCC_OSCSRC_MASK | M3_RCC_PWRDN)) | M3_RCC_XTAL_8MHZ;
    M3_RCC = rcc;
    rcc = (rcc & ~M3_RCC_SYSDIV_MASK) | M3_RCC_SYSDIV(3) | M3_RCC_USESYSDIV;
    M3_RCC = rcc;
    for (int i = 0; i < 100000 && !(M3_RIS & M3_PLL_LOCKED); i++)
        ;
    M3_RCC = rcc & ~M3_RCC_BYPASS;
    cm_clock_start(); /* the SysTick at 50 MHz, a period of 2^24 steps 0.34 s */
}

static void m3_io_init(void)
{
    M3_RCGC1 |= 1u << 0 | 1u << 4;           /* UART0, SSI0 */
    M3_RCGC2 |= 1u << 0 | 1u << 2 | 1u << 3; /* GPIO ports A, C, D */
    M3_UART_CTL = 0;
    M3_UART_IBRD = 27; /* 50 MHz / (16 x 115200) = 27 + 8/64 */
    M3_UART_FBRD = 8;
    M3_UART_LCRH = 3u << 5 | 1u << 4; /* 8 bits, FIFOs */
    M3_UART_CTL = 1u << 0 | 1u << 8 | 1u << 9;
    M3_GPIO_AFSEL(M3_GPIO_A) |= M3_SSI_PINS;
    M3_GPIO_DEN(M3_GPIO_A) |= M3_SSI_PINS;
    M3_GPIO_DIR(M3_GPIO_C) |= M3_OLED_DC;
    M3_GPIO_DEN(M3_GPIO_C) |= M3_OLED_DC;
    M3_GPIO_DATA(M3_GPIO_D, M3_SD_CS) = M3_SD_CS;
    M3_GPIO_DIR(M3_GPIO_D) |= M3_SD_CS;
    M3_GPIO_DEN(M3_GPIO_D) |= M3_SD_CS;
    /* SSI: SPI frames of 8 bits, clock idle high, data on the second edge (mode 3),
     * 50 MHz / (2 x 8) = 3.125 MHz. */
    M3_SSI_CR1 = 0;
    M3_SSI_CPSR = 2;
    M3_SSI_CR0 = 7u << 8 | 1u << 7 | 1u << 6 | 7u;
    M3_SSI_CR1 = 1u << 1;
    m3_oled_init();
}

/* Called by platform/cortexm.S with .data copied, .bss clear and the stack painted. */
void board_main(void)
{
    static char cmdline[256];
    static char *argv[24];
    board_band_init();
    m3_clock_init();
    m3_io_init();
    board_run(cmdline, sizeof cmdline, argv, (int)(sizeof argv / sizeof *argv));
}
