#!/usr/bin/env bash
# profile.sh: where a board image spends its cycles and instructions (ARM926, Cortex-M3, Cortex-M0): exact per-function counts and the timing model's cycles of intro frames under QEMU (make qemu-profile).
#
# Usage: platform/arm/profile.sh [fixed|float|fixed16|m3|m0] [SETTINGS] N...
# fixed, float, fixed16: the ARM926 images at 320x240 (platform/arm/qemu.sh frames); m3, m0: the
# Cortex-M3 and Cortex-M0 images at 128x64 (platform/m3/qemu.sh, platform/m0/qemu.sh frames), a
# counted window per band. Renders intro frames N... on the board (under -icount) with the
# TCG plugin build/arm/qemu_profile.so (platform/arm/qemu_profile.c) loaded: it counts every
# guest instruction per address, with the core's timing model's cycles and (ARM926) D-cache read
# misses (docs/arm.md, docs/m3.md, docs/m0.md, Cycle model; QEMU_CYCLES_OPTS passes model options),
# inside the frame's rendering only (from rt_render_band_into's first instruction to
# the board's next clock read). The addresses are mapped to source with
# `arm-none-eabi-addr2line -f -i` and summed, each table ranked by cycles, with instructions,
# cycles per instruction (CPI) and D-cache misses beside them:
#   - by function, inlined code counted in the function it was written in (the innermost
#     inlined function: r_mul, fx_sat, v3_dot_d ...);
#   - by containing function (the symbol the code was compiled into: rt_occluded, ss_fill ...),
#     with its calls (how often its first instruction ran) and instructions a call;
#   - by pair (inlined function in containing function).
# Prints the tables (PROFILE_TOP rows each, default 25) and checks that the plugin's total
# inside the frames equals the board's own icount figures (the `frame=N instructions=M`
# lines) to within 200 instructions a frame on the ARM926 (the board's figure also holds the clock
# reads' call and return, about 60 instructions, and the 24 MHz clock's 42-instruction step), 100
# a band on the Cortex-M boards (8 bands a frame on the M3, 16 on the M0; clock steps of 20 and
# 63 instructions); the instructions outside the frames (boot, scene evaluation,
# the PPM writes) are reported apart. Status 1 if the totals disagree. Everything also goes to
# build/qemu/profile-REAL.txt, and the plugin's raw `a ADDRESS COUNT CYCLES DMISSES` lines to
# build/qemu/profile-REAL.counts. On the M0, the share of the multiplication helpers (the
# products in 32-bit pieces, fx_v6m_smul and fx_v6m_umul, and libgcc's __aeabi_lmul) is
# printed under the tables.
set -euo pipefail
cd "$(dirname "$0")/../.."

die() { printf 'profile.sh: error: %s\n' "$*" >&2; exit 2; }
real=fixed
case "${1:-}" in fixed|float|fixed16|m3|m0) real=$1; shift ;; esac
[ $# -ge 1 ] || die "usage: platform/arm/profile.sh [fixed|float|fixed16|m3|m0] [SETTINGS] N..."
top=${PROFILE_TOP:-25}
case "$top" in ''|*[!0-9]*|0) die "PROFILE_TOP must be a whole number, 1 or more, not '$top'" ;; esac
case "$real" in
  m3|m0) elf=build/$real/intro-fixed.elf run=("platform/$real/qemu.sh" frames) size=128x64 ;;
  *) elf=build/arm/intro-$real.elf run=(platform/arm/qemu.sh frames "$real") size=320x240 ;;
esac
plugin=build/arm/qemu_profile.so
[ -f "$elf" ] || die "$elf is missing: run make ${elf#build/} first"
[ -f "$plugin" ] || die "$plugin is missing: run make $plugin (make qemu-profile builds it)"
command -v arm-none-eabi-addr2line >/dev/null || die "arm-none-eabi-addr2line is missing: run ./setup.sh --arm"

out=build/qemu
mkdir -p "$out"
counts=$out/profile-$real.counts
log=$out/profile-$real.log
report=$out/profile-$real.txt
rm -f "$counts"
QEMU_CYCLES_OUT="$counts" "${run[@]}" "$@" >"$log" 2>&1 ||
  { tail -3 "$log" >&2; die "the $real guest failed (log: $log)"; }
[ -s "$counts" ] || die "the plugin wrote no counts ($counts)"

# addr2line -a -f -i: for each address a line 0xADDRESS, then (function, file:line) pairs from
# the innermost inlined function out to the containing one.
awk '$1 == "a" { print "0x" $2 }' "$counts" | arm-none-eabi-addr2line -e "$elf" -a -f -i >"$out/profile-$real.lines"

{
  echo "profile of the $real image at $size, intro frames and settings: $*"
  awk -v top="$top" '
    FNR == 1 { file++ }
    file == 1 && $1 == "frame" { pf++; next }
    file == 1 && $1 == "a" { cnt["0x" $2] = $3; cyc["0x" $2] = $4; dm["0x" $2] = $5; next }
    file == 1 { total[$1] = $2; next }
    file == 2 {
      if ($0 ~ /^0x[0-9a-f]+$/) { flush(); addr = $0; n = 0; line = 0; next }
      if (++line % 2 == 1) fn[++n] = $0
      next
    }
    file == 3 && /^frame=/ { sub(/.*instructions=/, ""); board += $1; frames++; next }
    file == 4 && ($2 == "T" || $2 == "t") { entry[$3] = "0x" $1 }
    function flush(  inner, outer, k) {
      if (addr == "" || n == 0) return
      inner = fn[1]; outer = fn[n]
      if (inner == "??") inner = outer
      k = inner " in " outer
      i_ins[inner] += cnt[addr]; i_cyc[inner] += cyc[addr]; i_dm[inner] += dm[addr]
      o_ins[outer] += cnt[addr]; o_cyc[outer] += cyc[addr]; o_dm[outer] += dm[addr]
      p_ins[k] += cnt[addr]; p_cyc[k] += cyc[addr]; p_dm[k] += dm[addr]
      addr = ""
    }
    function table(title, c, ins, dmiss, calls,   k, i, j, t, keys, m, e, wc) {
      m = 0
      wc = total["window_cycles"]
      for (k in c) keys[++m] = k
      # selection of the largest rows (a few hundred keys at most)
      printf "\n%s\n%14s %7s %14s %5s %8s  %s\n", title, "cycles", "share", "instructions", "CPI", "D-misses", calls ? "function                          calls  a call" : "function"
      for (i = 1; i <= m && i <= top; i++) {
        for (j = i + 1; j <= m; j++)
          if (c[keys[j]] > c[keys[i]]) { t = keys[i]; keys[i] = keys[j]; keys[j] = t }
        k = keys[i]
        e = calls && (k in entry) ? cnt[entry[k]] + 0 : 0
        printf "%14d %6.2f%% %14d %5.2f %8d  ", c[k], 100 * c[k] / wc, ins[k], ins[k] ? c[k] / ins[k] : 0, dmiss[k]
        if (e > 0)
          printf "%-28s %10d %7.0f\n", k, e, ins[k] / e
        else
          printf "%s\n", k
      }
    }
    END {
      flush()
      w = total["window_total"]; r = total["run_total"]; k = pf; wc = total["window_cycles"]
      core = total["cpu"] == "m0" ? "Cortex-M0" : total["cpu"] == "m3" ? "Cortex-M3" : "ARM926"
      bands = total["windows"] / (k ? k : 1)
      printf "\ninside the frames: %d instructions over %d frames (%.1f M a frame)\n", w, k, w / k / 1e6
      if (total["cpu"] == "arm926") {
        printf "the ARM926 model'\''s cycles: %d (%.1f M a frame), %.3f a instruction; D-cache read misses %d, instructions fetched with an I-cache miss %d\n", wc, wc / k / 1e6, wc / w, total["window_dmiss"], total["window_imiss"]
        printf "cycles beyond one an instruction: interlocks %d, taken branches %d, multi-cycle instructions (multiplies, LDM/STM ...) %d, I-cache fills %d, D-cache fills %d\n", total["window_interlock"], total["window_branch"], total["window_multi"], total["window_ifill"], total["window_dfill"]
      } else {
        printf "the %s model'\''s cycles: %d (%.1f M a frame), %.3f a instruction (no caches)\n", core, wc, wc / k / 1e6, wc / w
        printf "cycles beyond one an instruction: taken branches %d, multi-cycle instructions (loads and stores, multiplies, LDM/STM ...) %d\n", total["window_branch"], total["window_multi"]
      }
      printf "the board'\''s icount figures for the same frames: %d over %d frames; difference %d (%.1f a frame)\n", board, frames, w - board, (w - board) / (frames ? frames : 1)
      printf "outside the frames (boot, scene evaluation, PPM writes): %d instructions; whole run %d\n", r - w, r
      table("by function (inlined code counted in the function it was written in):", i_cyc, i_ins, i_dm, 0)
      table("by containing function (the symbol the code was compiled into; calls: times its first instruction ran):", o_cyc, o_ins, o_dm, 1)
      table("by inlined function within containing function:", p_cyc, p_ins, p_dm, 0)
      if (total["cpu"] == "m0") {
        # by the function written: the inline products wherever they were inlined, and libgcc
        # 64-bit multiply (__aeabi_lmul, whose code is __muldi3)
        mc = mi = 0
        for (key in i_cyc)
          if (key ~ /^(fx_v6m_smul|fx_v6m_umul|__aeabi_lmul|__muldi3)$/) { mc += i_cyc[key]; mi += i_ins[key]; part = part sprintf(" %s %.1f%%", key, 100 * i_cyc[key] / wc) }
        printf "\nmultiplication without a long multiply (fx_v6m_smul, fx_v6m_umul inline; libgcc'\''s __aeabi_lmul = __muldi3): %d cycles, %.1f%% of the frames'\'' cycles (%s); %d instructions, %.1f%%\n", mc, 100 * mc / wc, substr(part, 2), mi, 100 * mi / w
      }
      d = w - board; if (d < 0) d = -d
      slack = total["cpu"] == "arm926" ? 200 : 100 * bands
      if (k != frames || frames == 0 || d > slack * frames) {
        printf "\nprofile: error: the plugin counted %d instructions in %d frames, the board %d in %d\n", w, k, board, frames
        exit 1
      }
    }' "$counts" "$out/profile-$real.lines" "$log" <(arm-none-eabi-nm "$elf")
} | tee "$report"
