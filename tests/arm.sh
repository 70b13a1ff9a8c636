#!/usr/bin/env bash
# arm.sh: the ARM926 images under QEMU against the host builds: bit-identical fixed frames, close soft-float frames, repeatable instruction counts, RAM, display.
#
# Expects make all arm. Prints `ok ...` / `FAIL ...` lines (tests/run.sh counts them) and exits 1
# if any check fails. Frames are those of platform/arm/qemu.sh frames, in build/qemu/.
set -u
cd "$(dirname "$0")/.."

B=build
T=$B/test/arm
rm -rf "$T" && mkdir -p "$T"
RAM_LIMIT=32768
# Intro frames across its five parts (25 fps): t = 0, 8, 17, 25, 35, 44 and 48 s.
FRAMES=(0 200 425 625 875 1100 1200)
status=0
pass() { echo "ok   $*"; }
fail() { echo "FAIL $*"; status=1; }

ppm() { printf '%s/qemu/%s-%04d.ppm' "$B" "$1" "$2"; }

# The budgets that need no run.
tests/arm_check.sh || status=1

for real in fixed float; do
  for n in "${FRAMES[@]}"; do
    "$B/rt-$real" render --size 320x240 --frame "$n" -o "$T/host-$real-$n.ppm" 2>/dev/null ||
      fail "arm: host $real render of frame $n"
  done
done

# Fixed: two runs; the frames equal the host's byte for byte, the counts equal each other.
for run in 1 2; do
  if platform/arm/qemu.sh frames fixed "${FRAMES[@]}" >"$T/fixed-$run.log" 2>&1; then
    pass "arm: qemu-frames fixed, run $run ($(grep -c '^frame=' "$T/fixed-$run.log") frames, mean $(sed -n 's/.* mean=\([0-9]*\).*/\1/p' "$T/fixed-$run.log") instructions)"
  else
    fail "arm: qemu-frames fixed, run $run: $(tail -2 "$T/fixed-$run.log" | tr '\n' ' ')"
  fi
  for n in "${FRAMES[@]}"; do
    cmp -s "$(ppm fixed "$n")" "$T/host-fixed-$n.ppm" || fail "arm: fixed frame $n (run $run) differs from build/rt-fixed render --size 320x240 --frame $n"
  done
done
same=0
for n in "${FRAMES[@]}"; do
  cmp -s "$(ppm fixed "$n")" "$T/host-fixed-$n.ppm" && same=$((same + 1))
done
[ "$same" -eq ${#FRAMES[@]} ] && pass "arm: fixed frames ${FRAMES[*]} bit-identical to the host's rt-fixed, in both runs"
if [ "$(grep -c '^frame=' "$T/fixed-1.log")" -eq ${#FRAMES[@]} ] &&
   diff <(grep '^frame=' "$T/fixed-1.log") <(grep '^frame=' "$T/fixed-2.log") >/dev/null; then
  pass "arm: two runs give identical instruction and cycle counts ($(grep '^frame=' "$T/fixed-1.log" | sed 's/.*instructions=//' | tr '\n' ' '))"
else
  fail "arm: instruction or cycle counts differ between two runs"
fi

# The profiler (make qemu-profile): the TCG plugin's count inside frames 425 and 875 equals the
# board's own icount figures for them (from the run above) to within 200 instructions a frame,
# known hot functions have their share, and the plugin leaves the pictures alone.
if PROFILE_TOP=200 platform/arm/profile.sh fixed 425 875 >"$T/profile.txt" 2>&1; then
  inside=$(sed -n 's/^inside the frames: \([0-9]*\) instructions over 2 frames.*/\1/p' "$T/profile.txt")
  board=$(sed -n 's/^frame=\(425\|875\) instructions=\([0-9]*\) .*/\2/p' "$T/fixed-1.log" | awk '{ s += $1 } END { print s + 0 }')
  share() { awk -v f="$1" '/^by containing function/ { on = 1; next } /^$/ { on = 0 } on && $6 == f { print $2 }' "$T/profile.txt"; }
  occ=$(share rt_occluded)
  norm=$(share fx_ray_dir)
  if [ -n "$inside" ] && [ "$board" -gt 0 ] && [ $((inside > board ? inside - board : board - inside)) -le 400 ] &&
     [ -n "$occ" ] && [ "$occ" != "0.00%" ] && [ -n "$norm" ] && [ "$norm" != "0.00%" ] &&
     cmp -s "$(ppm fixed 425)" "$T/host-fixed-425.ppm" && cmp -s "$(ppm fixed 875)" "$T/host-fixed-875.ppm"; then
    pass "arm: qemu-profile frames 425 875: $inside instructions inside the frames, the board's icount $board; rt_occluded $occ, fx_ray_dir $norm; frames unchanged"
  else
    fail "arm: qemu-profile frames 425 875: plugin $inside vs board $board instructions, rt_occluded '$occ', fx_ray_dir '$norm' (or the frames changed): $(tail -3 "$T/profile.txt" | tr '\n' ' ')"
  fi
else
  fail "arm: qemu-profile frames 425 875: $(tail -3 "$T/profile.txt" | tr '\n' ' ')"
fi

# The cheaper fixed-point variant (unit in Q16.16, build/arm/intro-fixed16.elf): its frames
# equal the host's rt-fixed16 byte for byte too.
if platform/arm/qemu.sh frames fixed16 "${FRAMES[@]}" >"$T/fixed16.log" 2>&1; then
  same=0
  for n in "${FRAMES[@]}"; do
    "$B/rt-fixed16" render --size 320x240 --frame "$n" -o "$T/host-fixed16-$n.ppm" 2>/dev/null &&
      cmp -s "$(ppm fixed16 "$n")" "$T/host-fixed16-$n.ppm" && same=$((same + 1))
  done
  if [ "$same" -eq ${#FRAMES[@]} ]; then
    pass "arm: fixed16 frames ${FRAMES[*]} bit-identical to the host's rt-fixed16 (mean $(sed -n 's/.* mean=\([0-9]*\).*/\1/p' "$T/fixed16.log") instructions; fixed: $(sed -n 's/.* mean=\([0-9]*\).*/\1/p' "$T/fixed-1.log"))"
  else
    fail "arm: $((${#FRAMES[@]} - same)) of the fixed16 frames ${FRAMES[*]} differ from build/rt-fixed16 render --size 320x240"
  fi
else
  fail "arm: qemu-frames fixed16: $(tail -2 "$T/fixed16.log" | tr '\n' ' ')"
fi
# Render settings on the board (qemu.sh passes them to src/app/intro.c): each set gives frames
# byte for byte those of the host's rt-fixed with the same settings, other pictures than the
# default's, and other instruction counts.
SET_FRAMES=(425 875)
for S in "--octaves 1 --grid 4 --threshold 0.03 --depth 2 --min-contrib 0.05" "--mode=full --octaves=2" \
  "--footprint off" "--mode probe"; do
  tag=$(tr -c 'a-z0-9\n' _ <<<"$S")
  # shellcheck disable=SC2086  # settings are words on purpose
  if platform/arm/qemu.sh frames fixed $S "${SET_FRAMES[@]}" >"$T/set-$tag.log" 2>&1; then
    bad=""
    for n in "${SET_FRAMES[@]}"; do
      # shellcheck disable=SC2086
      "$B/rt-fixed" render --size 320x240 --frame "$n" $S -o "$T/host-set-$tag-$n.ppm" 2>/dev/null || bad="$bad host render of $n failed;"
      cmp -s "$(ppm fixed "$n")" "$T/host-set-$tag-$n.ppm" || bad="$bad frame $n differs from the host's;"
      cmp -s "$(ppm fixed "$n")" "$T/host-fixed-$n.ppm" && bad="$bad frame $n is the default frame;"
      c=$(sed -n "s/^frame=$n instructions=\([0-9]*\) .*/\1/p" "$T/set-$tag.log")
      c0=$(sed -n "s/^frame=$n instructions=\([0-9]*\) .*/\1/p" "$T/fixed-1.log")
      { [ -n "$c" ] && [ "$c" -gt 0 ] && [ "$c" != "$c0" ]; } || bad="$bad frame $n: $c instructions (default $c0);"
      counts="${counts:-}$n: $c (default $c0) "
    done
    if [ -z "$bad" ]; then
      pass "arm: fixed frames ${SET_FRAMES[*]} with $S bit-identical to rt-fixed render with them, not the default frames; instructions ${counts}"
    else
      fail "arm: settings $S:$bad"
    fi
    counts=""
  else
    fail "arm: qemu-frames fixed $S: $(tail -2 "$T/set-$tag.log" | tr '\n' ' ')"
  fi
done
# A setting the board cannot take gets one line and status 2, before any frame.
for S in "--grid 16" "--octaves 9" "--threshold=2" "--depth 2 --depth=3" "--footprint 1"; do
  # shellcheck disable=SC2086
  out=$(platform/arm/qemu.sh bench fixed $S 0 0 1 2>&1)
  st=$?
  if [ $st -eq 2 ] && grep -q "^intro: error: ${S%%[ =]*}: " <<<"$out" && ! grep -q '^frame=' <<<"$out"; then
    pass "arm: bench $S refused on the board: $(grep '^intro: error' <<<"$out")"
  else
    fail "arm: bench $S: status $st: $(tr '\n' ' ' <<<"$out")"
  fi
done

# Soft-float: the same sources in float, against the host's float build.
if platform/arm/qemu.sh frames float "${FRAMES[@]}" >"$T/float.log" 2>&1; then
  pass "arm: qemu-frames float ($(grep -c '^frame=' "$T/float.log") frames, mean $(sed -n 's/.* mean=\([0-9]*\).*/\1/p' "$T/float.log") instructions)"
else
  fail "arm: qemu-frames float: $(tail -2 "$T/float.log" | tr '\n' ' ')"
fi
for n in "${FRAMES[@]}"; do
  line=$($B/rt-cmp "$(ppm float "$n")" "$T/host-float-$n.ppm" 2>&1)
  psnr=$(sed -n 's/.*psnr_db=\([^ ]*\).*/\1/p' <<<"$line")
  if [ -n "$psnr" ] && { [ "$psnr" = inf ] || awk -v p="$psnr" 'BEGIN { exit !(p >= 40) }'; }; then
    pass "arm: soft-float frame $n vs host float: $line"
  else
    fail "arm: soft-float frame $n vs host float (want psnr >= 40): $line"
  fi
done

# RAM: .data + .bss + the deepest stack use, over a stretch of the whole intro.
if platform/arm/qemu.sh bench fixed 0 1200 50 >"$T/bench.log" 2>&1; then
  ram=$(sed -n 's/^ram: .* total=\([0-9]*\) bytes$/\1/p' "$T/bench.log")
  if [ -n "$ram" ] && [ "$ram" -le "$RAM_LIMIT" ]; then
    pass "arm: RAM besides the framebuffers, 25 intro frames: $(grep '^ram:' "$T/bench.log" | sed 's/^ram: //') <= $RAM_LIMIT"
  else
    fail "arm: RAM: $(grep '^ram:' "$T/bench.log") (limit $RAM_LIMIT)"
  fi
else
  fail "arm: bench fixed 0 1200 50: $(tail -2 "$T/bench.log" | tr '\n' ' ')"
fi

# A CPU exception ends the run through the vectors with status 3 and a line naming it, instead
# of restarting the program (tests/arm_fault.c on the same start-up code and backend).
AO=$B/obj/arm-fixed
ARM="-mcpu=arm926ej-s -marm -mfloat-abi=soft"
if arm-none-eabi-gcc -std=c11 -O2 $ARM -ffreestanding -Iplatform -c tests/arm_fault.c -o "$T/arm_fault.o" &&
   arm-none-eabi-gcc $ARM -nostartfiles -T platform/arm/link.ld -Wl,--gc-sections -Wl,-z,noexecstack \
     -Wl,--no-warn-rwx-segments -o "$T/arm_fault.elf" "$T/arm_fault.o" "$AO/start.o" "$AO/platform/board.o" "$AO/platform/arm/arm.o" -lc -lgcc; then
  timeout --foreground -k 5 30 qemu-system-arm -M versatilepb -m 2 -display none -serial stdio -monitor none \
    -audiodev none,id=snd0 -global pl041.audiodev=snd0 -semihosting-config enable=on,target=native,arg=fault \
    -kernel "$T/arm_fault.elf" </dev/null >"$T/fault.log" 2>&1
  st=$?
  if [ $st -eq 3 ] && grep -q '^error: CPU exception: undefined instruction' "$T/fault.log" &&
     [ "$(grep -c 'executing an undefined' "$T/fault.log")" -eq 1 ]; then
    pass "arm: an undefined instruction ends the run with status 3: $(grep '^error' "$T/fault.log")"
  else
    fail "arm: undefined instruction: status $st, $(tr '\n' ' ' <"$T/fault.log" | cut -c1-200)"
  fi
else
  fail "arm: could not build tests/arm_fault.c"
fi

# The display: the PL110 shows a frame exactly as rendered (QEMU's screendump through the monitor).
n=875
rm -f "$T/serial.log" "$T/screen.ppm"
{
  for _ in $(seq 300); do grep -q '^shown' "$T/serial.log" 2>/dev/null && break; sleep 0.1; done
  echo "screendump $T/screen.ppm"
  sleep 1
  echo quit
} | timeout --foreground -k 5 60 qemu-system-arm -M versatilepb -m 2 -display none -monitor stdio -serial "file:$T/serial.log" \
      -audiodev none,id=snd0 -global pl041.audiodev=snd0 \
      -semihosting-config enable=on,target=native,arg=intro,arg=show,arg=$n \
      -kernel "$B/arm/intro-fixed.elf" >"$T/monitor.log" 2>&1
if [ -f "$T/screen.ppm" ] && cmp -s "$T/screen.ppm" "$T/host-fixed-$n.ppm"; then
  pass "arm: the PL110 framebuffer shows frame $n exactly as rt-fixed renders it (screendump)"
else
  fail "arm: screendump of frame $n on the PL110: $($B/rt-cmp "$T/screen.ppm" "$T/host-fixed-$n.ppm" 2>&1)"
fi
exit $status
