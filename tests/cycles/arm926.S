/* arm926.S: small ARM926 programs whose cycles are counted by hand in tests/cycles.sh (one per CASE_*, chosen with -D). */
/* Each runs its timed part between t_start and t_stop (the plugin's window), then exits through
 * semihosting. The data they read is the word at `self`, which holds its own address. */
        .syntax unified
        .arm
        .global _start, t_start, t_stop
        .text
_start:
        ldr     sp, =0x00200000
        ldr     r0, =self
        mov     r2, #3
        mov     r3, #0
        mov     r5, #0
        ldr     r6, =buf
        mov     r7, #4096
        mov     r8, #0
#if defined(CASE_THUMB)
        ldr     r0, =t_start + 1        /* into Thumb state */
        bx      r0
        .thumb
        .balign 32
t_start:
        push    {r4-r7, lr}             /* 5 */
        pop     {r4-r7}                 /* 4 */
        pop     {r1}                    /* one register: 2 */
        movs    r0, #20                 /* 1 */
1:      subs    r0, #1                  /* 20 x 1 */
        bne     1b                      /* 19 x 3 taken, 1 not */
        ldr     r1, [r6]                /* 1 */
        adds    r2, r1, r1              /* 1 + 1: the word loaded just before */
        ldrb    r1, [r6]                /* 1 */
        adds    r2, r1, r1              /* 1 + 2: the byte loaded just before */
        bl      t_sub                   /* the BL pair, run as one: 1 + 3 */
t_stop:
        movs    r0, #0x18               /* SYS_EXIT, from Thumb state */
        ldr     r1, =0x20026
        svc     0xab
        b       .
t_sub:  bx      lr                      /* 3 */
        .ltorg
        .arm
#else
        b       t_start
        .balign 32
t_start:
#endif
#if defined(CASE_THUMB)
#elif defined(CASE_LDCHAIN)
        /* 32 loads, each using the one before as its address: 1 cycle + 1 interlock, the last
         * without the interlock (its user lies outside the window) */
        .rept   32
        ldr     r0, [r0]
        .endr
#elif defined(CASE_LDBYTE)
        /* a byte load used by the next instruction: 2 interlock cycles; by the one after: 1 */
        .rept   8
        ldrb    r1, [r0]
        add     r3, r1, r3
        .endr
        .rept   8
        ldrb    r1, [r0]
        mov     r4, r5
        add     r3, r1, r3
        .endr
#elif defined(CASE_MUL)
        /* MUL: 2 cycles, its result one cycle late for the next instruction */
        .rept   16
        mul     r0, r2, r0
        .endr
#elif defined(CASE_SMULL)
        /* SMULL: 3 cycles, its result one cycle late for the next instruction */
        .rept   16
        smull   r0, r1, r2, r0
        .endr
#elif defined(CASE_LOOP)
        /* 50 rounds: SUBS 1 cycle, BNE taken 3, not taken 1 */
        mov     r0, #50
1:      subs    r0, r0, #1
        bne     1b
#elif defined(CASE_LDMSTM)
        ldmia   r6, {r1-r4}             /* 4 */
        stmia   r6, {r5, r7-r12}        /* 7 */
        ldmia   r6, {r1}                /* 2 (one register: 2) */
        stmia   r6, {r1, r2}            /* 2: r1 is ready */
        ldmia   r6, {r1-r3}             /* 3 */
        add     r4, r3, r3              /* 1 + 1: r3, the third loaded, arrives a cycle late */
        push    {r4-r11, lr}            /* 9 */
        pop     {r4-r11, lr}            /* 9 */
#elif defined(CASE_WALK)
        /* read one word a line, WALK_LINES lines from buf, stride WALK_STRIDE bytes, twice */
        mov     r0, r6
        ldr     r2, =WALK_LINES
1:      ldr     r1, [r0], WALK_STRIDE
        subs    r2, r2, #1
        bne     1b
        mov     r0, r6
        ldr     r2, =WALK_LINES
2:      ldr     r1, [r0], WALK_STRIDE
        subs    r2, r2, #1
        bne     2b
#else
#error "no CASE_ given"
#endif
#if !defined(CASE_THUMB)
t_stop:
        mov     r0, #0x18               /* SYS_EXIT */
        ldr     r1, =0x20026            /* ADP_Stopped_ApplicationExit */
        svc     0x123456
        b       .
#endif
        .ltorg
        .data
        .balign 4
self:   .word   self
        .bss
        .balign 4096
buf:    .space  65536
