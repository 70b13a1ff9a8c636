#!/usr/bin/env bash
# m3.sh: the Cortex-M3 image: static budgets (no floating point, flash, RAM) and runs under QEMU (lm3s6965evb) against the host build: bit-identical 128x64 frames sent band by band, repeatable counts, RAM budget, the OLED's grey picture, faults.
#
# Usage: tests/m3.sh [--print | --static]
#   Expects make all m3. Prints `ok ...` / `FAIL ...` lines (tests/run.sh counts them) and exits
#   1 if any check fails. Frames are those of platform/m3/qemu.sh frames, in build/qemu-m3/.
#   --static: only the budgets that need no run; --print: only the image's sizes (make m3).
# The budgets: build/m3/intro-fixed.elf has no floating-point or coprocessor instruction, no
# soft-float helper or libm function and only the allowed library members (the scans do find
# VFP/coprocessor instructions in a Thumb object assembled here and soft-float helpers in a
# Cortex-M3 object compiled from float C); flash: vector table + code + read-only data +
# initialised data <= 64 KiB; RAM: .data + .bss + the 8 KiB stack reserve <= 32 KiB (the budget,
# 24 KiB with the measured stack peak instead of the reserve, is checked from a run).
set -u
cd "$(dirname "$0")/.."
# These runs check frames and instruction counts: no cycle estimate (its plugin makes QEMU several
# times slower); tests/cycles.sh checks the cycles. CYCLES=1 in the environment keeps it.
export CYCLES=${CYCLES:-0}
. tests/lib.sh
. tests/board.sh

ELF=$B/m3/intro-fixed.elf
FLASH_LIMIT=65536
RESERVE_LIMIT=32768
RAM_LIMIT=24576   # a third of the chip's 64 KiB: data + bss + the measured stack peak
RAM_STRETCH=16384
flash_bytes() { echo $(($(board_section "$1" .vectors) + $(board_code_bytes "$1"))); }

if [ "${1:-}" = --print ]; then
  printf '%s: flash (vectors+code+rodata+data) %d B (limit %d of the chip'"'"'s 256 KiB), RAM data %d + bss %d + stack reserve %d = %d B of 64 KiB (make qemu-m3-frames prints the measured peak)\n' \
    "$ELF" "$(flash_bytes "$ELF")" "$FLASH_LIMIT" "$(board_section "$ELF" .data)" "$(board_section "$ELF" .bss)" \
    "$(board_section "$ELF" .stack)" "$(board_ram_bytes "$ELF")"
  exit 0
fi

# ---- the budgets that need no run ----------------------------------------------------------------
board_image "$ELF"
board_no_float "m3: image" thumb2 "$ELF"
board_only_allowed "m3: image" "$ELF" "$(board_allowed)" "libfixmath, memcpy/memset/memcmp, integer division"
# Positive controls: VFP and coprocessor instructions in a Thumb object (in and out of an IT
# block) are found, its bkpt, add and 32-bit load are not; float C compiled for the M3 calls
# soft-float helpers that the symbol scan finds.
ctl=$B/m3/vfp-control.o
printf '\t.syntax unified\n\t.cpu cortex-m4\n\t.fpu fpv4-sp-d16\n\t.thumb\n\tvadd.f32 s0, s0, s1\n\tvmul.f32 s2, s0, s1\n\tmrc p15, 0, r0, c0, c0, 0\n\tit eq\n\tvaddeq.f32 s0, s0, s1\n\tldc p1, c0, [r0]\n\tcdp p10, 0, c0, c1, c2, 0\n\tvmov r0, s0\n\tbkpt 0xab\n\tadd r0, r0, r1\n\tldr.w r3, [r2], #4\n' |
  arm-none-eabi-as -o "$ctl" -
board_scan_control m3 thumb2 "$ctl" "a Thumb test object (one in an IT block), and not its bkpt, add and ldr.w"
fctl=$B/m3/float-control.o
printf 'float m3_control(float a, float b) { return a * b + (float)(int)a / b; }\n' |
  arm-none-eabi-gcc -mcpu=cortex-m3 -mthumb -mfloat-abi=soft -O2 -x c -c -o "$fctl" -
syms=$(board_fp_symbols "$fctl" | wc -l)
[ "$syms" -ge 3 ] && pass "m3: positive control: the scan finds $syms soft-float helpers in float C compiled for the M3" ||
  fail "m3: positive control: the scan finds only $syms soft-float helpers in float C compiled for the M3"
board_within "m3:" "flash (vectors+code+rodata+data)" "$(flash_bytes "$ELF")" "$FLASH_LIMIT"
board_within "m3:" "data+bss+stack reserve" "$(board_ram_bytes "$ELF")" "$RESERVE_LIMIT"
[ "${1:-}" = --static ] && { lib_status; exit; }

# ---- runs under QEMU ---------------------------------------------------------------------------------
T=$B/test/m3
rm -rf "$T" && mkdir -p "$T"
FRAMES=(0 200 425 625 875 1100 1200)
ppm() { printf '%s/qemu-m3/fixed-%04d.ppm' "$B" "$1"; }

for n in "${FRAMES[@]}"; do
  "$B/rt-fixed" render --size 128x64 --frame "$n" -o "$T/host-$n.ppm" 2>/dev/null || fail "m3: host render of frame $n"
done

# Two runs: frames, sent band by band over semihosting, equal the host's byte for byte, counts
# equal each other.
board_two_runs m3 frames ppm host "rt-fixed render --size 128x64" platform/m3/qemu.sh frames

# Render settings on the board: byte for byte the host's with the same settings, not the default.
for S in "--octaves 1 --grid 4 --threshold 0.03 --depth 2 --min-contrib 0.05" "--mode full --octaves 2" \
         "--footprint off" "--footprint=off --octaves=2"; do
  n=425
  # shellcheck disable=SC2086  # settings are words on purpose
  if platform/m3/qemu.sh frames $S $n >"$T/set.log" 2>&1 &&
     "$B/rt-fixed" render --size 128x64 --frame $n $S -o "$T/host-set-$n.ppm" 2>/dev/null &&
     cmp -s "$(ppm $n)" "$T/host-set-$n.ppm" && ! cmp -s "$(ppm $n)" "$T/host-$n.ppm"; then
    pass "m3: frame $n with $S bit-identical to rt-fixed render with them, not the default frame ($(sed -n 's/^frame=.* instructions=\([0-9]*\).*/\1/p' "$T/set.log") instructions)"
  else
    fail "m3: frame $n with $S: $(tail -2 "$T/set.log" | tr '\n' ' ')"
  fi
done
for S in "--grid 16" "--grid 2"; do
  board_refused m3 "$S" platform/m3/qemu.sh bench
done

# RAM: .data + .bss + the deepest stack use over the intro, within a third of the chip; the
# report says whether it is within the stretch goal too.
stretch() { [ "$1" -le "$RAM_STRETCH" ] && echo "within the $RAM_STRETCH B stretch goal too" || echo "over the $RAM_STRETCH B stretch goal"; }
board_ram m3 "$RAM_LIMIT" stretch platform/m3/qemu.sh bench 0 1200 50

# The grey conversion: known colours give the documented levels (luma, then 16 levels).
printf 'P6\n6 1\n255\n\0\0\0\377\377\377\377\0\0\0\377\0\0\0\377\200\200\200' >"$T/colours.ppm"
if "$B/rt-cmp" --oled "$T/colours.ppm" "$T/colours-oled.ppm" 2>"$T/oled.err"; then
  # one row of the 24x4 picture: every 4th pixel's grey
  got=$(tail -c $((24 * 4 * 3)) "$T/colours-oled.ppm" | head -c $((24 * 3)) | od -An -tu1 -w3 -v | awk 'NR % 4 == 1 { printf "%s%d", sep, $1; sep = " " }')
  [ "$got" = "0 255 85 153 34 136" ] && pass "m3: grey levels of black, white, red, green, blue, grey 128: $got (17 x level)" ||
    fail "m3: grey levels of black, white, red, green, blue, grey 128: got '$got', want '0 255 85 153 34 136'"
else
  fail "m3: rt-cmp --oled: $(cat "$T/oled.err")"
fi

# The OLED: what QEMU's SSD0323 shows (its screendump) is the host's grey picture of the frame.
n=875
if platform/m3/qemu.sh show $n "$T/screen.ppm" >"$T/show.log" 2>&1 &&
   "$B/rt-cmp" --oled "$T/host-$n.ppm" "$T/oled-$n.ppm" 2>>"$T/show.log" && cmp -s "$T/screen.ppm" "$T/oled-$n.ppm"; then
  pass "m3: the OLED shows frame $n exactly as rt-cmp --oled turns the host's frame into 16 greys (screendump, 512x256)"
else
  fail "m3: screendump of frame $n on the OLED: $(tail -2 "$T/show.log" | tr '\n' ' ') $($B/rt-cmp "$T/screen.ppm" "$T/oled-$n.ppm" 2>&1)"
fi

# play (make qemu-m3, here without a window and in real time): the intro runs on the OLED, looping;
# two screendumps 2 s apart show two different pictures, neither of them blank.
rm -f "$T/play-1.ppm" "$T/play-2.ppm"
{
  sleep 3; echo "screendump $T/play-1.ppm"; sleep 2; echo "screendump $T/play-2.ppm"; sleep 1; echo quit
} | timeout --foreground -k 5 60 qemu-system-arm -M lm3s6965evb -kernel "$B/m3/intro-fixed.elf" -display none \
      -monitor stdio -serial "file:$T/play.log" -semihosting-config enable=on,target=native,arg=intro,arg=play \
      >/dev/null 2>&1
levels() { tail -c +16 "$1" | od -An -tu1 -v -w1 | sort -u | wc -l; }
if [ -s "$T/play-1.ppm" ] && [ -s "$T/play-2.ppm" ] && ! cmp -s "$T/play-1.ppm" "$T/play-2.ppm" &&
   [ "$(levels "$T/play-1.ppm")" -ge 4 ] && [ "$(levels "$T/play-2.ppm")" -ge 4 ] && grep -q '^intro: playing looped' "$T/play.log"; then
  pass "m3: play shows the intro moving on the OLED (two screendumps 2 s apart differ, $(levels "$T/play-1.ppm") and $(levels "$T/play-2.ppm") grey levels)"
else
  fail "m3: play: $(tr '\n' ' ' <"$T/play.log" | cut -c1-200)"
fi

# A CPU exception ends the run through the vector table with status 3 and one line naming it.
board_fault m3 "$T" "-mcpu=cortex-m3 -mthumb -mfloat-abi=soft" platform/m3/link.ld "$B/obj/m3-fixed" "platform/m3/m3.o platform/band.o platform/cortexm.o" \
  '^error: CPU exception: HardFault (pc=0x' -M lm3s6965evb
lib_status
