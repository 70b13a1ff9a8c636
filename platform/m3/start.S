/* start.S: vector table and reset entry of the Cortex-M3 image: copies .data, clears .bss, paints the stack for the peak-use measurement, calls m3_main; every fault ends the run through m3_fault, the SysTick extends the clock. */
    .syntax unified
    .cpu cortex-m3
    .thumb

    /* The vector table at address 0: the core loads SP and PC from its first two words. */
    .section .vectors, "a"
    .global m3_vectors
m3_vectors:
    .word   __stack_top
    .word   m3_reset
    .word   m3_trap             /* 2 NMI */
    .word   m3_trap             /* 3 HardFault */
    .word   m3_trap             /* 4 MemManage */
    .word   m3_trap             /* 5 BusFault */
    .word   m3_trap             /* 6 UsageFault */
    .word   0, 0, 0, 0
    .word   m3_trap             /* 11 SVCall */
    .word   m3_trap             /* 12 DebugMonitor */
    .word   0
    .word   m3_trap             /* 14 PendSV */
    .word   m3_systick          /* 15 SysTick */
    .rept   64                  /* external interrupts: none is enabled */
    .word   m3_trap
    .endr

    .text
    .global m3_reset
    .type m3_reset, %function
    .thumb_func
m3_reset:
    ldr     r0, =__data_start
    ldr     r1, =__data_end
    ldr     r2, =__data_load
1:  cmp     r0, r1
    itt     lo
    ldrlo   r3, [r2], #4
    strlo   r3, [r0], #4
    blo     1b
    ldr     r0, =__bss_start
    ldr     r1, =__bss_end
    movs    r2, #0
2:  cmp     r0, r1
    it      lo
    strlo   r2, [r0], #4
    blo     2b
    /* Nothing is on the stack yet: every word of it gets the paint; m3.c finds the deepest
     * overwritten one. */
    ldr     r0, =__stack_bottom
    ldr     r1, =__stack_top
    ldr     r2, =BOARD_STACK_PAINT
3:  cmp     r0, r1
    it      lo
    strlo   r2, [r0], #4
    blo     3b
    bl      m3_main
4:  b       4b
    .size m3_reset, . - m3_reset

    /* Any fault or unexpected exception: m3_fault(stacked pc, exception number) logs it and
     * ends the run; it never returns. */
    .type m3_trap, %function
    .thumb_func
m3_trap:
    tst     lr, #4
    ite     eq
    mrseq   r0, msp
    mrsne   r0, psp
    ldr     r0, [r0, #24]
    mrs     r1, ipsr
    ldr     r2, =m3_fault
    bx      r2
    .size m3_trap, . - m3_trap
