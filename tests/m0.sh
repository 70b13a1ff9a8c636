#!/usr/bin/env bash
# m0.sh: the Cortex-M0 image under QEMU (microbit, an nRF51822 with 16 KiB of SRAM) against the host build: no long multiply, divide or floating point in it, bit-identical 128x64 frames, repeatable counts, the RAM and flash budgets, settings, faults.
#
# Usage: tests/m0.sh [--print]   (--print: only the image's sizes, for make m0)
# Expects make all m0. Prints `ok ...` / `FAIL ...` lines (tests/run.sh counts them) and exits 1
# if any check fails. Frames are those of platform/m0/qemu.sh frames, in build/qemu-m0/, compared
# with rt-fixed render --size 128x64 (the M3's frames).
set -u
cd "$(dirname "$0")/.." || exit 1
# These runs check frames and instruction counts: no cycle estimate (its plugin makes QEMU several
# times slower); tests/cycles.sh checks the cycles. CYCLES=1 in the environment keeps it.
export CYCLES=${CYCLES:-0}

. tests/lib.sh
. tests/board.sh
T=$B/test/m0
ELF=$B/m0/intro-fixed.elf
RAM_LIMIT=16384    # the chip's SRAM: data + bss + the measured stack peak
FLASH_LIMIT=131072 # half the chip's 256 KiB of flash
FRAMES=(0 200 425 625 875 1100 1200)
ppm() { printf '%s/qemu-m0/fixed-%04d.ppm' "$B" "$1"; }

[ -f "$ELF" ] || { echo "FAIL $ELF is missing (make m0)"; exit 1; }
section() { board_section "$@"; }
if [ "${1:-}" = --print ]; then # make m0: the image's sizes, nothing checked
  printf '%s: flash (vectors+code+rodata+data) %d B (limit %d of the chip'"'"'s 256 KiB), RAM data %d + bss %d, %d B left for the stack of the 16 KiB (make qemu-m0-frames prints the measured peak)\n' \
    "$ELF" $(($(section "$ELF" .vectors) + $(section "$ELF" .text) + $(section "$ELF" .rodata) + $(section "$ELF" .ARM.exidx) + $(section "$ELF" .data))) \
    "$FLASH_LIMIT" "$(section "$ELF" .data)" "$(section "$ELF" .bss)" "$(section "$ELF" .stack)"
  exit 0
fi

rm -rf "$T" && mkdir -p "$T"

# ---- what the image holds -------------------------------------------------------------------
# Instructions ARMv6-M lacks or the port must not use: the long multiplies, the divides, and any
# floating-point or coprocessor instruction; and every 32-bit encoding must be one of ARMv6-M's
# own (bl, mrs, msr, dmb, dsb, isb, udf.w). Literal-pool data (.word) is skipped. Prints the
# offending lines.
bad_instructions() {
  arm-none-eabi-objdump -d "$1" |
    awk -F'\t' 'NF >= 3 && $3 !~ /^\./ {
                  w = $2; gsub(/ +$/, "", w); m = $3; sub(/[ \t].*/, "", m); sub(/\.w$/, "", m)
                  if (m ~ /^(smull|umull|smlal|umlal|sdiv|udiv|smlal[a-z]*|umaal)/ || m ~ /^(v|f)[a-z]/ ||
                      (length(w) == 9 && substr(w, 5, 1) == " " && m !~ /^(bl|mrs|msr|dmb|dsb|isb|udf)$/))
                    print $1 " " $3 }'
}
fp_symbols() {
  arm-none-eabi-nm "$1" |
    awk '{ s = $NF }
         s ~ /^__aeabi_([fd](add|sub|rsub|mul|div|neg|cmp|cmpeq|cmplt|cmple|cmpge|cmpgt|cmpun|2)|[ul]?[il]2[fd]|[fd]2|c[fd](cmp|rcmp))/ ||
         s ~ /^__(add|sub|mul|div|neg|cmp|eq|ne|lt|le|gt|ge|unord)[sdt]f[23]$/ ||
         s ~ /^__(fix|fixuns)[sdt]f[sdt]i$/ || s ~ /^__float(un)?[sdt]i[sdt]f$/ ||
         s ~ /^(sqrt|sin|cos|tan|atan2?|exp|log|pow|floor|ceil|fabs|fmod)f?$/ { print s }' | sort -u
}
bad=$(bad_instructions "$ELF")
[ -z "$bad" ] && pass "m0: image has no SMULL, UMULL, SMLAL, UMLAL, SDIV, UDIV, floating-point or other 32-bit instruction outside ARMv6-M's (bl, mrs, msr, barriers)" ||
  fail "m0: image has instructions ARMv6-M lacks: $(head -5 <<<"$bad" | tr '\n' ' ')"
syms=$(fp_symbols "$ELF")
[ -z "$syms" ] && pass "m0: image calls no soft-float helper or libm function" ||
  fail "m0: image contains floating-point functions: $(echo $syms)"
# Positive controls: the scan finds each of them in a Thumb-2 object, and not its adds and bl;
# the symbol scan finds soft-float helpers in float C compiled for the M0.
ctl=$T/v7m-control.o
printf '\t.syntax unified\n\t.cpu cortex-m4\n\t.fpu fpv4-sp-d16\n\t.thumb\n\tsmull r0, r1, r2, r3\n\tumull r0, r1, r2, r3\n\tsmlal r0, r1, r2, r3\n\tumlal r0, r1, r2, r3\n\tsdiv r0, r1, r2\n\tudiv r0, r1, r2\n\tvadd.f32 s0, s0, s1\n\tldr.w r3, [r2], #4\n\tadds r0, r0, r1\n\tbl 0\n' |
  arm-none-eabi-as -o "$ctl" -
n=$(bad_instructions "$ctl" | wc -l)
[ "$n" -eq 8 ] && pass "m0: positive control: the scan finds the 8 long-multiply, divide, VFP and Thumb-2 instructions of a test object, and not its adds and bl" ||
  fail "m0: positive control: the scan finds $n, not 8, instructions in a Thumb-2 test object"
fctl=$T/float-control.o
printf 'float m0_control(float a, float b) { return a * b + (float)(int)a / b; }\n' |
  arm-none-eabi-gcc -mcpu=cortex-m0 -mthumb -mfloat-abi=soft -O2 -x c -c -o "$fctl" -
n=$(fp_symbols "$fctl" | wc -l)
[ "$n" -ge 3 ] && pass "m0: positive control: the scan finds $n soft-float helpers in float C compiled for the M0" ||
  fail "m0: positive control: the scan finds only $n soft-float helpers in float C compiled for the M0"
# The products go through fx_armv6m.h: the library's 64-bit multiply is called only where an
# operand has more than 32 bits (a few dozen places, none of the tracer's dot products).
calls=$(arm-none-eabi-objdump -d "$ELF" | grep -c 'bl.*<__aeabi_lmul>')
[ "$calls" -le 60 ] && pass "m0: $calls calls of __aeabi_lmul in the image (<= 60: the 32 x 32-bit products are inline)" ||
  fail "m0: $calls calls of __aeabi_lmul in the image (> 60: are the products inline?)"
flash=$(($(section "$ELF" .vectors) + $(section "$ELF" .text) + $(section "$ELF" .rodata) + $(section "$ELF" .ARM.exidx) + $(section "$ELF" .data)))
[ "$flash" -le "$FLASH_LIMIT" ] && pass "m0: flash (vectors+code+rodata+data) $flash B <= $FLASH_LIMIT B" ||
  fail "m0: flash (vectors+code+rodata+data) $flash B > $FLASH_LIMIT B"

# ---- frames ---------------------------------------------------------------------------------
for n in "${FRAMES[@]}"; do
  "$B/rt-fixed" render --size 128x64 --frame "$n" -o "$T/host-$n.ppm" 2>/dev/null || fail "m0: host render of frame $n"
done
for run in 1 2; do
  if platform/m0/qemu.sh frames "${FRAMES[@]}" >"$T/frames-$run.log" 2>&1; then
    pass "m0: qemu-m0-frames, run $run ($(grep -c '^frame=' "$T/frames-$run.log") frames, mean $(sed -n 's/.* mean=//p' "$T/frames-$run.log") instructions)"
  else
    fail "m0: qemu-m0-frames, run $run: $(tail -2 "$T/frames-$run.log" | tr '\n' ' ')"
  fi
  for n in "${FRAMES[@]}"; do
    cmp -s "$(ppm "$n")" "$T/host-$n.ppm" || fail "m0: frame $n (run $run) differs from build/rt-fixed render --size 128x64 --frame $n"
  done
done
same=0
for n in "${FRAMES[@]}"; do cmp -s "$(ppm "$n")" "$T/host-$n.ppm" && same=$((same + 1)); done
[ "$same" -eq ${#FRAMES[@]} ] && pass "m0: frames ${FRAMES[*]}, sent band by band over semihosting, bit-identical to rt-fixed render --size 128x64 (the default settings, grid 8), in both runs"
if [ "$(grep -c '^frame=' "$T/frames-1.log")" -eq ${#FRAMES[@]} ] &&
   diff <(grep '^frame=' "$T/frames-1.log") <(grep '^frame=' "$T/frames-2.log") >/dev/null; then
  pass "m0: two runs give identical instruction counts ($(grep '^frame=' "$T/frames-1.log" | sed 's/.*instructions=//' | tr '\n' ' '))"
else
  fail "m0: instruction counts differ between two runs"
fi

# Render settings on the board: byte for byte the host's with the same settings, not the default.
for S in "--octaves 1 --grid 4 --threshold 0.03 --depth 2 --min-contrib 0.05" "--mode full --octaves 2" \
         "--footprint=off --octaves=2"; do
  n=425
  # shellcheck disable=SC2086  # settings are words on purpose
  if platform/m0/qemu.sh frames $S $n >"$T/set.log" 2>&1 &&
     "$B/rt-fixed" render --size 128x64 --frame $n $S -o "$T/host-set-$n.ppm" 2>/dev/null &&
     cmp -s "$(ppm $n)" "$T/host-set-$n.ppm" && ! cmp -s "$(ppm $n)" "$T/host-$n.ppm"; then
    pass "m0: frame $n with $S bit-identical to rt-fixed render with them, not the default frame ($(sed -n 's/^frame=.* instructions=//p' "$T/set.log") instructions)"
  else
    fail "m0: frame $n with $S: $(tail -2 "$T/set.log" | tr '\n' ' ')"
  fi
done
for S in "--grid 16" "--grid 2" "--depth 6"; do
  # shellcheck disable=SC2086
  out=$(platform/m0/qemu.sh bench $S 0 0 1 2>&1)
  st=$?
  if [ $st -eq 2 ] && grep -Eq '^intro: error: --(grid|depth): ' <<<"$out" && ! grep -q '^frame=' <<<"$out"; then
    pass "m0: bench $S refused on the board: $(grep '^intro: error' <<<"$out")"
  else
    fail "m0: bench $S: status $st: $(tr '\n' ' ' <<<"$out")"
  fi
done

# RAM: .data + .bss + the deepest stack use over the intro, within the chip's 16 KiB.
if platform/m0/qemu.sh bench 0 1200 25 >"$T/bench.log" 2>&1; then
  ram=$(sed -n 's/^ram: .* total=\([0-9]*\) bytes$/\1/p' "$T/bench.log")
  if [ -n "$ram" ] && [ "$ram" -le "$RAM_LIMIT" ]; then
    pass "m0: RAM over 49 intro frames, no frame in it: $(grep '^ram:' "$T/bench.log" | sed 's/^ram: //') <= $RAM_LIMIT"
  else
    fail "m0: RAM: $(grep '^ram:' "$T/bench.log") (limit $RAM_LIMIT)"
  fi
else
  fail "m0: bench 0 1200 25: $(tail -2 "$T/bench.log" | tr '\n' ' ')"
fi

# Probe mode's stack within the RAM too.
if platform/m0/qemu.sh bench --mode probe 0 1200 100 >"$T/probe.log" 2>&1; then
  ram=$(sed -n 's/^ram: .* total=\([0-9]*\) bytes$/\1/p' "$T/probe.log")
  if [ -n "$ram" ] && [ "$ram" -le "$RAM_LIMIT" ]; then
    pass "m0: RAM in probe mode over 13 intro frames: $(grep '^ram:' "$T/probe.log" | sed 's/^ram: //') <= $RAM_LIMIT"
  else
    fail "m0: RAM in probe mode: $(grep '^ram:' "$T/probe.log") (limit $RAM_LIMIT)"
  fi
else
  fail "m0: bench --mode probe 0 1200 100: $(tail -2 "$T/probe.log" | tr '\n' ' ')"
fi

# A CPU exception ends the run through the vector table with status 3 and one line naming it.
board_fault m0 "$T" "-mcpu=cortex-m0 -mthumb -mfloat-abi=soft" platform/m0/link.ld "$B/obj/m0-fixed" "platform/m0/m0.o platform/band.o platform/cortexm.o" \
  '^error: CPU exception: HardFault (pc=0x' -M microbit
lib_status
