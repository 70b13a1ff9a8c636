#!/usr/bin/env bash
# qemu.sh: runs the Cortex-M0 intro image on qemu-system-arm -M microbit (an nRF51822, 16 KiB of SRAM): render frames to files or benchmark a stretch.
#
# Usage (from the top of the repository; make qemu-m0-frames calls it):
#   platform/m0/qemu.sh frames [SETTINGS] N...             build/qemu-m0/fixed-NNNN.ppm (128x64 colour)
#   platform/m0/qemu.sh bench  [SETTINGS] FIRST LAST STEP  frames FIRST..LAST every STEP, no files
# SETTINGS are render's options --depth N (at most 5 on this board), --mode full|adaptive,
# --grid N (4 or 8 on the board), --threshold X, --min-contrib X, --octaves N and
# --footprint on|off, as `--opt value` or `--opt=value` (platform/qemu-settings.sh splits them,
# the board checks them). The board has
# no display: frames leave band by band through semihosting. Both commands run under
# `-icount shift=0` (one guest instruction = 1 ns of virtual time; the SysTick steps 62.5 ns at
# the chip's 16 MHz, so a frame's count is exact to within 63 instructions a band, the same on
# every run) and print `frame=N instructions=M cycles=C` per frame, then `frames=K mean=M cycles=C`,
# `worst=M cycles=C`, a `cycles:` line (cycles per instruction, estimated fps at the nRF51's 16 MHz
# and at 133 MHz, an RP2040-class clock) and the guest's RAM use (`ram: ...`). The cycles are the
# Cortex-M0 timing model's estimate (the TCG plugin build/arm/qemu_profile.so with cpu=m0,
# platform/qemu-cycles.sh; docs/m0.md, Cycle model), exact and repeatable like the counts;
# QEMU_CYCLES_OPTS and QEMU_CYCLES_OUT as for platform/arm/qemu.sh. A frame is byte for byte
# `build/rt-fixed render --size 128x64 --frame N` (with the same settings). The exit
# status is the guest's; QEMU runs under a time limit, QEMU_TIMEOUT seconds (default 600).
set -euo pipefail
cd "$(dirname "$0")/../.."
. platform/qemu-settings.sh

usage="usage: platform/m0/qemu.sh frames|bench [SETTINGS] [ARGS...] (see the file's header)"

[ $# -ge 1 ] || die "$usage"
cmd=$1
shift
elf=build/m0/intro-fixed.elf
qemu_checks "$elf" m0

# The render settings go to the board first (it checks their values); the rest stay in order.
qemu_settings "$@"
set -- "${args[@]+"${args[@]}"}"

case "$cmd" in
  frames)
    qemu_frame_args "$@"
    mkdir -p build/qemu-m0
    for n in "$@"; do
      rm -f "build/qemu-m0/fixed-$(printf '%04d' "$((10#$n))").ppm"
    done
    set -- --out build/qemu-m0/fixed "$@"
    ;;
  bench)
    qemu_bench_args "$@"
    ;;
  *) die "unknown command '$cmd'; $usage" ;;
esac

# the cycle estimate: the timing plugin, its figures merged into the guest's lines afterwards
. platform/qemu-cycles.sh
cycles_plugin "$elf" m0
CYCLES_MHZ="16 133"
guest_log=$(mktemp)
trap 'rm -f "$guest_log"; [ -n "${QEMU_CYCLES_OUT:-}" ] || rm -f "$cycles_out"' EXIT
status=0
# --foreground: QEMU stays in the terminal's process group; no stdin.
timeout --foreground -k 10 "$timeout_s" qemu-system-arm -M microbit -kernel "$elf" -display none \
  -serial stdio -monitor none -icount shift=0,align=off,sleep=off "${plugin[@]}" \
  -semihosting-config "$(semihosting "$cmd" ${settings[@]+"${settings[@]}"} "$@")" </dev/null >"$guest_log" ||
  status=$?
if [ "$status" -eq 0 ]; then
  cycles_merge "$guest_log" || status=1
else
  cat "$guest_log"
fi
if [ "$status" -eq 124 ] || [ "$status" -eq 137 ]; then
  echo "qemu.sh: error: the M0 guest did not finish within $timeout_s s (hung?); QEMU stopped" >&2
  exit 1
fi
exit "$status"
