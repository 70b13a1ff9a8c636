/* m0.S: small Cortex-M0 (ARMv6-M) programs whose cycles are counted by hand in tests/cycles.sh (one per CASE_*, chosen with -D). */
/* The vector table's reset entry runs the timed part between t_start and t_stop (the plugin's
 * window), then exits through semihosting (BKPT 0xAB). Thumb-1 only: no IT, no 32-bit encodings
 * but BL. */
        .syntax unified
        .cpu    cortex-m0
        .thumb
        .global _start, t_start, t_stop
        .section .vectors, "a"
        .word   0x20004000
        .word   _start + 1
        .text
        .thumb_func
_start:
        ldr     r0, =self
        movs    r2, #3
        ldr     r6, =buf
        movs    r5, #0
        b       t_start
        .balign 4
t_start:
#if defined(CASE_LDCHAIN)
        /* each load's address is the load before's value: 2 cycles each */
        .rept   32
        ldr     r0, [r0]
        .endr
#elif defined(CASE_LDINDEP)
        /* independent loads: 2 cycles each as well (the M0 pipelines no neighbouring loads) */
        .rept   32
        ldr     r1, [r0]
        .endr
#elif defined(CASE_MULS)
        /* MULS: the muls option, 1 (the single-cycle multiplier) by default */
        .rept   16
        muls    r0, r2, r0
        .endr
#elif defined(CASE_LOOP)
        /* 50 rounds: SUBS 1 cycle, BNE taken 3, not taken 1 */
        movs    r0, #50
1:      subs    r0, r0, #1
        bne     1b
#elif defined(CASE_LDMSTM)
        push    {r4-r7, lr}             /* 1 + 5 */
        pop     {r4-r7}                 /* 1 + 4 */
        pop     {r1}                    /* 1 + 1 */
        ldmia   r6!, {r1-r3}            /* 1 + 3 */
        stmia   r6!, {r1-r3}            /* 1 + 3 */
#elif defined(CASE_CALLS)
        bl      t_sub                   /* 4 */
        bl      t_leaf                  /* 4 */
        b       t_stop                  /* 3 */
t_sub:  push    {r4, lr}                /* 1 + 2 */
        pop     {r4, pc}                /* 4 + 2 */
t_leaf: bx      lr                      /* 3 */
#else
#error "no CASE_ given"
#endif
t_stop:
        movs    r0, #0x18               /* SYS_EXIT */
        ldr     r1, =0x20026
        bkpt    0xab
        b       .
        .ltorg
        .data
        .balign 4
self:   .word   self
        .bss
        .balign 4
buf:    .space  64
