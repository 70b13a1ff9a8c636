/* m0.c: the bare-metal Cortex-M0 backend (QEMU microbit, an nRF51822): UART log, SysTick clock, semihosting files, arguments and exit; bands through platform/band.c with no display.
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
#include "platform.h"

#define M0_REG(a) (*(volatile uint32_t *)(a))

/* UART0 (nRF51). */
#define M0_UART_STARTTX M0_REG(0x40002008u)
#define M0_UART_TXDRDY M0_REG(0x4000211cu)
#define M0_UART_ENABLE M0_REG(0x40002500u)
#define M0_UART_TXD M0_REG(0x4000251cu)
#define M0_UART_BAUDRATE M0_REG(0x40002524u)
#define M0_UART_115200 0x01d7e000u

/* SysTick and the interrupt control register's "SysTick pending" bit. */
#define M0_SYST_CSR M0_REG(0xe000e010u)
#define M0_SYST_RVR M0_REG(0xe000e014u)
#define M0_SYST_CVR M0_REG(0xe000e018u)
#define M0_ICSR M0_REG(0xe000ed04u)
#define M0_PENDSTSET (1u << 26)
#define M0_SYST_MAX 0xffffffu

static volatile uint32_t m0_wraps; /* SysTick periods elapsed */

int board_semi(uint32_t op, void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return (int)r0;
}

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

/* The SysTick exception (start.S's vector table): one more period of 2^24 steps. */
void m0_systick(void);
void m0_systick(void) { m0_wraps++; }

uint64_t plat_time_ns(void)
{
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
    uint32_t wraps = m0_wraps, v = M0_SYST_CVR;
    if (M0_ICSR & M0_PENDSTSET) { /* wrapped, its exception not taken yet */
        v = M0_SYST_CVR;
        wraps++;
    }
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
    uint64_t steps = ((uint64_t)wraps << 24) + (M0_SYST_MAX - v);
    return (steps * 125) >> 1; /* 62.5 ns a step at 16 MHz */
}

/* Called by start.S's m0_trap for any fault or unexpected exception: logs it and where it
 * happened (the stacked pc), and ends the run with status 3. */
void m0_fault(uint32_t pc, uint32_t ipsr);
void m0_fault(uint32_t pc, uint32_t ipsr)
{
    static const char *const names[16] = {"thread", "reset", "NMI",    "HardFault", "4",  "5",
                                          "6",      "7",     "8",      "9",         "10", "SVCall",
                                          "12",     "13",    "PendSV", "SysTick"};
    uint32_t n = ipsr & 0x3f;
    board_fault(n < 16 ? names[n] : "interrupt", "pc", pc);
}

/* Called by start.S with .data copied, .bss clear and the stack painted. */
void m0_main(void);
void m0_main(void)
{
    static char cmdline[256];
    static char *argv[24];
    board_band_init();
    M0_UART_BAUDRATE = M0_UART_115200;
    M0_UART_ENABLE = 4;
    M0_UART_STARTTX = 1;
    /* SysTick on the processor clock, its exception every 2^24 steps (1.05 s). The count reads 0
     * until the first step loads it, which plat_time_ns would take for the end of a period:
     * wait for it. */
    M0_SYST_RVR = M0_SYST_MAX;
    M0_SYST_CVR = 0;
    M0_SYST_CSR = 7;
    while (M0_SYST_CVR == 0)
        ;
    board_run(cmdline, sizeof cmdline, argv, (int)(sizeof argv / sizeof *argv));
}
