/* start.S: reset entry of the ARM926 image: sets the stack, clears .bss, paints the stack for the peak-use measurement, calls arm_main. */
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
    ldr     r2, =ARM_STACK_PAINT
2:  cmp     r0, r1
    strlo   r2, [r0], #4
    blo     2b
    bl      arm_main
3:  b       3b
    .size _start, . - _start
