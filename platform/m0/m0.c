/* m0.c: the bare-metal Cortex-M0 backend (QEMU microbit, an nRF51822): its UART log; semihosting, the SysTick clock and faults from platform/cortexm.c, files, arguments and exit from platform/board.c, bands through platform/band.c with no display.
 *
 * The nRF51822 is an ARMv6-M core (no long multiply, no divide, no CLZ, Thumb-1 with a few 32-bit
 * encodings) with 256 KiB of flash and 16 KiB of SRAM, at 16 MHz. QEMU's board has no display:
 * frames leave band by band through semihosting only (platform/band.c), no frame is ever in RAM.
 * What QEMU's models do (hw/char/nrf51_uart.c, hw/arm/nrf51_soc.c): the UART sends a byte
 * written to TXD once it is enabled (ENABLE = 4) and its transmitter started (TASKS_STARTTX),
 * then raises EVENTS_TXDRDY; the core's SysTick runs on the 16 MHz system clock, 62.5 ns a step.
 */
#include <stdint.h>

#include "board.h"
#include "cortexm.h"
#include "platform.h"

#define M0_REG(a) (*(volatile uint32_t *)(a))

/* UART0 (nRF51). */
#define M0_UART_STARTTX M0_REG(0x40002008u)
#define M0_UART_TXDRDY M0_REG(0x4000211cu)
#define M0_UART_ENABLE M0_REG(0x40002500u)
#define M0_UART_TXD M0_REG(0x4000251cu)
#define M0_UART_BAUDRATE M0_REG(0x40002524u)
#define M0_UART_115200 0x01d7e000u

void board_putc(char c)
{
    M0_UART_TXDRDY = 0;
    M0_UART_TXD = (uint32_t)(unsigned char)c;
    while (!M0_UART_TXDRDY)
        ;
}

/* No display: the bands go only to the file (platform/band.c). */
void board_band_show(const uint32_t *px, int stride, int width, int y0, int rows)
{
    (void)px, (void)stride, (void)width, (void)y0, (void)rows;
}

/* Called by platform/cortexm.S with .data copied, .bss clear and the stack painted. */
void board_main(void)
{
    static char cmdline[256];
    static char *argv[24];
    board_band_init();
    M0_UART_BAUDRATE = M0_UART_115200;
    M0_UART_ENABLE = 4;
    M0_UART_STARTTX = 1;
    cm_clock_start(); /* the SysTick at 16 MHz, a period of 2^24 steps 1.05 s */
    board_run(cmdline, sizeof cmdline, argv, (int)(sizeof argv / sizeof *argv));
}
