#!/usr/bin/env bash
# arm.sh: the ARM926 images: static budgets (no floating point, 64 KiB of code, RAM) and runs under QEMU against the host builds (bit-identical fixed frames, close soft-float frames, repeatable instruction counts, RAM, display).
#
# Usage: tests/arm.sh [--print | --static]
#   Expects make all arm. Prints `ok ...` / `FAIL ...` lines (tests/run.sh counts them) and exits
#   1 if any check fails. Frames are those of platform/arm/qemu.sh frames, in build/qemu/.
#   --static: only the budgets that need no run; --print: only the images' sizes (make arm).
# The budgets: build/arm/intro-fixed.elf and intro-fixed16.elf have no VFP/coprocessor
# instruction and no soft-float helper or libm function (the scans do find them in intro-float.elf
# and in a small object assembled here); the fixed image links only allowed library code, has at
# most 64 KiB of code + read-only data + initialised data (the original's limit) and at most
# 32 KiB of .data + .bss + reserved stack (the measured stack peak is checked from a run).
set -u
cd "$(dirname "$0")/.."
# These runs check frames and instruction counts: no cycle estimate (its plugin makes QEMU several
# times slower); tests/cycles.sh checks the cycles. CYCLES=1 in the environment keeps it.
export CYCLES=${CYCLES:-0}
. tests/lib.sh
. tests/board.sh

FIXED=$B/arm/intro-fixed.elf
FLOAT=$B/arm/intro-float.elf
FIXED16=$B/arm/intro-fixed16.elf
CODE_LIMIT=65536
RAM_LIMIT=32768

if [ "${1:-}" = --print ]; then
  for f in "$FIXED" "$FIXED16" "$FLOAT"; do
    [ -f "$f" ] || continue
    # the 64 KiB limit is the fixed images' (the soft-float image is the comparison build)
    limit="limit $CODE_LIMIT" ram_limit="limit $RAM_LIMIT"
    [ "$f" = "$FLOAT" ] && limit="comparison build, no limit" && ram_limit="no limit"
    printf '%s: code+rodata+data %d B (%s), data %d + bss %d + stack reserve %d = %d B RAM (%s), framebuffers %d B\n' \
      "$f" "$(board_code_bytes "$f")" "$limit" "$(board_section "$f" .data)" "$(board_section "$f" .bss)" \
      "$(board_section "$f" .stack)" "$(board_ram_bytes "$f")" "$ram_limit" "$(board_section "$f" .fb)"
  done
  exit 0
fi

# ---- the budgets that need no run ----------------------------------------------------------------
board_image "$FIXED"
board_image "$FLOAT"
board_no_float "arm: fixed image" arm "$FIXED"
if [ -f "$FIXED16" ]; then
  n=$(board_fp_instructions arm "$FIXED16")
  syms=$(board_fp_symbols "$FIXED16")
  if [ "$n" -eq 0 ] && [ -z "$syms" ]; then
    pass "arm: fixed16 image has no floating-point instruction, soft-float helper or libm function (code+rodata+data $(board_code_bytes "$FIXED16") B)"
  else
    fail "arm: fixed16 image: $n floating-point/coprocessor instructions, functions: $(tr '\n' ' ' <<<"$syms")"
  fi
else
  fail "arm: $FIXED16 is missing (make arm)"
fi
# the switch-table helpers of the Thumb code (Makefile: ARM_COLD_SRCS) besides the common members
ALLOWED=$(board_allowed 'thumb1_case_[su]?[qh]i')
board_only_allowed "arm: fixed image" "$FIXED" "$ALLOWED" "libfixmath, memcpy/memset/memcmp, integer division, Thumb switch tables"
# Positive controls: the float image is full of soft-float helpers and libm, and the instruction
# scan finds VFP/coprocessor instructions, conditional ones too, in an object that has some.
others=$(board_members "$FLOAT" | grep -Ev "$ALLOWED" | wc -l)
[ "$others" -ge 5 ] && pass "arm: positive control: the float image links $others library members outside the allow-list" ||
  fail "arm: positive control: the float image links only $others library members outside the allow-list"
syms=$(board_fp_symbols "$FLOAT" | wc -l)
[ "$syms" -ge 5 ] && pass "arm: positive control: the scan finds $syms soft-float/libm functions in the float image" ||
  fail "arm: positive control: the scan finds only $syms floating-point functions in the float image"
ctl=$B/arm/vfp-control.o
printf '\t.arm\n\t.fpu vfp\n\tvadd.f32 s0, s0, s1\n\tvmul.f64 d0, d1, d2\n\tmrc p15, 0, r0, c0, c0, 0\n\tvaddeq.f32 s0, s0, s1\n\tmrceq p15, 0, r0, c0, c0, 0\n\tldceq p1, c0, [r0]\n\tcdpne p10, 0, c0, c1, c2, 0\n\tsvc 0x123456\n\tadd r0, r0, r1\n' |
  arm-none-eabi-as -mcpu=arm926ej-s -o "$ctl" -
board_scan_control arm arm "$ctl" "a test object (conditional ones too), and not its svc and add"
board_within "arm: fixed image" code+rodata+data "$(board_code_bytes "$FIXED")" "$CODE_LIMIT"
board_within "arm: fixed image" "data+bss+stack reserve (framebuffers apart)" "$(board_ram_bytes "$FIXED")" "$RAM_LIMIT"
[ "${1:-}" = --static ] && { lib_status; exit; }

# ---- runs under QEMU ---------------------------------------------------------------------------------
T=$B/test/arm
rm -rf "$T" && mkdir -p "$T"
# Intro frames across its five parts (25 fps): t = 0, 8, 17, 25, 35, 44 and 48 s.
FRAMES=(0 200 425 625 875 1100 1200)
ppm() { printf '%s/qemu/%s-%04d.ppm' "$B" "$1" "$2"; }

for real in fixed float; do
  for n in "${FRAMES[@]}"; do
    "$B/rt-$real" render --size 320x240 --frame "$n" -o "$T/host-$real-$n.ppm" 2>/dev/null ||
      fail "arm: host $real render of frame $n"
  done
done

# Fixed: two runs; the frames equal the host's byte for byte, the counts equal each other.
ppm_fixed() { ppm fixed "$1"; }
board_two_runs arm fixed ppm_fixed host-fixed "the host's rt-fixed render --size 320x240" platform/arm/qemu.sh frames fixed

# The profiler (make qemu-profile): the TCG plugin's count inside frames 425 and 875 equals the
# board's own icount figures for them (from the run above) to within 200 instructions a frame,
# known hot functions have their share, and the plugin leaves the pictures alone.
if PROFILE_TOP=200 platform/arm/profile.sh fixed 425 875 >"$T/profile.txt" 2>&1; then
  inside=$(sed -n 's/^inside the frames: \([0-9]*\) instructions over 2 frames.*/\1/p' "$T/profile.txt")
  board=$(sed -n 's/^frame=\(425\|875\) instructions=\([0-9]*\).*/\2/p' "$T/fixed-1.log" | awk '{ s += $1 } END { print s + 0 }')
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
      c=$(sed -n "s/^frame=$n instructions=\([0-9]*\).*/\1/p" "$T/set-$tag.log")
      c0=$(sed -n "s/^frame=$n instructions=\([0-9]*\).*/\1/p" "$T/fixed-1.log")
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
  board_refused arm "$S" platform/arm/qemu.sh bench fixed
done

# Soft-float: the same sources in float, against the host's float build.
if platform/arm/qemu.sh frames float "${FRAMES[@]}" >"$T/float.log" 2>&1; then
  pass "arm: qemu-frames float ($(grep -c '^frame=' "$T/float.log") frames, mean $(sed -n 's/.* mean=\([0-9]*\).*/\1/p' "$T/float.log") instructions)"
else
  fail "arm: qemu-frames float: $(tail -2 "$T/float.log" | tr '\n' ' ')"
fi
for n in "${FRAMES[@]}"; do
  line=$($B/rt-cmp "$(ppm float "$n")" "$T/host-float-$n.ppm" 2>&1)
  psnr=$(field psnr_db "$line")
  if [ -n "$psnr" ] && { [ "$psnr" = inf ] || awk -v p="$psnr" 'BEGIN { exit !(p >= 40) }'; }; then
    pass "arm: soft-float frame $n vs host float: $line"
  else
    fail "arm: soft-float frame $n vs host float (want psnr >= 40): $line"
  fi
done

# RAM besides the framebuffers: .data + .bss + the deepest stack use, over a stretch of the whole intro.
board_ram arm "$RAM_LIMIT" "" platform/arm/qemu.sh bench fixed 0 1200 50

# A CPU exception ends the run through the vectors with status 3 and a line naming it, instead
# of restarting the program (tests/arm_fault.c on the same start-up code and backend).
board_fault arm "$T" "-mcpu=arm926ej-s -marm -mfloat-abi=soft" platform/arm/link.ld "$B/obj/arm-fixed" platform/arm/arm.o \
  '^error: CPU exception: undefined instruction' -M versatilepb -m 2 -audiodev none,id=snd0 -global pl041.audiodev=snd0

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
lib_status
