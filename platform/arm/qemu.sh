#!/usr/bin/env bash
# qemu.sh: runs the ARM926 intro image on qemu-system-arm -M versatilepb: play it in QEMU's window, render frames to files, or benchmark a stretch.
#
# Usage (from the top of the repository; make qemu, make qemu-frames and make qemu-bench call it):
#   platform/arm/qemu.sh play   [REAL] [SETTINGS]                  QEMU's window, the intro looping
#   platform/arm/qemu.sh frames [REAL] [SETTINGS] N...             build/qemu/<real>-NNNN.ppm
#   platform/arm/qemu.sh bench  [REAL] [SETTINGS] FIRST LAST STEP  frames FIRST..LAST every STEP
# REAL is fixed (default), float (soft-float) or fixed16 (build/arm/intro-fixed16.elf, unit
# vectors in Q16.16). SETTINGS are render's options --depth N, --mode full|adaptive, --grid N,
# --threshold X, --min-contrib X, --octaves N and --footprint on|off, as `--opt value` or
# `--opt=value` (defaults as for render; platform/qemu-settings.sh splits them); the board parses and checks them
# (grids 4 and 8 only: the working storage of grids 2 and 16 does not fit its RAM budget). A
# fixed frame rendered with settings is byte for byte `build/rt-fixed render --size 320x240
# --frame N SETTINGS`.
# frames and bench run headless under `-icount shift=0` (one guest instruction = 1 ns of virtual
# time, so the counts are exact and repeatable) and print one `frame=N instructions=M cycles=C`
# line per frame, then `frames=K mean=M cycles=C`, `worst=M cycles=C`, a `cycles:` line (cycles
# per instruction, estimated fps at 200 MHz and at the i.MX233's 454 MHz) and the guest's RAM use
# (`ram: ...`). The cycles are the ARM926EJ-S timing model's estimate with its 16 KiB caches
# (the TCG plugin build/arm/qemu_profile.so, platform/qemu-cycles.sh; docs/arm.md, Cycle model):
# exact and repeatable like the instruction counts. QEMU_CYCLES_OPTS adds plugin options
# (e.g. dcache=8192,icache=8192), QEMU_CYCLES_OUT=FILE keeps the plugin's per-address counts
# (platform/arm/profile.sh). The exit status is the guest's. QEMU runs under a time limit,
# QEMU_TIMEOUT seconds (default 600): a hung guest is an error, not a hang.
set -euo pipefail
cd "$(dirname "$0")/../.."
. platform/qemu-settings.sh

usage="usage: platform/arm/qemu.sh play|frames|bench [fixed|float|fixed16] [SETTINGS] [ARGS...] (see the file's header)"

[ $# -ge 1 ] || die "$usage"
cmd=$1
shift
real=fixed
if [ $# -ge 1 ] && { [ "$1" = fixed ] || [ "$1" = float ] || [ "$1" = fixed16 ]; }; then
  real=$1
  shift
fi
elf=build/arm/intro-$real.elf
qemu_checks "$elf" arm

# The render settings go to the board first (it checks their values); the rest stay in order.
qemu_settings "$@"
set -- "${args[@]}"
common=(-M versatilepb -m 2 -serial stdio -monitor none
        -audiodev none,id=snd0 -global pl041.audiodev=snd0 -kernel "$elf")

case "$cmd" in
  play)
    [ $# -eq 0 ] || die "play takes no frame arguments"
    if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ]; then
      die "no display (DISPLAY is not set): QEMU's window needs one; make qemu-frames renders frames to files instead"
    fi
    echo "qemu: playing the $real intro at 320x240 on the emulated PL110; close the window or press Ctrl-C in this terminal to stop"
    echo "qemu: the intro's \`fps=\` lines are the emulator's speed on this host, not the board's; the board's estimated fps (cycle model): platform/arm/qemu.sh bench $real 0 1200 24"
    exec qemu-system-arm "${common[@]}" -semihosting-config "$(semihosting play "${settings[@]}")"
    ;;
  frames)
    qemu_frame_args "$@"
    # no file is removed: each frame the board writes replaces its file whole (a temporary file
    # renamed), so a refused run leaves the earlier frames as they were
    mkdir -p build/qemu
    set -- --out "build/qemu/$real" "$@"
    ;;
  bench)
    qemu_bench_args "$@"
    ;;
  *) die "unknown command '$cmd'; $usage" ;;
esac

# the cycle estimate: the timing plugin, its figures merged into the guest's lines afterwards
. platform/qemu-cycles.sh
cycles_plugin "$elf" arm926
CYCLES_MHZ="200 454"
guest_log=$(mktemp)
trap 'rm -f "$guest_log"; [ -n "${QEMU_CYCLES_OUT:-}" ] || rm -f "$cycles_out"' EXIT
status=0
# --foreground: QEMU stays in the terminal's process group (else -serial stdio stops it with
# SIGTTOU when run from a terminal); -k: killed if it ignores the polite signal; no stdin.
qemu_run timeout --foreground -k 10 "$timeout_s" qemu-system-arm "${common[@]}" -display none "${plugin[@]}" \
  -icount shift=0,align=off,sleep=off -semihosting-config "$(semihosting "$cmd" "${settings[@]}" "$@")" </dev/null >"$guest_log" ||
  status=$?
if [ "$status" -eq 0 ]; then
  cycles_merge "$guest_log" || status=1
else
  cat "$guest_log"
fi
if [ "$status" -eq 124 ] || [ "$status" -eq 137 ]; then
  echo "qemu.sh: error: the $real guest did not finish within $timeout_s s (hung?); QEMU stopped" >&2
  exit 1
fi
exit "$status"
