/* fx_armv6m.h: the numeric layer's 32 x 32 -> 64-bit products on ARMv6-M (Cortex-M0/M0+), which has no long multiply (SMULL, UMULL): formed from four 16 x 16 -> 32-bit MULS, inline, with the same bits as the C product.
 *
 * Included by real_fixed.h on ARMv6-M only, where FX_SMUL and FX_UMUL are these functions (elsewhere
 * the compiler's own 64-bit products); tests/test_numeric.c checks them against those on the host. Without it GCC calls libgcc's general 64 x 64-bit multiply (__aeabi_lmul, about
 * 41 instructions, plus the call and the operands' sign words) for every (int64_t)a * b. With a =
 * ah 2^16 + al and b = bh 2^16 + bl (al, bl in [0, 2^16), ah, bh their high halves, signed or
 * not as the product is): a b = ah bh 2^32 + (ah bl + al bh) 2^16 + al bl; each of the four
 * partial products fits 32 bits, and the middle two are added into the 64-bit sum one at a time
 * (their sum can need 33 bits). The divisions and square roots need nothing here: fx.c forms
 * them from these products (fx_udiv64, fx_isqrt64; FX_SOFT_DIVIDE is on where there is no
 * divider), and GCC's __builtin_clz becomes a call of libgcc's __clzsi2 on ARMv6-M (no CLZ
 * instruction; about 19 instructions, 2% of a frame).
 */
#ifndef FIXRAY_FX_ARMV6M_H
#define FIXRAY_FX_ARMV6M_H

#include <stdint.h>

/* a b for 32-bit signed a and b, exactly. Each middle product m enters as the 64-bit m 2^16:
 * its words m >> 16 (arithmetic) and m << 16, one ADDS and one ADCS. */
static inline __attribute__((always_inline)) int64_t fx_v6m_smul(int32_t a, int32_t b)
{
    const int32_t ah = a >> 16, bh = b >> 16; /* arithmetic: a = ah 2^16 + al */
    const uint32_t al = (uint32_t)a & 0xffffu, bl = (uint32_t)b & 0xffffu;
    const int32_t m1 = ah * (int32_t)bl, m2 = (int32_t)al * bh;   /* |m| < 2^31 */
    uint64_t r = (uint64_t)(uint32_t)(ah * bh) << 32 | (al * bl); /* |ah bh| <= 2^30 */
    r += (uint64_t)(uint32_t)(m1 >> 16) << 32 | (uint32_t)m1 << 16;
    r += (uint64_t)(uint32_t)(m2 >> 16) << 32 | (uint32_t)m2 << 16;
    return (int64_t)r; /* the two's complement of the product (GCC converts modulo 2^64) */
}

/* a b for 32-bit unsigned a and b, exactly. */
static inline __attribute__((always_inline)) uint64_t fx_v6m_umul(uint32_t a, uint32_t b)
{
    const uint32_t ah = a >> 16, bh = b >> 16, al = a & 0xffffu, bl = b & 0xffffu;
    const uint32_t m1 = ah * bl, m2 = al * bh; /* each below 2^32 */
    uint64_t r = (uint64_t)(ah * bh) << 32 | al * bl;
    r += (uint64_t)(m1 >> 16) << 32 | m1 << 16;
    r += (uint64_t)(m2 >> 16) << 32 | m2 << 16;
    return r;
}

#endif
