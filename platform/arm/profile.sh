#!/usr/bin/env bash
# profile.sh: where the ARM926 image spends its cycles and instructions: exact per-function counts and the timing model's cycles of intro frames under QEMU (make qemu-profile).
#
# Usage: platform/arm/profile.sh [fixed|float|fixed16] [SETTINGS] N...
# Renders intro frames N... on the board (platform/arm/qemu.sh frames, under -icount) with the
# TCG plugin build/arm/qemu_profile.so (platform/arm/qemu_profile.c) loaded: it counts every
# guest instruction per address, with the ARM926 timing model's cycles and D-cache read misses
# (docs/arm.md, Cycle model; QEMU_CYCLES_OPTS passes cache options), inside the frame's rendering only (from rt_render_band_into's first instruction to
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
# lines) to within 200 instructions a frame (the board's figure also holds the clock reads' call and
# return, about 60 instructions, and the 24 MHz clock's 42-instruction step); the instructions outside the frames (boot, scene evaluation,
# the PPM writes) are reported apart. Status 1 if the totals disagree. Everything also goes to
# build/qemu/profile-REAL.txt, and the plugin's raw `a ADDRESS COUNT CYCLES DMISSES` lines to
# build/qemu/profile-REAL.counts.
set -euo pipefail
cd "$(dirname "$0")/../.."

die() { printf 'profile.sh: error: %s\n' "$*" >&2; exit 2; }
real=fixed
if [ $# -ge 1 ] && { [ "$1" = fixed ] || [ "$1" = float ] || [ "$1" = fixed16 ]; }; then
  real=$1
  shift
fi
[ $# -ge 1 ] || die "usage: platform/arm/profile.sh [fixed|float|fixed16] [SETTINGS] N..."
top=${PROFILE_TOP:-25}
case "$top" in ''|*[!0-9]*|0) die "PROFILE_TOP must be a whole number, 1 or more, not '$top'" ;; esac
elf=build/arm/intro-$real.elf
plugin=build/arm/qemu_profile.so
[ -f "$elf" ] || die "$elf is missing: run make arm first"
[ -f "$plugin" ] || die "$plugin is missing: run make $plugin (make qemu-profile builds it)"
command -v arm-none-eabi-addr2line >/dev/null || die "arm-none-eabi-addr2line is missing: run ./setup.sh --arm"

out=build/qemu
mkdir -p "$out"
counts=$out/profile-$real.counts
log=$out/profile-$real.log
report=$out/profile-$real.txt
rm -f "$counts"
QEMU_CYCLES_OUT="$counts" platform/arm/qemu.sh frames "$real" "$@" >"$log" 2>&1 ||
  { tail -3 "$log" >&2; die "the $real guest failed (log: $log)"; }
[ -s "$counts" ] || die "the plugin wrote no counts ($counts)"

# addr2line -a -f -i: for each address a line 0xADDRESS, then (function, file:line) pairs from
# the innermost inlined function out to the containing one.
awk '$1 == "a" { print "0x" $2 }' "$counts" | arm-none-eabi-addr2line -e "$elf" -a -f -i >"$out/profile-$real.lines"

{
  echo "profile of the $real image at 320x240, intro frames and settings: $*"
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
      printf "\ninside the frames: %d instructions over %d frames (%.1f M a frame)\n", w, k, w / k / 1e6
      printf "the ARM926 model'\''s cycles: %d (%.1f M a frame), %.3f a instruction; D-cache read misses %d, instructions fetched with an I-cache miss %d\n", wc, wc / k / 1e6, wc / w, total["window_dmiss"], total["window_imiss"]
      printf "cycles beyond one an instruction: interlocks %d, taken branches %d, multi-cycle instructions (multiplies, LDM/STM ...) %d, I-cache fills %d, D-cache fills %d\n", total["window_interlock"], total["window_branch"], total["window_multi"], total["window_ifill"], total["window_dfill"]
      printf "the board'\''s icount figures for the same frames: %d over %d frames; difference %d (%.1f a frame)\n", board, frames, w - board, (w - board) / (frames ? frames : 1)
      printf "outside the frames (boot, scene evaluation, PPM writes): %d instructions; whole run %d\n", r - w, r
      table("by function (inlined code counted in the function it was written in):", i_cyc, i_ins, i_dm, 0)
      table("by containing function (the symbol the code was compiled into; calls: times its first instruction ran):", o_cyc, o_ins, o_dm, 1)
      table("by inlined function within containing function:", p_cyc, p_ins, p_dm, 0)
      d = w - board; if (d < 0) d = -d
      if (k != frames || frames == 0 || d > 200 * frames) {
        printf "\nprofile: error: the plugin counted %d instructions in %d frames, the board %d in %d\n", w, k, board, frames
        exit 1
      }
    }' "$counts" "$out/profile-$real.lines" "$log" <(arm-none-eabi-nm "$elf")
} | tee "$report"
