/* cortexm.h: the Cortex-M boards' SysTick (platform/cortexm.c, the boards' start-up): its registers, and its start inline in each board's. */
#ifndef FIXRAY_CORTEXM_H
#define FIXRAY_CORTEXM_H

#include <stdint.h>

#define CM_REG(a) (*(volatile uint32_t *)(a))

/* SysTick and the interrupt control register's "SysTick pending" bit. */
#define CM_SYST_CSR CM_REG(0xe000e010u)
#define CM_SYST_RVR CM_REG(0xe000e014u)
#define CM_SYST_CVR CM_REG(0xe000e018u)
#define CM_ICSR CM_REG(0xe000ed04u)
#define CM_PENDSTSET (1u << 26)
#define CM_SYST_MAX 0xffffffu

/* Starts the SysTick on the processor clock, its exception every 2^24 steps (cortexm.c's
 * plat_time_ns counts them). */
static inline void cm_clock_start(void)
{
    CM_SYST_RVR = CM_SYST_MAX;
    CM_SYST_CVR = 0;
    CM_SYST_CSR = 7;
    /* The count reads 0 until the first step loads it, which plat_time_ns would take for the
     * end of a period: wait for it. */
    while (CM_SYST_CVR == 0)
        ;
}

#endif
