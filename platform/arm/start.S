/* start.S: reset entry and exception vectors of the ARM926 image: sets the stack, clears .bss, paints the stack for the peak-use measurement, calls arm_main; a CPU exception ends the run through arm_fault. */
    .syntax unified
    .arm
    .section .text.start, "ax"
    .global _start
    .type _start, %function
_start:
    /* QEMU starts the ELF at its entry point in SVC mode, MMU and interrupts off. */
    ldr     sp, =__stack_top
    ldr     r0, =__bss_start
    ldr     r1, =__bss_end
    mov     r2, #0
1:  cmp     r0, r1
    strlo   r2, [r0], #4
    blo     1b
    /* Every word of the stack gets the paint pattern; arm_main finds the deepest overwritten one. */
    ldr     r0, =__stack_bottom
    ldr     r1, =__stack_top
    ldr     r2, =BOARD_STACK_PAINT
2:  cmp     r0, r1
    strlo   r2, [r0], #4
    blo     2b
    bl      arm_main
3:  b       3b
    .size _start, . - _start

    /* The exception vectors, linked at address 0. Without them a fault would run the zeroed
     * RAM below the program as no-ops into _start and restart the run forever. */
    .section .vectors, "ax"
    .global arm_vectors
arm_vectors:
    b       _start
    b       1f                  /* undefined instruction */
    b       2f                  /* SVC (semihosting's svc is taken by QEMU before this) */
    b       3f                  /* prefetch abort */
    b       4f                  /* data abort */
    b       5f                  /* reserved */
    b       6f                  /* IRQ (never enabled) */
    b       7f                  /* FIQ (never enabled) */
1:  mov     r1, #1
    b       8f
2:  mov     r1, #2
    b       8f
3:  mov     r1, #3
    b       8f
4:  mov     r1, #4
    b       8f
5:  mov     r1, #5
    b       8f
6:  mov     r1, #6
    b       8f
7:  mov     r1, #7
8:  mov     r0, lr              /* where it happened (plus 4 or 8) */
    msr     cpsr_c, #0xd3       /* back to supervisor mode, interrupts off: its stack is valid */
    ldr     r2, =arm_fault
    bx      r2                  /* arm_fault(lr, kind) logs and exits; it never returns */
