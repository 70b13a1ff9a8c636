/* qemu_profile.c: a QEMU TCG plugin that counts guest instructions and estimates their cycles (ARM926EJ-S, Cortex-M3 or Cortex-M0 timing tables, ARM926 caches), per address, per frame and in all.
 *
 * Loaded by platform/arm/qemu.sh, platform/m3/qemu.sh and platform/m0/qemu.sh (frames, bench) and
 * platform/arm/profile.sh (make qemu-profile) into qemu-system-arm 7.2 with
 *   -plugin build/arm/qemu_profile.so,out=FILE[,cpu=arm926|m3|m0][,start=ADDR,stop=ADDR][,frame=ADDR]
 *           [,icache=BYTES][,dcache=BYTES][,ways=N][,line=BYTES][,repl=rr|lru|random]
 *           [,imiss=CYCLES][,dmiss=CYCLES][,refill=CYCLES][,lmul=CYCLES][,div=CYCLES][,muls=CYCLES]
 * Every executed instruction is charged the cycles of its class in the core's timing table
 * (docs/arm.md, docs/m3.md and docs/m0.md, section "Cycle model", give the tables and their
 * sources). The
 * plugin sees each instruction's bytes when QEMU translates it and, when it runs, which
 * instruction runs next and how many memory accesses it made: that settles taken or not taken
 * for branches, whether a conditional load or store executed, and (ARM926) the load-use and
 * multiply-result interlocks through a scoreboard of when each register's value is ready. On
 * the ARM926 every fetch looks up an I-cache and every data access a D-cache; a read miss adds
 * the line fill's cycles (the caches allocate on reads only, as the ARM926's do).
 *
 * The counting window opens at the instruction at `start` (the entry of rt_render_band_into)
 * and closes at the next instruction at `stop` (the entry of plat_time_ns, which the board
 * calls right after rendering a band). `frame` (the entry of plat_band_begin, called once a
 * frame before its bands) closes the frame's record: the windows' instructions and cycles since
 * the previous one. At exit FILE gets summary lines (`cpu`, `windows`, `window_total`,
 * `window_cycles`, `window_dmiss`, `window_imiss`, `run_total`, `run_cycles`), one line
 * `frame INSTRUCTIONS CYCLES DMISSES IMISSES` per frame, and one line
 * `a ADDR COUNT CYCLES DMISSES` (hexadecimal address, decimal figures) per address executed inside
 * a window. Without start/stop the whole run is one window. Addresses from 0 to 16 MiB are counted
 * one by one (the boards' RAM and flash, where the images run); anything above goes into one bucket
 * reported as address ffffffff. Everything is a function of the executed instruction stream,
 * which -icount makes the same run to run: the figures repeat exactly.
 *
 * QEMU ships no qemu-plugin.h in Debian: the few types and functions of the plugin API
 * (version 1, the version of QEMU 7.2) that this file uses are declared below. The two names
 * QEMU looks up, qemu_plugin_version and qemu_plugin_install, are the API's, not ours.
 */
#include <inttypes.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the plugin API, version 1 (QEMU 7.2), as far as used here ---------------------------- */
typedef uint64_t qemu_plugin_id_t;
typedef struct qemu_info_t {
    const char *target_name;
    struct {
        int min;
        int cur;
    } version;
    bool system_emulation;
    union {
        struct {
            int smp_vcpus;
            int max_vcpus;
        } system;
    };
} qemu_info_t;
struct qemu_plugin_tb;
struct qemu_plugin_insn;
typedef uint32_t qemu_plugin_meminfo_t;
enum qemu_plugin_cb_flags { QEMU_PLUGIN_CB_NO_REGS, QEMU_PLUGIN_CB_R_REGS, QEMU_PLUGIN_CB_RW_REGS };
enum qemu_plugin_mem_rw { QEMU_PLUGIN_MEM_R = 1, QEMU_PLUGIN_MEM_W, QEMU_PLUGIN_MEM_RW };
typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);
typedef void (*qemu_plugin_vcpu_udata_cb_t)(unsigned int vcpu_index, void *userdata);
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);
typedef void (*qemu_plugin_vcpu_mem_cb_t)(unsigned int vcpu_index, qemu_plugin_meminfo_t info,
                                          uint64_t vaddr, void *userdata);
void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
void qemu_plugin_register_vcpu_insn_exec_cb(struct qemu_plugin_insn *insn,
                                            qemu_plugin_vcpu_udata_cb_t cb,
                                            enum qemu_plugin_cb_flags flags, void *userdata);
void qemu_plugin_register_vcpu_mem_cb(struct qemu_plugin_insn *insn, qemu_plugin_vcpu_mem_cb_t cb,
                                      enum qemu_plugin_cb_flags flags, enum qemu_plugin_mem_rw rw,
                                      void *userdata);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb, void *userdata);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
const void *qemu_plugin_insn_data(const struct qemu_plugin_insn *insn);
size_t qemu_plugin_insn_size(const struct qemu_plugin_insn *insn);
bool qemu_plugin_mem_is_store(qemu_plugin_meminfo_t info);

__attribute__((visibility("default"))) int qemu_plugin_version = 1;
__attribute__((visibility("default"))) int qemu_plugin_install(qemu_plugin_id_t id,
                                                               const qemu_info_t *info, int argc,
                                                               char **argv);

/* ---- what the timing tables need of one instruction, decoded at translation ------------ */
enum { CPU_ARM926, CPU_M3, CPU_M0 };

/* kinds */
#define K_BRANCH 1u /* may change the flow: taken when the next address is not the next insn */
#define K_MEM 2u    /* a load or store: no access made means its condition failed */
#define K_LOAD1 4u  /* M3: a single load (LDR, LDRB, LDRH ...): a following load/store pipelines */
#define K_STORE1 8u /* M3: a single store */

typedef struct cyc_insn {
    uint64_t addr;
    uint32_t slot;
    uint8_t size;
    uint8_t kind;
    uint8_t base;    /* cycles when executed and not taken */
    uint8_t taken;   /* cycles when a K_BRANCH one is taken */
    uint16_t reads;  /* registers read at issue (interlocks, M3 address dependence) */
    uint16_t late;   /* registers whose value is ready `lat` cycles after issue */
    uint8_t lat;     /* ARM926: cycles from issue to the late registers' readiness */
    uint8_t lat_seq; /* ARM926 LDM: the k-th loaded register is ready lat + k cycles after issue */
    uint8_t mark;    /* 1 start, 2 stop, 4 frame */
    uint8_t pad;
} cyc_insn;

static int cyc_cpu = CPU_ARM926;
static unsigned cyc_refill = 2; /* M3: the P of the timing table, a pipeline refill */
static unsigned cyc_lmul = 5;   /* M3: UMULL/SMULL (3-5 with early termination); MLAL + 2 */
static unsigned cyc_div = 12;   /* M3: SDIV/UDIV (2-12 with early termination) */
static unsigned cyc_muls = 1; /* M0: MULS, 1 on the single-cycle multiplier, 32 on the small one */

static unsigned popcount16(uint32_t v)
{
    unsigned n = 0;
    for (v &= 0xffffu; v; v &= v - 1)
        n++;
    return n;
}

#define R(n) ((uint16_t)(1u << ((n)&15u)))

/* ARM926EJ-S, ARM state (ARM9EJ-S TRM, instruction cycle timings). */
static void dec_arm(uint32_t w, cyc_insn *d)
{
    unsigned cond = w >> 28, op = (w >> 25) & 7u;
    unsigned rn = (w >> 16) & 15u, rd = (w >> 12) & 15u, rs = (w >> 8) & 15u, rm = w & 15u;
    d->base = 1;
    if (cond == 15u) { /* unconditional space: BLX immediate, PLD ... */
        if (op == 5u)
            d->kind = K_BRANCH, d->taken = 3;
        return;
    }
    switch (op) {
    case 0:
    case 1:
        if (op == 0 && (w & 0x0fc000f0u) == 0x00000090u) { /* MUL, MLA */
            int s = (w >> 20) & 1u;
            d->reads = R(rs) | R(rm) | ((w & (1u << 21)) ? R(rd) : 0);
            d->base = s ? 4 : 2;
            d->late = R(rn), d->lat = 3;
            return;
        }
        if (op == 0 && (w & 0x0f8000f0u) == 0x00800090u) { /* UMULL, UMLAL, SMULL, SMLAL */
            int s = (w >> 20) & 1u;
            d->reads = R(rs) | R(rm) | ((w & (1u << 21)) ? R(rn) | R(rd) : 0);
            d->base = s ? 5 : 3;
            d->late = R(rn) | R(rd), d->lat = 4;
            return;
        }
        if (op == 0 && (w & 0x0fb00ff0u) == 0x01000090u) { /* SWP, SWPB */
            d->kind = K_MEM, d->reads = R(rn) | R(rm), d->base = 2;
            d->late = R(rd), d->lat = 3;
            return;
        }
        if (op == 0 && (w & 0x90u) == 0x90u) { /* halfword, signed byte, doubleword transfers */
            unsigned sh = (w >> 5) & 3u;
            d->kind = K_MEM;
            d->reads = R(rn) | ((w & (1u << 22)) ? 0 : R(rm));
            if (w & (1u << 20)) { /* LDRH, LDRSB, LDRSH: the byte/halfword latency */
                d->late = R(rd), d->lat = 3;
            } else if (sh == 2u) { /* LDRD */
                d->base = 2, d->late = R(rd) | R(rd + 1), d->lat = 3;
            } else if (sh == 3u) { /* STRD */
                d->base = 2, d->reads |= R(rd) | R(rd + 1);
            } else { /* STRH */
                d->reads |= R(rd);
            }
            return;
        }
        if (op == 0 && (w & 0x0f900000u) == 0x01000000u) { /* miscellaneous */
            if ((w & 0x0ffffff0u) == 0x012fff10u || (w & 0x0ffffff0u) == 0x012fff30u) {
                d->kind = K_BRANCH, d->reads = R(rm), d->taken = 3; /* BX, BLX register */
            } else if ((w & 0x0f900090u) == 0x01000080u) { /* SMULxy, SMLAxy, SMLAWy, SMLALxy */
                d->reads = R(rs) | R(rm) | R(rd) | R(rn);
                d->base = ((w >> 21) & 3u) == 2u ? 2 : 1;
                d->late = ((w >> 21) & 3u) == 2u ? R(rn) | R(rd) : R(rn), d->lat = 2;
            } else if ((w & 0x0f9000f0u) == 0x01000050u) { /* QADD, QSUB, QDADD, QDSUB */
                d->reads = R(rn) | R(rm), d->late = R(rd), d->lat = 2;
            } else if ((w & 0x0ff000f0u) == 0x01600010u) { /* CLZ */
                d->reads = R(rm);
            }
            return;
        }
        {
            unsigned opc = (w >> 21) & 15u;
            if (opc != 13u && opc != 15u) /* MOV and MVN read no Rn */
                d->reads = R(rn);
            if (op == 0) {
                d->reads |= R(rm);
                if (w & 0x10u) /* shift by a register: one more cycle */
                    d->reads |= R(rs), d->base = 2;
            }
            if (rd == 15u && (opc < 8u || opc > 11u)) /* writes the PC */
                d->kind = K_BRANCH, d->taken = (uint8_t)(d->base + 2);
        }
        return;
    case 2:
    case 3:
        if (op == 3 && (w & 0x10u)) /* media / undefined space: not in the ARMv5TE image */
            return;
        d->kind = K_MEM;
        d->reads = R(rn) | (op == 3 ? R(rm) : 0);
        if (w & (1u << 20)) { /* LDR, LDRB */
            if (rd == 15u)
                d->kind |= K_BRANCH, d->taken = 5;
            else
                d->late = R(rd), d->lat = (w & (1u << 22)) ? 3 : 2;
        } else {
            d->reads |= R(rd);
        }
        return;
    case 4: { /* LDM, STM: one cycle a register, two at least */
        unsigned n = popcount16(w);
        d->kind = K_MEM;
        d->reads = R(rn);
        d->base = (uint8_t)(n < 2 ? 2 : n);
        if (w & (1u << 20)) {
            d->late = (uint16_t)(w & 0x7fffu), d->lat = 2, d->lat_seq = 1;
            if (w & 0x8000u)
                d->kind |= K_BRANCH, d->taken = (uint8_t)(n + 4);
        } else {
            d->reads |= (uint16_t)w;
        }
        return;
    }
    case 5: /* B, BL */ d->kind = K_BRANCH, d->taken = 3; return;
    case 7:
        if (w & (1u << 24)) /* SWI (semihosting): as a taken branch */
            d->base = 3;
        return;
    default: /* coprocessor transfers */ return;
    }
}

/* ARM926EJ-S, Thumb state (the ARM instruction each one stands for). */
static void dec_t16_arm926(uint32_t h, cyc_insn *d)
{
    unsigned lo = h & 7u, mid = (h >> 3) & 7u, hi = (h >> 6) & 7u, r8 = (h >> 8) & 7u;
    d->base = 1;
    if ((h >> 13) == 0) { /* shift by immediate, add/subtract */
        if (((h >> 11) & 3u) == 3u)
            d->reads = R(mid) | ((h & 0x400u) ? 0 : R(hi));
        else
            d->reads = R(mid);
    } else if ((h >> 13) == 1u) { /* MOV/CMP/ADD/SUB immediate */
        if (((h >> 11) & 3u) != 0)
            d->reads = R(r8);
    } else if ((h >> 10) == 0x10u) { /* data processing */
        unsigned op = (h >> 6) & 15u;
        d->reads = R(mid) | ((op == 9u || op == 15u) ? 0 : R(lo));
        if (op == 2u || op == 3u || op == 4u || op == 7u) /* shift by register */
            d->base = 2;
        if (op == 13u) /* MULS */
            d->base = 4, d->late = R(lo), d->lat = 4;
    } else if ((h >> 10) == 0x11u) { /* high-register ADD/CMP/MOV, BX/BLX */
        unsigned op = (h >> 8) & 3u, rd = (h & 7u) | ((h >> 4) & 8u), rm = (h >> 3) & 15u;
        d->reads = R(rm) | (op < 2u ? R(rd) : 0);
        if (op == 3u || (rd == 15u && op != 1u))
            d->kind = K_BRANCH, d->taken = 3;
    } else if ((h >> 11) == 9u) { /* LDR literal */
        d->kind = K_MEM, d->late = R(r8), d->lat = 2;
    } else if ((h >> 12) == 5u) { /* load/store register offset */
        unsigned op = (h >> 9) & 7u;
        d->kind = K_MEM, d->reads = R(hi) | R(mid);
        if (op < 3u)
            d->reads |= R(lo);
        else
            d->late = R(lo), d->lat = op == 4u ? 2 : 3;
    } else if ((h >> 13) == 3u || (h >> 12) == 8u) { /* LDR/STR(B) and LDRH/STRH immediate */
        d->kind = K_MEM, d->reads = R(mid);
        if (h & 0x800u)
            d->late = R(lo), d->lat = ((h >> 12) == 6u) ? 2 : 3;
        else
            d->reads |= R(lo);
    } else if ((h >> 12) == 9u) { /* LDR/STR SP-relative */
        d->kind = K_MEM, d->reads = R(13);
        if (h & 0x800u)
            d->late = R(r8), d->lat = 2;
        else
            d->reads |= R(r8);
    } else if ((h >> 12) == 10u) { /* ADD Rd, PC/SP, #imm */
        d->reads = (h & 0x800u) ? R(13) : 0;
    } else if ((h & 0xf600u) == 0xb400u) { /* PUSH, POP */
        unsigned n = popcount16(h & 0x1ffu);
        d->kind = K_MEM, d->reads = R(13), d->base = (uint8_t)(n < 2 ? 2 : n);
        if (h & 0x800u) {
            d->late = (uint16_t)(h & 0xffu), d->lat = 2, d->lat_seq = 1;
            if (h & 0x100u)
                d->kind |= K_BRANCH, d->taken = (uint8_t)(n + 4);
        } else {
            d->reads |= (uint16_t)((h & 0xffu) | ((h & 0x100u) ? R(14) : 0));
        }
    } else if ((h >> 12) == 11u) { /* ADD/SUB SP and the rest of the miscellaneous space */
        d->reads = R(13);
    } else if ((h >> 12) == 12u) { /* LDMIA, STMIA */
        unsigned n = popcount16(h & 0xffu);
        d->kind = K_MEM, d->reads = R(r8), d->base = (uint8_t)(n < 2 ? 2 : n);
        if (h & 0x800u)
            d->late = (uint16_t)(h & 0xffu), d->lat = 2, d->lat_seq = 1;
        else
            d->reads |= (uint16_t)(h & 0xffu);
    } else if ((h >> 12) == 13u) { /* conditional branch, SWI */
        if (((h >> 8) & 15u) == 15u)
            d->base = 3;
        else if (((h >> 8) & 15u) != 14u)
            d->kind = K_BRANCH, d->taken = 3;
    } else if ((h >> 11) == 0x1cu) { /* B */
        d->kind = K_BRANCH, d->taken = 3;
    } else if ((h >> 11) == 0x1eu) { /* BL/BLX prefix: writes LR */
    } else {                         /* BL/BLX suffix */
        d->kind = K_BRANCH, d->reads = R(14), d->taken = 3;
    }
}

/* Cortex-M3, 16-bit Thumb instructions (Cortex-M3 TRM, processor instruction timings). */
static void dec_t16_m3(uint32_t h, cyc_insn *d)
{
    unsigned lo = h & 7u, mid = (h >> 3) & 7u, hi = (h >> 6) & 7u, r8 = (h >> 8) & 7u;
    unsigned P = cyc_refill;
    d->base = 1;
    if ((h >> 10) == 0x11u) { /* high-register ADD/CMP/MOV, BX/BLX */
        unsigned op = (h >> 8) & 3u, rd = (h & 7u) | ((h >> 4) & 8u);
        d->reads = R((h >> 3) & 15u);
        if (op == 3u || (rd == 15u && op != 1u))
            d->kind = K_BRANCH, d->taken = (uint8_t)(1 + P);
    } else if ((h >> 11) == 9u) { /* LDR literal */
        d->kind = K_MEM | K_LOAD1, d->base = 2, d->late = R(r8);
    } else if ((h >> 12) == 5u) { /* load/store register offset */
        unsigned op = (h >> 9) & 7u;
        d->kind = K_MEM | (op < 3u ? K_STORE1 : K_LOAD1), d->base = 2, d->reads = R(hi) | R(mid);
        if (op >= 3u)
            d->late = R(lo);
    } else if ((h >> 13) == 3u || (h >> 12) == 8u) { /* LDR/STR(B/H) immediate */
        d->kind = K_MEM | ((h & 0x800u) ? K_LOAD1 : K_STORE1), d->base = 2, d->reads = R(mid);
        if (h & 0x800u)
            d->late = R(lo);
    } else if ((h >> 12) == 9u) { /* LDR/STR SP-relative */
        d->kind = K_MEM | ((h & 0x800u) ? K_LOAD1 : K_STORE1), d->base = 2, d->reads = R(13);
        if (h & 0x800u)
            d->late = R(r8);
    } else if ((h & 0xf600u) == 0xb400u) { /* PUSH, POP: 1 + N (+ P with the PC) */
        unsigned n = popcount16(h & 0x1ffu);
        d->kind = K_MEM, d->base = (uint8_t)(1 + n);
        if ((h & 0x900u) == 0x900u)
            d->kind |= K_BRANCH, d->taken = (uint8_t)(1 + n + P);
    } else if ((h & 0xf500u) == 0xb100u) { /* CBZ, CBNZ */
        d->kind = K_BRANCH, d->reads = R(lo), d->taken = (uint8_t)(1 + P);
    } else if ((h & 0xff00u) == 0xbf00u) { /* IT and hints: one cycle (folding not modelled) */
    } else if ((h >> 12) == 12u) {         /* LDMIA, STMIA: 1 + N */
        d->kind = K_MEM, d->base = (uint8_t)(1 + popcount16(h & 0xffu));
    } else if ((h >> 12) == 13u) { /* conditional branch, SVC */
        if (((h >> 8) & 15u) == 15u)
            d->base = 3;
        else if (((h >> 8) & 15u) != 14u)
            d->kind = K_BRANCH, d->taken = (uint8_t)(1 + P);
    } else if ((h >> 11) == 0x1cu) { /* B */
        d->kind = K_BRANCH, d->taken = (uint8_t)(1 + P);
    }
    /* the rest (ALU, shifts, MULS, ADD SP ...) one cycle */
}

/* Cortex-M3, 32-bit Thumb-2 instructions: hw1 first halfword, hw2 second. */
static void dec_t32_m3(uint32_t hw1, uint32_t hw2, cyc_insn *d)
{
    unsigned P = cyc_refill, rn = hw1 & 15u;
    d->base = 1;
    if ((hw1 & 0xfe40u) == 0xe800u) { /* LDM, STM (PUSH.W, POP.W): 1 + N (+ P with the PC) */
        unsigned n = popcount16(hw2);
        d->kind = K_MEM, d->base = (uint8_t)(1 + n);
        if ((hw1 & 0x10u) && (hw2 & 0x8000u))
            d->kind |= K_BRANCH, d->taken = (uint8_t)(1 + n + P);
    } else if ((hw1 & 0xfe40u) == 0xe840u) { /* LDRD, STRD, exclusives, TBB/TBH */
        if ((hw1 & 0xfff0u) == 0xe8d0u && (hw2 & 0xffe0u) == 0xf000u)
            d->kind = K_MEM | K_BRANCH, d->base = 2, d->taken = (uint8_t)(2 + P);
        else
            d->kind = K_MEM, d->base = 3;
    } else if ((hw1 & 0xf800u) == 0xf000u && (hw2 & 0x8000u)) { /* branches, misc control */
        if ((hw2 & 0x5000u) == 0 && ((hw1 >> 7) & 7u) != 7u)    /* B<cond>.W */
            d->kind = K_BRANCH, d->taken = (uint8_t)(1 + P);
        else if (hw2 & 0x1000u) /* B.W, BL */
            d->kind = K_BRANCH, d->taken = (uint8_t)(1 + P);
        else if ((hw1 & 0xffe0u) == 0xf3e0u) /* MRS */
            d->base = 2;
    } else if ((hw1 & 0xfe00u) == 0xf800u) { /* single loads and stores */
        unsigned rt = (hw2 >> 12) & 15u;
        int load = (hw1 & 0x10u) != 0;
        int regoff = !(hw1 & 0x80u) && rn != 15u && (hw2 & 0xfc0u) == 0;
        d->kind = K_MEM | (load ? K_LOAD1 : K_STORE1), d->base = 2;
        d->reads = R(rn) | (regoff ? R(hw2 & 15u) : 0);
        if (load && rt == 15u && ((hw1 >> 5) & 3u) == 2u) /* LDR PC */
            d->kind = K_MEM | K_BRANCH, d->taken = (uint8_t)(2 + P);
        else if (load)
            d->late = R(rt);
    } else if ((hw1 & 0xff80u) == 0xfb00u) { /* MUL 1, MLA/MLS 2 */
        d->base = ((hw2 >> 12) & 15u) == 15u ? 1 : 2;
    } else if ((hw1 & 0xff80u) == 0xfb80u) { /* long multiplies, divides */
        unsigned op = (hw1 >> 4) & 7u;
        if (op == 1u || op == 3u)
            d->base = (uint8_t)cyc_div;
        else if (op == 0u || op == 2u)
            d->base = (uint8_t)cyc_lmul;
        else
            d->base = (uint8_t)(cyc_lmul + 2);
    }
    /* data processing (immediate, shifted register, register) one cycle */
}

/* Cortex-M0, ARMv6-M 16-bit Thumb (Cortex-M0 TRM, instruction set summary: zero wait states).
 * No pipelining of neighbouring loads and stores, no branch folding: the table as it stands. */
static void dec_t16_m0(uint32_t h, cyc_insn *d)
{
    d->base = 1;
    if ((h >> 10) == 0x10u) { /* data processing: MULS by the multiplier, the rest 1 */
        if (((h >> 6) & 15u) == 13u)
            d->base = (uint8_t)cyc_muls;
    } else if ((h >> 10) == 0x11u) { /* high-register ADD/CMP/MOV, BX/BLX: 3 when writing the PC */
        unsigned op = (h >> 8) & 3u, rd = (h & 7u) | ((h >> 4) & 8u);
        if (op == 3u || (rd == 15u && op != 1u))
            d->kind = K_BRANCH, d->taken = 3;
    } else if ((h >> 11) == 9u || (h >> 12) == 5u || (h >> 13) == 3u || (h >> 12) == 8u ||
               (h >> 12) == 9u) { /* LDR literal, loads and stores: 2 */
        d->kind = K_MEM, d->base = 2;
    } else if ((h & 0xf600u) == 0xb400u) { /* PUSH, POP: 1 + N; POP with the PC 4 + N */
        unsigned n = popcount16(h & 0x1ffu);
        d->kind = K_MEM, d->base = (uint8_t)(1 + n);
        if ((h & 0x900u) == 0x900u)
            d->kind |= K_BRANCH, d->taken = (uint8_t)(4 + n);
    } else if ((h >> 12) == 12u) { /* LDMIA, STMIA: 1 + N */
        d->kind = K_MEM, d->base = (uint8_t)(1 + popcount16(h & 0xffu));
    } else if ((h >> 12) == 13u) { /* conditional branch 1 or 3 taken; SVC */
        if (((h >> 8) & 15u) < 14u)
            d->kind = K_BRANCH, d->taken = 3;
    } else if ((h >> 11) == 0x1cu) { /* B */
        d->kind = K_BRANCH, d->taken = 3;
    }
    /* the rest (shifts, add/subtract, immediates, ADD SP, ADR, extends, REV, CPS, hints) 1 */
}

/* Cortex-M0, the 32-bit encodings ARMv6-M has: BL 4; MRS, MSR, DMB, DSB, ISB 4. */
static void dec_t32_m0(uint32_t hw1, uint32_t hw2, cyc_insn *d)
{
    d->base = 4;
    if ((hw1 & 0xf800u) == 0xf000u && (hw2 & 0xd000u) == 0xd000u) /* BL */
        d->kind = K_BRANCH, d->taken = 4;
}

static void cyc_decode(const uint8_t *b, size_t size, int thumb, cyc_insn *d)
{
    uint32_t h0 = (uint32_t)b[0] | (uint32_t)b[1] << 8;
    uint32_t h1 = size == 4 ? ((uint32_t)b[2] | (uint32_t)b[3] << 8) : 0;
    if (cyc_cpu == CPU_M0) {
        if (size == 2)
            dec_t16_m0(h0, d);
        else
            dec_t32_m0(h0, h1, d);
    } else if (cyc_cpu == CPU_M3) {
        if (size == 2)
            dec_t16_m3(h0, d);
        else
            dec_t32_m3(h0, h1, d);
    } else if (!thumb) {
        dec_arm(h0 | h1 << 16, d);
    } else if (size == 2) {
        dec_t16_arm926(h0, d);
    } else { /* QEMU runs a BL/BLX prefix and suffix as one: 1 + 3 cycles */
        d->kind = K_BRANCH, d->base = 1, d->taken = 4;
    }
}

/* ---- the ARM926 caches ------------------------------------------------------------------ */
typedef struct cyc_cache {
    unsigned size, ways, line, sets, miss;
    unsigned line_shift;
    uint32_t *tag;   /* sets * ways; tag | 1 when valid */
    uint64_t *stamp; /* LRU ages */
    unsigned *next;  /* round-robin victims */
    uint64_t tick, misses;
} cyc_cache;

enum { REPL_RR, REPL_LRU, REPL_RANDOM };
static int cyc_repl = REPL_RR;
static uint32_t cyc_rand = 0x2545f491u; /* a fixed seed: repeatable */
static cyc_cache cyc_ic = {16384, 4, 32, 0, 24, 0, NULL, NULL, NULL, 0, 0};
static cyc_cache cyc_dc = {16384, 4, 32, 0, 24, 0, NULL, NULL, NULL, 0, 0};

static int cache_init(cyc_cache *c, const char *name)
{
    if (c->size == 0)
        return 1;
    unsigned sh = 0;
    while ((1u << sh) < c->line)
        sh++;
    if ((1u << sh) != c->line || c->line < 4 || c->ways == 0 || c->size % (c->ways * c->line)) {
        fprintf(stderr,
                "qemu_profile: error: %s: size %u is not a whole number of sets of %u ways of "
                "%u-byte lines (a power of two)\n",
                name, c->size, c->ways, c->line);
        return 0;
    }
    c->line_shift = sh;
    c->sets = c->size / (c->ways * c->line);
    c->tag = calloc((size_t)c->sets * c->ways, sizeof *c->tag);
    c->stamp = calloc((size_t)c->sets * c->ways, sizeof *c->stamp);
    c->next = calloc(c->sets, sizeof *c->next);
    if (!c->tag || !c->stamp || !c->next) {
        fprintf(stderr, "qemu_profile: error: out of memory\n");
        return 0;
    }
    return 1;
}

/* Looks addr up; on a miss with allocate, fills a way. Returns 1 on a miss. */
static int cache_access(cyc_cache *c, uint64_t addr, int allocate)
{
    if (c->size == 0)
        return 0;
    uint64_t lineno = addr >> c->line_shift;
    unsigned set = (unsigned)(lineno % c->sets);
    uint32_t tag = (uint32_t)(lineno / c->sets) << 1 | 1u;
    uint32_t *t = c->tag + (size_t)set * c->ways;
    uint64_t *s = c->stamp + (size_t)set * c->ways;
    c->tick++;
    for (unsigned w = 0; w < c->ways; w++)
        if (t[w] == tag) {
            s[w] = c->tick;
            return 0;
        }
    if (!allocate)
        return 1;
    unsigned v = 0;
    for (v = 0; v < c->ways && t[v]; v++) /* an empty way first */
        ;
    if (v == c->ways) {
        if (cyc_repl == REPL_RR) {
            v = c->next[set];
            c->next[set] = (v + 1) % c->ways;
        } else if (cyc_repl == REPL_LRU) {
            v = 0;
            for (unsigned w = 1; w < c->ways; w++)
                if (s[w] < s[v])
                    v = w;
        } else {
            cyc_rand ^= cyc_rand << 13, cyc_rand ^= cyc_rand >> 17, cyc_rand ^= cyc_rand << 5;
            v = cyc_rand % c->ways;
        }
    }
    t[v] = tag;
    s[v] = c->tick;
    return 1;
}

/* ---- the counters ------------------------------------------------------------------------ */
/* One set of counters per halfword address below PROF_SPAN (ARM and Thumb code alike), one for
 * the rest. */
#define PROF_SPAN (16u << 20)
#define PROF_SLOTS (PROF_SPAN / 2 + 1)
#define PROF_OTHER (PROF_SLOTS - 1)

static uint64_t *prof_count, *prof_cycles, *prof_dmiss; /* inside windows */
static uint64_t prof_start = UINT64_MAX, prof_stop = UINT64_MAX, prof_frame = UINT64_MAX;
static int prof_open, prof_windows;
static char *prof_out;

static uint64_t run_insns, run_cycles, win_insns, win_cycles, win_dmiss, win_imiss;
/* where the window's cycles beyond one an instruction go: interlocks, taken branches, the rest of
 * the instructions' own cycles (multiplies, LDM/STM ...), I-cache and D-cache fills */
static uint64_t win_interlock, win_branch, win_multi, win_ifill, win_dfill;
/* the frame being counted, and the finished ones */
static uint64_t fr_insns, fr_cycles, fr_dmiss, fr_imiss;
static uint64_t (*fr_list)[4];
static size_t fr_n, fr_cap;

/* the pipeline's state */
static uint64_t cyc_now;       /* cycles so far */
static uint64_t cyc_ready[16]; /* when each register's value can be read (ARM926) */
static const cyc_insn *cyc_prev;
static int prev_in_window, prev_mems, prev_pipe_load; /* M3: the last insn was a single load */
static uint16_t prev_load_regs;
static unsigned prev_dmiss, prev_ipen;
static uint64_t cyc_fetch_line = UINT64_MAX;

static size_t prof_slot(uint64_t addr)
{
    return addr < PROF_SPAN ? (size_t)(addr / 2) : PROF_OTHER;
}

static void frame_close(void)
{
    if (fr_insns == 0)
        return;
    if (fr_n == fr_cap) {
        size_t cap = fr_cap ? fr_cap * 2 : 64;
        void *p = realloc(fr_list, cap * sizeof *fr_list);
        if (!p) {
            fprintf(stderr, "qemu_profile: error: out of memory\n");
            exit(1);
        }
        fr_list = p, fr_cap = cap;
    }
    fr_list[fr_n][0] = fr_insns, fr_list[fr_n][1] = fr_cycles;
    fr_list[fr_n][2] = fr_dmiss, fr_list[fr_n][3] = fr_imiss;
    fr_n++;
    fr_insns = fr_cycles = fr_dmiss = fr_imiss = 0;
}

/* Charges the previous instruction now that the next one's address is known. */
static void cyc_retire(uint64_t next_addr)
{
    const cyc_insn *d = cyc_prev;
    int executed = !(d->kind & K_MEM) || prev_mems > 0;
    int taken = (d->kind & K_BRANCH) && next_addr != d->addr + d->size;
    uint64_t issue = cyc_now + prev_ipen, c, lock = 0;
    unsigned dpen = prev_dmiss * cyc_dc.miss;
    if (cyc_cpu == CPU_ARM926) {
        uint64_t ready = issue;
        for (uint16_t r = d->reads; r; r &= (uint16_t)(r - 1)) {
            uint64_t t = cyc_ready[__builtin_ctz(r)];
            ready = t > ready ? t : ready;
        }
        lock = ready - issue;
        issue = ready;
        c = taken ? d->taken : executed ? d->base : 1;
        if (executed && d->late) {
            unsigned k = 0;
            for (uint16_t r = d->late; r; r &= (uint16_t)(r - 1), k++)
                cyc_ready[__builtin_ctz(r)] = issue + dpen + d->lat + (d->lat_seq ? k : 0);
        }
        c += dpen;
    } else {
        c = taken ? d->taken : executed ? d->base : 1;
        /* a single load or store right after a single load pipelines into one cycle, unless
         * its address needs that load's value */
        if (executed && (d->kind & (K_LOAD1 | K_STORE1)) && prev_pipe_load &&
            !(d->reads & prev_load_regs) && !taken)
            c = 1;
        prev_pipe_load = executed && (d->kind & K_LOAD1) && !(d->kind & K_BRANCH);
        prev_load_regs = d->late;
    }
    uint64_t end = issue + c;
    uint64_t spent = end - cyc_now;
    cyc_now = end;
    run_cycles += spent;
    run_insns++;
    if (prev_in_window) {
        prof_count[d->slot]++;
        prof_cycles[d->slot] += spent;
        prof_dmiss[d->slot] += prev_dmiss;
        win_insns++, win_cycles += spent, win_dmiss += prev_dmiss, win_imiss += prev_ipen != 0;
        win_interlock += lock, win_ifill += prev_ipen, win_dfill += dpen;
        if (taken)
            win_branch += c - dpen - 1;
        else
            win_multi += c - dpen - 1;
        fr_insns++, fr_cycles += spent, fr_dmiss += prev_dmiss, fr_imiss += prev_ipen != 0;
    }
}

static void cyc_exec(unsigned int vcpu, void *udata)
{
    (void)vcpu;
    const cyc_insn *d = udata;
    if (cyc_prev)
        cyc_retire(d->addr);
    if (d->mark & 4u)
        frame_close();
    if ((d->mark & 1u) && !prof_open)
        prof_open = 1;
    if ((d->mark & 2u) && prof_open)
        prof_open = 0, prof_windows++;
    cyc_prev = d;
    prev_in_window = prof_open;
    prev_mems = 0;
    prev_dmiss = 0;
    /* a fetch from the line of the previous fetch hits: no lookup */
    uint64_t line = d->addr >> cyc_ic.line_shift;
    prev_ipen = 0;
    if (line != cyc_fetch_line || cyc_ic.size == 0) {
        prev_ipen = cache_access(&cyc_ic, d->addr, 1) ? cyc_ic.miss : 0;
        cyc_fetch_line = line;
    }
}

static void cyc_mem(unsigned int vcpu, qemu_plugin_meminfo_t info, uint64_t vaddr, void *udata)
{
    (void)vcpu;
    (void)udata;
    prev_mems++;
    /* peripherals (from 256 MiB up on both boards) are not cached */
    if (vaddr >= 0x10000000u && cyc_cpu == CPU_ARM926)
        return;
    if (cache_access(&cyc_dc, vaddr, !qemu_plugin_mem_is_store(info)))
        if (!qemu_plugin_mem_is_store(info))
            prev_dmiss++;
}

static void prof_translate(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    (void)id;
    size_t n = qemu_plugin_tb_n_insns(tb);
    /* ARM926: a block is all ARM or all Thumb; a Thumb block holds a 2-byte instruction, or is
     * one BL/BLX pair (QEMU runs the two halves as one 4-byte instruction) */
    int thumb = cyc_cpu != CPU_ARM926;
    for (size_t i = 0; i < n && !thumb; i++)
        if (qemu_plugin_insn_size(qemu_plugin_tb_get_insn(tb, i)) == 2)
            thumb = 1;
    if (!thumb && n == 1) {
        const uint8_t *b = qemu_plugin_insn_data(qemu_plugin_tb_get_insn(tb, 0));
        uint64_t a = qemu_plugin_insn_vaddr(qemu_plugin_tb_get_insn(tb, 0));
        if ((a & 3u) || ((b[1] >> 3) == 0x1eu && ((b[3] >> 3) == 0x1fu || (b[3] >> 3) == 0x1du)))
            thumb = 1;
    }
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        cyc_insn *d = calloc(1, sizeof *d);
        if (!d) {
            fprintf(stderr, "qemu_profile: error: out of memory\n");
            exit(1);
        }
        d->addr = qemu_plugin_insn_vaddr(insn);
        d->size = (uint8_t)qemu_plugin_insn_size(insn);
        d->slot = (uint32_t)prof_slot(d->addr);
        cyc_decode(qemu_plugin_insn_data(insn), d->size, thumb, d);
        d->mark = (uint8_t)((d->addr == prof_start ? 1u : 0u) | (d->addr == prof_stop ? 2u : 0u) |
                            (d->addr == prof_frame ? 4u : 0u));
        qemu_plugin_register_vcpu_insn_exec_cb(insn, cyc_exec, QEMU_PLUGIN_CB_NO_REGS, d);
        qemu_plugin_register_vcpu_mem_cb(insn, cyc_mem, QEMU_PLUGIN_CB_NO_REGS, QEMU_PLUGIN_MEM_RW,
                                         NULL);
    }
}

static void prof_exit(qemu_plugin_id_t id, void *udata)
{
    (void)id;
    (void)udata;
    if (cyc_prev) /* the last instruction: as not taken */
        cyc_retire(cyc_prev->addr + cyc_prev->size);
    if (prof_open)
        prof_windows++;
    frame_close();
    FILE *f = fopen(prof_out, "w");
    if (!f) {
        fprintf(stderr, "qemu_profile: error: cannot write %s\n", prof_out);
        return;
    }
    fprintf(f,
            "cpu %s\nwindows %d\nwindow_total %" PRIu64 "\nwindow_cycles %" PRIu64
            "\nwindow_dmiss %" PRIu64 "\nwindow_imiss %" PRIu64 "\nrun_total %" PRIu64
            "\nrun_cycles %" PRIu64 "\nwindow_interlock %" PRIu64 "\nwindow_branch %" PRIu64
            "\nwindow_multi %" PRIu64 "\nwindow_ifill %" PRIu64 "\nwindow_dfill %" PRIu64 "\n",
            cyc_cpu == CPU_M0       ? "m0"
                : cyc_cpu == CPU_M3 ? "m3"
                                    : "arm926",
            prof_windows, win_insns, win_cycles, win_dmiss, win_imiss, run_insns, run_cycles,
            win_interlock, win_branch, win_multi, win_ifill, win_dfill);
    for (size_t i = 0; i < fr_n; i++)
        fprintf(f, "frame %" PRIu64 " %" PRIu64 " %" PRIu64 " %" PRIu64 "\n", fr_list[i][0],
                fr_list[i][1], fr_list[i][2], fr_list[i][3]);
    for (size_t i = 0; i < PROF_SLOTS; i++)
        if (prof_count[i])
            fprintf(f, "a %08" PRIx64 " %" PRIu64 " %" PRIu64 " %" PRIu64 "\n",
                    i == PROF_OTHER ? (uint64_t)0xffffffffu : (uint64_t)i * 2, prof_count[i],
                    prof_cycles[i], prof_dmiss[i]);
    if (fclose(f) != 0)
        fprintf(stderr, "qemu_profile: error: cannot write %s\n", prof_out);
}

/* A number argument: decimal or 0x-prefixed hexadecimal; 0 on a malformed value. */
static int prof_num(const char *s, uint64_t *v)
{
    char *end;
    unsigned long long x = strtoull(s, &end, 0);
    if (*s == '\0' || *s == '-' || *end != '\0')
        return 0;
    *v = x;
    return 1;
}

/* NAME=VALUE with a number up to max into *out; 1 when argument a is that option and valid. */
static int prof_opt(const char *a, const char *name, uint64_t max, unsigned *out)
{
    size_t n = strlen(name);
    uint64_t v;
    if (strncmp(a, name, n) != 0 || a[n] != '=' || !prof_num(a + n + 1, &v) || v > max)
        return 0;
    *out = (unsigned)v;
    return 1;
}

int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc, char **argv)
{
    (void)info;
    unsigned ways = 4, line = 32;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strncmp(a, "out=", 4) == 0 && a[4]) {
            prof_out = argv[i] + 4;
        } else if (strcmp(a, "cpu=arm926") == 0) {
            cyc_cpu = CPU_ARM926;
        } else if (strcmp(a, "cpu=m3") == 0) {
            cyc_cpu = CPU_M3;
        } else if (strcmp(a, "cpu=m0") == 0) {
            cyc_cpu = CPU_M0;
        } else if (strcmp(a, "repl=rr") == 0 || strcmp(a, "repl=lru") == 0 ||
                   strcmp(a, "repl=random") == 0) {
            cyc_repl = a[5] == 'r' && a[6] == 'r' ? REPL_RR : a[5] == 'l' ? REPL_LRU : REPL_RANDOM;
        } else if ((strncmp(a, "start=", 6) == 0 && prof_num(a + 6, &prof_start)) ||
                   (strncmp(a, "stop=", 5) == 0 && prof_num(a + 5, &prof_stop)) ||
                   (strncmp(a, "frame=", 6) == 0 && prof_num(a + 6, &prof_frame)) ||
                   prof_opt(a, "icache", 1u << 24, &cyc_ic.size) ||
                   prof_opt(a, "dcache", 1u << 24, &cyc_dc.size) ||
                   prof_opt(a, "ways", 64, &ways) || prof_opt(a, "line", 1024, &line) ||
                   prof_opt(a, "imiss", 200, &cyc_ic.miss) ||
                   prof_opt(a, "dmiss", 200, &cyc_dc.miss) ||
                   prof_opt(a, "refill", 3, &cyc_refill) || prof_opt(a, "lmul", 7, &cyc_lmul) ||
                   prof_opt(a, "div", 12, &cyc_div) || prof_opt(a, "muls", 32, &cyc_muls)) {
        } else {
            fprintf(stderr,
                    "qemu_profile: error: unknown or malformed argument '%s' (out=FILE, "
                    "cpu=arm926|m3|m0, start=ADDR, stop=ADDR, frame=ADDR, icache=, dcache=, ways=, "
                    "line=, repl=rr|lru|random, imiss=, dmiss=, refill=1..3, lmul=..7, div=..12, "
                    "muls=..32)\n",
                    a);
            return -1;
        }
    }
    if (!prof_out || (prof_start == UINT64_MAX) != (prof_stop == UINT64_MAX)) {
        fprintf(stderr, "qemu_profile: error: wants out=FILE, and start=ADDR with stop=ADDR\n");
        return -1;
    }
    /* the LM3S6965 and the nRF51 have no caches; their flash needs no wait states at 50 and 16 MHz */
    if (cyc_cpu != CPU_ARM926)
        cyc_ic.size = cyc_dc.size = 0;
    cyc_ic.ways = cyc_dc.ways = ways;
    cyc_ic.line = cyc_dc.line = line;
    if (!cache_init(&cyc_ic, "icache") || !cache_init(&cyc_dc, "dcache"))
        return -1;
    if (prof_start == UINT64_MAX) /* no window given: the whole run is one */
        prof_open = 1;
    prof_count = calloc(PROF_SLOTS, sizeof *prof_count);
    prof_cycles = calloc(PROF_SLOTS, sizeof *prof_cycles);
    prof_dmiss = calloc(PROF_SLOTS, sizeof *prof_dmiss);
    if (!prof_count || !prof_cycles || !prof_dmiss) {
        fprintf(stderr, "qemu_profile: error: out of memory\n");
        return -1;
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, prof_translate);
    qemu_plugin_register_atexit_cb(id, prof_exit, NULL);
    return 0;
}
