#!/usr/bin/env bash
# qemu.sh: runs the Cortex-M3 intro image on qemu-system-arm -M lm3s6965evb: play it on the emulated OLED, render frames to files, benchmark a stretch, or show one frame.
#
# Usage (from the top of the repository; make qemu-m3 and make qemu-m3-frames call it):
#   platform/m3/qemu.sh play   [SETTINGS]                  QEMU's window: the OLED, the intro looping
#   platform/m3/qemu.sh frames [SETTINGS] N...             build/qemu-m3/fixed-NNNN.ppm (128x64 colour)
#   platform/m3/qemu.sh bench  [SETTINGS] FIRST LAST STEP  frames FIRST..LAST every STEP, no files
#   platform/m3/qemu.sh show   [SETTINGS] N SCREEN.ppm     frame N on the OLED, saved by QEMU's
#                                                          screendump (512x256: 4x4 per pixel)
# SETTINGS are render's options --depth N, --mode full|adaptive, --grid N (4 or 8 on the board),
# --threshold X, --min-contrib X, --octaves N and --footprint on|off, as `--opt value` or
# `--opt=value` (defaults as for render; platform/qemu-settings.sh splits them, the board checks them).
# frames, bench and show run headless under `-icount shift=0` (one guest instruction = 1 ns of
# virtual time: exact, repeatable counts, 20 ns steps of the board's 50 MHz SysTick); frames and
# bench print `frame=N instructions=M cycles=C` per frame, then `frames=K mean=M cycles=C`,
# `worst=M cycles=C`, a `cycles:` line (cycles per instruction, estimated fps at 50 MHz) and the
# guest's RAM use (`ram: ...`). The cycles are the Cortex-M3 timing model's estimate (the TCG
# plugin build/arm/qemu_profile.so with cpu=m3, platform/qemu-cycles.sh; docs/m3.md, Cycle model),
# exact and repeatable like the counts; QEMU_CYCLES_OPTS and QEMU_CYCLES_OUT as for
# platform/arm/qemu.sh. A frame is byte for byte `build/rt-fixed render --size 128x64 --frame N`. The exit
# status is the guest's; QEMU runs under a time limit, QEMU_TIMEOUT seconds (default 600).
set -euo pipefail
cd "$(dirname "$0")/../.."
. platform/qemu-settings.sh

usage="usage: platform/m3/qemu.sh play|frames|bench|show [SETTINGS] [ARGS...] (see the file's header)"

[ $# -ge 1 ] || die "$usage"
cmd=$1
shift
elf=build/m3/intro-fixed.elf
qemu_checks "$elf" m3

screen=
if [ "$cmd" = show ]; then
  [ $# -ge 2 ] || die "show wants N SCREEN.ppm"
  screen=${*: -1}
  set -- "${@:1:$#-1}"
  case "$screen" in *.ppm) ;; *) die "show: the screen file must end in .ppm, not '$screen'" ;; esac
fi
# The render settings go to the board first (it checks their values); the rest stay in order.
qemu_settings "$@"
set -- "${args[@]+"${args[@]}"}"
common=(-M lm3s6965evb -kernel "$elf")

case "$cmd" in
  play)
    [ $# -eq 0 ] || die "play takes no frame arguments"
    if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ]; then
      die "no display (DISPLAY is not set): QEMU's window needs one; make qemu-m3-frames renders frames to files instead"
    fi
    echo "qemu: playing the intro at 128x64 on the emulated OLED (16 greys); close the window or press Ctrl-C in this terminal to stop"
    echo "qemu: the intro's \`fps=\` lines are the emulator's speed on this host, not the board's; the board's estimated fps (cycle model): platform/m3/qemu.sh bench 0 1200 24"
    exec qemu-system-arm "${common[@]}" -serial stdio -semihosting-config "$(semihosting play ${settings[@]+"${settings[@]}"})" \
      2> >(sed -u '/Timer with period zero, disabling/d' >&2)
    ;;
  frames)
    qemu_frame_args "$@"
    # no file is removed: each frame the board writes replaces its file whole (a temporary file
    # renamed), so a refused run leaves the earlier frames as they were
    mkdir -p build/qemu-m3
    set -- --out build/qemu-m3/fixed "$@"
    ;;
  bench)
    qemu_bench_args "$@"
    ;;
  show)
    [ $# -eq 1 ] || die "show wants one frame number and the screen file"
    mkdir -p -- "$(dirname -- "$screen")" build/qemu-m3
    # QEMU's monitor reads a command line: the screendump goes to a name of our own (letters,
    # digits, / - .), then is moved to the screen file, whatever characters its name holds.
    work=$(mktemp -d build/qemu-m3/show.XXXXXX)
    trap 'rm -rf "$work"' EXIT
    log=$work/serial.log
    : >"$log"
    # The guest logs `shown frame=N` once the frame is on the OLED; then the monitor saves it.
    # A guest that refuses its arguments logs an error and ends (its RAM report, `ram:`) at once.
    status=0
    {
      for _ in $(seq 600); do grep -qE '^(shown|ram:)|error: ' "$log" && break; sleep 0.1; done
      if grep -q '^shown' "$log"; then
        sleep 0.5
        echo "screendump $work/screen.ppm"
        sleep 1
      fi
      echo quit
    } | timeout --foreground -k 5 "$timeout_s" qemu-system-arm "${common[@]}" -display none -monitor stdio \
        -serial "file:$log" -icount shift=0,align=off,sleep=off \
        -semihosting-config "$(semihosting show ${settings[@]+"${settings[@]}"} "$1")" >"$work/monitor.log" 2>&1 ||
      status=${PIPESTATUS[1]}
    qemu_log_split <"$log"
    if ! grep -q '^shown' "$log"; then
      [ "$status" -ne 0 ] || status=1
      # the guest's own error line (on standard error above) says why; else say it here
      if ! grep -qE '^(intro: )?error: ' "$log"; then
        if [ "$status" -eq 124 ] || [ "$status" -eq 137 ]; then
          echo "qemu.sh: error: the M3 guest showed no frame within $timeout_s s (hung?); QEMU stopped" >&2
        else
          echo "qemu.sh: error: the M3 guest ended (status $status) without showing the frame" >&2
        fi
      fi
      exit "$status"
    fi
    [ -s "$work/screen.ppm" ] || die "no screendump was written: $(grep -v '^(qemu)\|QEMU\|Timer with period zero' "$work/monitor.log" | head -1)"
    mv -f -- "$work/screen.ppm" "$screen"
    exit 0
    ;;
  *) die "unknown command '$cmd'; $usage" ;;
esac

# the cycle estimate: the timing plugin, its figures merged into the guest's lines afterwards
. platform/qemu-cycles.sh
cycles_plugin "$elf" m3
CYCLES_MHZ=50
guest_log=$(mktemp)
trap 'rm -f "$guest_log"; [ -n "${QEMU_CYCLES_OUT:-}" ] || rm -f "$cycles_out"' EXIT
status=0
# --foreground: QEMU stays in the terminal's process group; no stdin.
qemu_run timeout --foreground -k 10 "$timeout_s" qemu-system-arm "${common[@]}" -display none -serial stdio -monitor none \
  "${plugin[@]}" -icount shift=0,align=off,sleep=off \
  -semihosting-config "$(semihosting "$cmd" ${settings[@]+"${settings[@]}"} "$@")" </dev/null >"$guest_log" ||
  status=$?
if [ "$status" -eq 0 ]; then
  cycles_merge "$guest_log" || status=1
else
  cat "$guest_log"
fi
if [ "$status" -eq 124 ] || [ "$status" -eq 137 ]; then
  echo "qemu.sh: error: the M3 guest did not finish within $timeout_s s (hung?); QEMU stopped" >&2
  exit 1
fi
exit "$status"
