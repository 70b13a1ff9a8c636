/* cortexm.S: the Cortex-M boards' vector table and reset entry (platform/m3/, platform/m0/), in Thumb-1 alone so that ARMv6-M runs it too: copies .data, clears .bss, paints the stack for the peak-use measurement, calls board_main; every fault ends the run through cm_fault, the SysTick extends the clock (platform/cortexm.c).
 *
 * CM_IRQS (the Makefile's) is the chip's number of external interrupts, none of them enabled; on
 * ARMv7-M the MemManage, BusFault, UsageFault and DebugMonitor vectors trap too.
 */
    .syntax unified
    .thumb

    /* The vector table at address 0: the core loads SP and PC from its first two words. */
    .section .vectors, "a"
    .global cm_vectors
cm_vectors:
    .word   __stack_top
    .word   cm_reset
    .word   cm_trap             /* 2 NMI */
    .word   cm_trap             /* 3 HardFault (ARMv6-M's only fault) */
#if defined(__ARM_ARCH_7M__)
    .word   cm_trap             /* 4 MemManage */
    .word   cm_trap             /* 5 BusFault */
    .word   cm_trap             /* 6 UsageFault */
#else
    .word   0, 0, 0
#endif
    .word   0, 0, 0, 0
    .word   cm_trap             /* 11 SVCall */
#if defined(__ARM_ARCH_7M__)
    .word   cm_trap             /* 12 DebugMonitor */
#else
    .word   0
#endif
    .word   0
    .word   cm_trap             /* 14 PendSV */
    .word   cm_systick          /* 15 SysTick */
    .rept   CM_IRQS             /* external interrupts: none is enabled */
    .word   cm_trap
    .endr

    .text
    .global cm_reset
    .type cm_reset, %function
    .thumb_func
cm_reset:
    ldr     r0, =__data_start
    ldr     r1, =__data_end
    ldr     r2, =__data_load
1:  cmp     r0, r1
    bhs     2f
    ldm     r2!, {r3}
    stm     r0!, {r3}
    b       1b
2:  ldr     r0, =__bss_start
    ldr     r1, =__bss_end
    movs    r2, #0
3:  cmp     r0, r1
    bhs     4f
    stm     r0!, {r2}
    b       3b
    /* Nothing is on the stack yet: every word of it gets the paint; board.c finds the deepest
     * overwritten one. */
4:  ldr     r0, =__stack_bottom
    ldr     r1, =__stack_top
    ldr     r2, =BOARD_STACK_PAINT
5:  cmp     r0, r1
    bhs     6f
    stm     r0!, {r2}
    b       5b
6:  bl      board_main
7:  b       7b
    .size cm_reset, . - cm_reset

    /* Any fault or unexpected exception: cm_fault(stacked pc, exception number) logs it and
     * ends the run; it never returns. (No IT blocks and no TST immediate on ARMv6-M.) */
    .type cm_trap, %function
    .thumb_func
cm_trap:
    movs    r0, #4
    mov     r1, lr
    tst     r0, r1
    bne     1f
    mrs     r0, msp
    b       2f
1:  mrs     r0, psp
2:  ldr     r0, [r0, #24]
    mrs     r1, ipsr
    ldr     r2, =cm_fault
    bx      r2
    .size cm_trap, . - cm_trap
