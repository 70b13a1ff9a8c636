/* qemu_profile.c: a QEMU TCG plugin that counts the guest instructions executed at each address, inside frames and in all.
 *
 * Loaded by platform/arm/profile.sh (make qemu-profile) into qemu-system-arm 7.2 with
 *   -plugin build/arm/qemu_profile.so,out=FILE,start=ADDR,stop=ADDR
 * Every translated guest instruction gets an inline 64-bit counter (QEMU adds 1 to it each time
 * the instruction starts, no call into the plugin). The counting window opens when the
 * instruction at `start` (the entry of rt_render) is reached and closes at the next instruction
 * at `stop` (the entry of plat_time_ns, which the board calls right after rt_render): at those
 * two points a callback adds the counters' change since the window opened into the window's
 * totals. At exit FILE gets one line `ADDR COUNT` (hexadecimal address, decimal count) per
 * address executed inside a window, after three summary lines:
 *   windows N        frames counted
 *   window_total M   instructions inside the windows
 *   run_total T      instructions in the whole run (boot, parsing, file writing included)
 * Without start/stop the whole run is one window. Addresses from 0 to 16 MiB are counted one by
 * one (the versatilepb board's RAM, where the image runs); anything above goes into one bucket
 * reported as address ffffffff.
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
enum qemu_plugin_cb_flags { QEMU_PLUGIN_CB_NO_REGS, QEMU_PLUGIN_CB_R_REGS, QEMU_PLUGIN_CB_RW_REGS };
enum qemu_plugin_op { QEMU_PLUGIN_INLINE_ADD_U64 };
typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);
typedef void (*qemu_plugin_vcpu_udata_cb_t)(unsigned int vcpu_index, void *userdata);
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);
void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
void qemu_plugin_register_vcpu_insn_exec_cb(struct qemu_plugin_insn *insn,
                                            qemu_plugin_vcpu_udata_cb_t cb,
                                            enum qemu_plugin_cb_flags flags, void *userdata);
void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *insn,
                                                enum qemu_plugin_op op, void *ptr, uint64_t imm);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb, void *userdata);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);

__attribute__((visibility("default"))) int qemu_plugin_version = 1;
__attribute__((visibility("default"))) int qemu_plugin_install(qemu_plugin_id_t id,
                                                               const qemu_info_t *info, int argc,
                                                               char **argv);

/* ---- the counters ------------------------------------------------------------------------ */
/* One counter per halfword address below PROF_SPAN (ARM and Thumb code alike), one for the rest. */
#define PROF_SPAN (16u << 20)
#define PROF_SLOTS (PROF_SPAN / 2 + 1)
#define PROF_OTHER (PROF_SLOTS - 1)

static uint64_t *prof_now;    /* counts since the start of the run */
static uint64_t *prof_mark;   /* prof_now when the window opened */
static uint64_t *prof_window; /* counts inside windows */
static uint8_t *prof_seen;    /* 1 where an instruction was translated */
static uint64_t prof_start = UINT64_MAX, prof_stop = UINT64_MAX;
static int prof_open, prof_windows;
static char *prof_out;
/* The lowest and highest slot translated so far: the windows only sweep that span. */
static size_t prof_lo = PROF_SLOTS, prof_hi;

static size_t prof_slot(uint64_t addr)
{
    return addr < PROF_SPAN ? (size_t)(addr / 2) : PROF_OTHER;
}

static void prof_open_window(unsigned int vcpu, void *udata)
{
    (void)vcpu;
    (void)udata;
    if (prof_open)
        return;
    for (size_t i = prof_lo; i <= prof_hi && i < PROF_SLOTS; i++)
        prof_mark[i] = prof_now[i];
    prof_mark[PROF_OTHER] = prof_now[PROF_OTHER];
    prof_open = 1;
}

static void prof_close_window(unsigned int vcpu, void *udata)
{
    (void)vcpu;
    (void)udata;
    if (!prof_open)
        return;
    for (size_t i = prof_lo; i <= prof_hi && i < PROF_SLOTS; i++)
        prof_window[i] += prof_now[i] - prof_mark[i];
    prof_window[PROF_OTHER] += prof_now[PROF_OTHER] - prof_mark[PROF_OTHER];
    prof_open = 0;
    prof_windows++;
}

static void prof_translate(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    (void)id;
    size_t n = qemu_plugin_tb_n_insns(tb);
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        uint64_t addr = qemu_plugin_insn_vaddr(insn);
        size_t s = prof_slot(addr);
        /* the window's callbacks first, so that the instruction at start counts inside the
         * window and the one at stop outside it */
        if (addr == prof_start)
            qemu_plugin_register_vcpu_insn_exec_cb(insn, prof_open_window, QEMU_PLUGIN_CB_NO_REGS,
                                                   NULL);
        if (addr == prof_stop)
            qemu_plugin_register_vcpu_insn_exec_cb(insn, prof_close_window, QEMU_PLUGIN_CB_NO_REGS,
                                                   NULL);
        qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64, &prof_now[s],
                                                   1);
        prof_seen[s] = 1;
        if (s != PROF_OTHER) {
            prof_lo = s < prof_lo ? s : prof_lo;
            prof_hi = s > prof_hi ? s : prof_hi;
        }
    }
}

static void prof_exit(qemu_plugin_id_t id, void *udata)
{
    (void)id;
    (void)udata;
    if (prof_start == UINT64_MAX) /* no window given: the whole run is one */
        memcpy(prof_window, prof_now, PROF_SLOTS * sizeof *prof_now), prof_windows = 1;
    uint64_t run = 0, win = 0;
    for (size_t i = 0; i < PROF_SLOTS; i++) {
        run += prof_now[i];
        win += prof_window[i];
    }
    FILE *f = fopen(prof_out, "w");
    if (!f) {
        fprintf(stderr, "qemu_profile: error: cannot write %s\n", prof_out);
        return;
    }
    fprintf(f, "windows %d\nwindow_total %" PRIu64 "\nrun_total %" PRIu64 "\n", prof_windows, win,
            run);
    for (size_t i = 0; i < PROF_SLOTS; i++)
        if (prof_seen[i] && prof_window[i])
            fprintf(f, "%08" PRIx64 " %" PRIu64 "\n",
                    i == PROF_OTHER ? (uint64_t)0xffffffffu : (uint64_t)i * 2, prof_window[i]);
    if (fclose(f) != 0)
        fprintf(stderr, "qemu_profile: error: cannot write %s\n", prof_out);
}

/* An address argument: decimal or 0x-prefixed hexadecimal; 0 on a malformed value. */
static int prof_addr(const char *s, uint64_t *v)
{
    char *end;
    unsigned long long x = strtoull(s, &end, 0);
    if (*s == '\0' || *end != '\0')
        return 0;
    *v = x;
    return 1;
}

int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc, char **argv)
{
    (void)info;
    for (int i = 0; i < argc; i++) {
        if (strncmp(argv[i], "out=", 4) == 0 && argv[i][4]) {
            prof_out = argv[i] + 4;
        } else if (strncmp(argv[i], "start=", 6) == 0 && prof_addr(argv[i] + 6, &prof_start)) {
        } else if (strncmp(argv[i], "stop=", 5) == 0 && prof_addr(argv[i] + 5, &prof_stop)) {
        } else {
            fprintf(stderr,
                    "qemu_profile: error: unknown or malformed argument '%s' (out=FILE, "
                    "start=ADDR, stop=ADDR)\n",
                    argv[i]);
            return -1;
        }
    }
    if (!prof_out || (prof_start == UINT64_MAX) != (prof_stop == UINT64_MAX)) {
        fprintf(stderr, "qemu_profile: error: wants out=FILE, and start=ADDR with stop=ADDR\n");
        return -1;
    }
    prof_now = calloc(PROF_SLOTS, sizeof *prof_now);
    prof_mark = calloc(PROF_SLOTS, sizeof *prof_mark);
    prof_window = calloc(PROF_SLOTS, sizeof *prof_window);
    prof_seen = calloc(PROF_SLOTS, 1);
    if (!prof_now || !prof_mark || !prof_window || !prof_seen) {
        fprintf(stderr, "qemu_profile: error: out of memory\n");
        return -1;
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, prof_translate);
    qemu_plugin_register_atexit_cb(id, prof_exit, NULL);
    return 0;
}
