/* start.S: vector table and reset entry of the Cortex-M0 image (ARMv6-M, Thumb-1 only): copies .data, clears .bss, paints the stack for the peak-use measurement, calls m0_main; every fault ends the run through m0_fault, the SysTick extends the clock. */
    .syntax unified
    .cpu cortex-m0
    .thumb

    /* The vector table at address 0: the core loads SP and PC from its first two words. */
    .section .vectors, "a"
    .global m0_vectors
m0_vectors:
    .word   __stack_top
    .word   m0_reset
    .word   m0_trap             /* 2 NMI */
    .word   m0_trap             /* 3 HardFault: ARMv6-M's only fault */
    .word   0, 0, 0, 0, 0, 0, 0
    .word   m0_trap             /* 11 SVCall */
    .word   0, 0
    .word   m0_trap             /* 14 PendSV */
    .word   m0_systick          /* 15 SysTick */
    .rept   32                  /* external interrupts: none is enabled */
    .word   m0_trap
    .endr

    .text
    .global m0_reset
    .type m0_reset, %function
    .thumb_func
m0_reset:
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
6:  bl      m0_main
7:  b       7b
    .size m0_reset, . - m0_reset

    /* Any fault or unexpected exception: m0_fault(stacked pc, exception number) logs it and
     * ends the run; it never returns. (No IT blocks and no TST immediate on ARMv6-M.) */
    .type m0_trap, %function
    .thumb_func
m0_trap:
    movs    r0, #4
    mov     r1, lr
    tst     r0, r1
    bne     1f
    mrs     r0, msp
    b       2f
1:  mrs     r0, psp
2:  ldr     r0, [r0, #24]
    mrs     r1, ipsr
    ldr     r2, =m0_fault
    bx      r2
    .size m0_trap, . - m0_trap
