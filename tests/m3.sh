#!/usr/bin/env bash
# m3.sh: the Cortex-M3 image under QEMU (lm3s6965evb) against the host build: bit-identical 128x64 frames sent band by band, repeatable counts, RAM budget, the OLED's grey picture, faults.
#
# Expects make all m3. Prints `ok ...` / `FAIL ...` lines (tests/run.sh counts them) and exits 1
# if any check fails. Frames are those of platform/m3/qemu.sh frames, in build/qemu-m3/.
set -u
cd "$(dirname "$0")/.."

B=build
T=$B/test/m3
rm -rf "$T" && mkdir -p "$T"
RAM_LIMIT=24576   # a third of the chip's 64 KiB: data + bss + the measured stack peak
RAM_STRETCH=16384
FRAMES=(0 200 425 625 875 1100 1200)
status=0
pass() { echo "ok   $*"; }
fail() { echo "FAIL $*"; status=1; }
ppm() { printf '%s/qemu-m3/fixed-%04d.ppm' "$B" "$1"; }

# The budgets that need no run.
tests/m3_check.sh || status=1

for n in "${FRAMES[@]}"; do
  "$B/rt-fixed" render --size 128x64 --frame "$n" -o "$T/host-$n.ppm" 2>/dev/null || fail "m3: host render of frame $n"
done

# Two runs: frames equal the host's byte for byte, counts equal each other.
for run in 1 2; do
  if platform/m3/qemu.sh frames "${FRAMES[@]}" >"$T/frames-$run.log" 2>&1; then
    pass "m3: qemu-m3-frames, run $run ($(grep -c '^frame=' "$T/frames-$run.log") frames, mean $(sed -n 's/.* mean=\([0-9]*\).*/\1/p' "$T/frames-$run.log") instructions)"
  else
    fail "m3: qemu-m3-frames, run $run: $(tail -2 "$T/frames-$run.log" | tr '\n' ' ')"
  fi
  for n in "${FRAMES[@]}"; do
    cmp -s "$(ppm "$n")" "$T/host-$n.ppm" || fail "m3: frame $n (run $run) differs from build/rt-fixed render --size 128x64 --frame $n"
  done
done
same=0
for n in "${FRAMES[@]}"; do cmp -s "$(ppm "$n")" "$T/host-$n.ppm" && same=$((same + 1)); done
[ "$same" -eq ${#FRAMES[@]} ] && pass "m3: frames ${FRAMES[*]}, sent band by band over semihosting, bit-identical to rt-fixed render --size 128x64, in both runs"
if [ "$(grep -c '^frame=' "$T/frames-1.log")" -eq ${#FRAMES[@]} ] &&
   diff <(grep '^frame=' "$T/frames-1.log") <(grep '^frame=' "$T/frames-2.log") >/dev/null; then
  pass "m3: two runs give identical instruction and cycle counts ($(grep '^frame=' "$T/frames-1.log" | sed 's/.*instructions=//' | tr '\n' ' '))"
else
  fail "m3: instruction counts differ between two runs"
fi

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
  # shellcheck disable=SC2086
  out=$(platform/m3/qemu.sh bench $S 0 0 1 2>&1)
  st=$?
  if [ $st -eq 2 ] && grep -q '^intro: error: --grid: ' <<<"$out" && ! grep -q '^frame=' <<<"$out"; then
    pass "m3: bench $S refused on the board: $(grep '^intro: error' <<<"$out")"
  else
    fail "m3: bench $S: status $st: $(tr '\n' ' ' <<<"$out")"
  fi
done

# RAM: .data + .bss + the deepest stack use over the intro, within a third of the chip.
if platform/m3/qemu.sh bench 0 1200 50 >"$T/bench.log" 2>&1; then
  ram=$(sed -n 's/^ram: .* total=\([0-9]*\) bytes$/\1/p' "$T/bench.log")
  if [ -n "$ram" ] && [ "$ram" -le "$RAM_LIMIT" ]; then
    stretch="over the $RAM_STRETCH B stretch goal"
    [ "$ram" -le "$RAM_STRETCH" ] && stretch="within the $RAM_STRETCH B stretch goal too"
    pass "m3: RAM over 25 intro frames, no frame in it: $(grep '^ram:' "$T/bench.log" | sed 's/^ram: //') <= $RAM_LIMIT ($stretch)"
  else
    fail "m3: RAM: $(grep '^ram:' "$T/bench.log") (limit $RAM_LIMIT)"
  fi
else
  fail "m3: bench 0 1200 50: $(tail -2 "$T/bench.log" | tr '\n' ' ')"
fi

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
MO=$B/obj/m3-fixed
M3="-mcpu=cortex-m3 -mthumb -mfloat-abi=soft"
# shellcheck disable=SC2086
if arm-none-eabi-gcc -std=c11 -O2 $M3 -ffreestanding -Iplatform -c tests/arm_fault.c -o "$T/fault.o" &&
   arm-none-eabi-gcc $M3 -nostartfiles -T platform/m3/link.ld -Wl,--gc-sections -Wl,-z,noexecstack \
     -Wl,--no-warn-rwx-segments -o "$T/fault.elf" "$T/fault.o" "$MO/start.o" "$MO/platform/board.o" "$MO/platform/m3/m3.o" -lc -lgcc; then
  timeout --foreground -k 5 30 qemu-system-arm -M lm3s6965evb -display none -serial stdio -monitor none \
    -semihosting-config enable=on,target=native,arg=fault -kernel "$T/fault.elf" </dev/null >"$T/fault.log" 2>&1
  st=$?
  if [ $st -eq 3 ] && [ "$(grep -c '^error: CPU exception: HardFault (pc=0x' "$T/fault.log")" -eq 1 ] &&
     ! grep -q 'still running' "$T/fault.log"; then
    pass "m3: an undefined instruction ends the run with status 3: $(grep '^error' "$T/fault.log")"
  else
    fail "m3: undefined instruction: status $st, $(tr '\n' ' ' <"$T/fault.log" | cut -c1-200)"
  fi
else
  fail "m3: could not build tests/arm_fault.c for the M3"
fi
exit $status
