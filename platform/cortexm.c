/* cortexm.c: what the Cortex-M boards (platform/m3/, platform/m0/) share: semihosting through bkpt, the SysTick clock, the fault report (the C half of platform/cortexm.S).
 *
 * The SysTick runs on the processor clock, CM_SYSTICK_HZ (the Makefile's: 50 MHz on the M3 board,
 * 16 MHz on the M0's), its exception every 2^24 steps extending the count.
 */
#include <stdint.h>

#include "board.h"
#include "cortexm.h"
#include "platform.h"

/* Twice a step's nanoseconds, a whole number at both boards' clocks (40 and 125). */
#define CM_STEP_NS2 (2000000000u / CM_SYSTICK_HZ)
_Static_assert(2000000000u % CM_SYSTICK_HZ == 0, "a SysTick step must be a whole half-nanosecond");

static volatile uint32_t cm_wraps; /* SysTick periods elapsed */

int board_semi(uint32_t op, void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return (int)r0;
}

/* The SysTick exception (cortexm.S's vector table): one more period of 2^24 steps. */
void cm_systick(void);
void cm_systick(void) { cm_wraps++; }

uint64_t plat_time_ns(void)
{
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
    uint32_t wraps = cm_wraps, v = CM_SYST_CVR;
    if (CM_ICSR & CM_PENDSTSET) { /* wrapped, its exception not taken yet */
        v = CM_SYST_CVR;
        wraps++;
    }
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
    uint64_t steps = ((uint64_t)wraps << 24) + (CM_SYST_MAX - v);
#if CM_STEP_NS2 % 2 == 0
    return steps * (CM_STEP_NS2 / 2);
#else
    return (steps * CM_STEP_NS2) >> 1;
#endif
}

/* ARMv7-M's own faults' names; ARMv6-M never raises them. */
#if defined(__ARM_ARCH_7M__)
#define CM_V7M_NAME(name, number) name
#else
#define CM_V7M_NAME(name, number) number
#endif

/* Called by cortexm.S's cm_trap for any fault or unexpected exception: logs it and where it
 * happened (the stacked pc), and ends the run with status 3. */
void cm_fault(uint32_t pc, uint32_t ipsr);
void cm_fault(uint32_t pc, uint32_t ipsr)
{
    static const char *const names[16] = {"thread",
                                          "reset",
                                          "NMI",
                                          "HardFault",
                                          CM_V7M_NAME("MemManage", "4"),
                                          CM_V7M_NAME("BusFault", "5"),
                                          CM_V7M_NAME("UsageFault", "6"),
                                          "7",
                                          "8",
                                          "9",
                                          "10",
                                          "SVCall",
                                          CM_V7M_NAME("DebugMon", "12"),
                                          "13",
                                          "PendSV",
                                          "SysTick"};
    uint32_t n = ipsr & 0x1ff;
    board_fault(n < 16 ? names[n] : "interrupt", "pc", pc);
}
