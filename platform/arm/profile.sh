#!/usr/bin/env bash
# profile.sh: where the ARM926 image spends its instructions: exact per-function counts of intro frames under QEMU (make qemu-profile).
#
# Usage: platform/arm/profile.sh [fixed|float|fixed16|m3|m0] [SETTINGS] N...
# (m3, m0: the Cortex-M3 or M0 image, build/m3|m0/intro-fixed.elf at 128x64, run by its board's
# qemu.sh; a window per band; the M0's clock steps 62.5 instructions, the M3's 20, so their
# figures may differ from the plugin's by that much a band.)
# Renders intro frames N... on the board (platform/arm/qemu.sh frames, under -icount) with the
# TCG plugin build/arm/qemu_profile.so (platform/arm/qemu_profile.c) loaded: it counts every
# guest instruction per address, inside the frame's rendering only (from rt_render_band_into's first instruction to
# the board's next clock read). The addresses are mapped to source with
# `arm-none-eabi-addr2line -f -i` and summed:
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
# build/qemu/profile-REAL.txt, and the raw `ADDRESS COUNT` lines to build/qemu/profile-REAL.counts.
set -euo pipefail
cd "$(dirname "$0")/../.."

die() { printf 'profile.sh: error: %s\n' "$*" >&2; exit 2; }
real=fixed
if [ $# -ge 1 ] && { [ "$1" = fixed ] || [ "$1" = float ] || [ "$1" = fixed16 ] || [ "$1" = m3 ] || [ "$1" = m0 ]; }; then
  real=$1
  shift
fi
[ $# -ge 1 ] || die "usage: platform/arm/profile.sh [fixed|float|fixed16|m3|m0] [SETTINGS] N..."
top=${PROFILE_TOP:-25}
case "$top" in ''|*[!0-9]*|0) die "PROFILE_TOP must be a whole number, 1 or more, not '$top'" ;; esac
elf=build/arm/intro-$real.elf
run=(platform/arm/qemu.sh frames "$real")
size=320x240
slack=200 # instructions a frame the board's figures may differ by
onewindow=1 # the plugin's windows (rt_render_band_into to the clock read) are the frames
if [ "$real" = m0 ] || [ "$real" = m3 ]; then
  elf=build/$real/intro-fixed.elf
  run=("platform/$real/qemu.sh" frames)
  size=128x64
  slack=1100 # up to 16 bands, each within a clock step, and the clock reads
  onewindow=0 # a window per band
fi
plugin=build/arm/qemu_profile.so
[ -f "$elf" ] || die "$elf is missing: run make arm first"
[ -f "$plugin" ] || die "$plugin is missing: run make $plugin (make qemu-profile builds it)"
command -v arm-none-eabi-addr2line >/dev/null || die "arm-none-eabi-addr2line is missing: run ./setup.sh --arm"

# (awk reads nm's whole output: leaving early would kill nm with SIGPIPE, fatal under pipefail)
sym() { arm-none-eabi-nm "$elf" | awk -v s="$1" '$3 == s && !f { print "0x" $1; f = 1 }'; }
start=$(sym rt_render_band_into)
stop=$(sym plat_time_ns)
if [ -z "$start" ] || [ -z "$stop" ]; then die "rt_render_band_into or plat_time_ns not found in $elf"; fi

out=build/qemu
mkdir -p "$out"
counts=$out/profile-$real.counts
log=$out/profile-$real.log
report=$out/profile-$real.txt
rm -f "$counts"
QEMU_PLUGIN="$plugin,out=$counts,start=$start,stop=$stop" "${run[@]}" "$@" >"$log" 2>&1 ||
  { tail -3 "$log" >&2; die "the $real guest failed (log: $log)"; }
[ -s "$counts" ] || die "the plugin wrote no counts ($counts)"

# addr2line -a -f -i: for each address a line 0xADDRESS, then (function, file:line) pairs from
# the innermost inlined function out to the containing one.
awk 'NR > 3 { print "0x" $1 }' "$counts" | arm-none-eabi-addr2line -e "$elf" -a -f -i >"$out/profile-$real.lines"

{
  echo "profile of the $real image at $size, intro frames and settings: $*"
  awk -v top="$top" -v logf="$log" -v slack="$slack" -v onewindow="$onewindow" '
    FNR == 1 { file++ }
    file == 1 && FNR <= 3 { total[$1] = $2; next }
    file == 1 { cnt["0x" $1] = $2; next }
    file == 2 {
      if ($0 ~ /^0x[0-9a-f]+$/) { flush(); addr = $0; n = 0; line = 0; next }
      if (++line % 2 == 1) fn[++n] = $0
      next
    }
    file == 3 && /^frame=/ { sub(/.*instructions=/, ""); board += $0; frames++; next }
    file == 4 && ($2 == "T" || $2 == "t") { entry[$3] = "0x" $1 }
    function flush(  c, inner, outer) {
      if (addr == "" || n == 0) return
      c = cnt[addr]
      inner = fn[1]; outer = fn[n]
      if (inner == "??") inner = outer
      by_inner[inner] += c; by_outer[outer] += c; by_pair[inner " in " outer] += c
      mapped += c
      addr = ""
    }
    function table(title, a, calls,   k, i, j, t, keys, m, c) {
      m = 0
      for (k in a) keys[++m] = k
      # selection of the largest rows (a few hundred keys at most)
      printf "\n%s\n%14s %7s  %s\n", title, "instructions", "share", calls ? "function                          calls  a call" : "function"
      for (i = 1; i <= m && i <= top; i++) {
        for (j = i + 1; j <= m; j++)
          if (a[keys[j]] > a[keys[i]]) { t = keys[i]; keys[i] = keys[j]; keys[j] = t }
        c = calls && (keys[i] in entry) ? cnt[entry[keys[i]]] + 0 : 0
        if (c > 0)
          printf "%14d %6.2f%%  %-28s %10d %7.0f\n", a[keys[i]], 100 * a[keys[i]] / total["window_total"], keys[i], c, a[keys[i]] / c
        else
          printf "%14d %6.2f%%  %s\n", a[keys[i]], 100 * a[keys[i]] / total["window_total"], keys[i]
      }
    }
    END {
      flush()
      w = total["window_total"]; r = total["run_total"]; k = total["windows"]
      printf "\ninside the frames: %d instructions over %d %s (%.1f M a %s)\n", w, k, onewindow ? "frames" : "bands", w / k / 1e6, onewindow ? "frame" : "band"
      printf "the board'\''s icount figures for the same frames: %d over %d frames; difference %d (%.1f a frame)\n", board, frames, w - board, (w - board) / (frames ? frames : 1)
      printf "outside the frames (boot, scene evaluation, PPM writes): %d instructions; whole run %d\n", r - w, r
      table("by function (inlined code counted in the function it was written in):", by_inner, 0)
      table("by containing function (the symbol the code was compiled into; calls: times its first instruction ran):", by_outer, 1)
      table("by inlined function within containing function:", by_pair, 0)
      d = w - board; if (d < 0) d = -d
      if ((onewindow && k != frames) || frames == 0 || d > slack * frames) {
        printf "\nprofile: error: the plugin counted %d instructions in %d frames, the board %d in %d\n", w, k, board, frames
        exit 1
      }
    }' "$counts" "$out/profile-$real.lines" "$log" <(arm-none-eabi-nm "$elf")
} | tee "$report"
