# qemu-settings.sh: what platform/arm/qemu.sh, platform/m3/qemu.sh and platform/m0/qemu.sh share (sourced, not run, from the top of the repository): the error exit, the checks of the image, QEMU and QEMU_TIMEOUT, the render-settings parsing, the frame and bench arguments' checks, the semihosting argument list and the output filter.

# die MESSAGE...: `qemu.sh: error: MESSAGE` on standard error, exit status 2.
die() { printf 'qemu.sh: error: %s\n' "$*" >&2; exit 2; }

# qemu_checks ELF TARGET: the image ELF is built (else: run make TARGET), qemu-system-arm is
# installed and QEMU_TIMEOUT (default 600) is a whole number of seconds, set in timeout_s.
qemu_checks() {
  [ -f "$1" ] || die "$1 is missing: run make $2 first"
  command -v qemu-system-arm >/dev/null || die "qemu-system-arm is not installed: run ./setup.sh --arm"
  timeout_s=${QEMU_TIMEOUT:-600}
  case "$timeout_s" in ''|*[!0-9]*|0) die "QEMU_TIMEOUT must be a whole number of seconds, 1 or more, not '$timeout_s'" ;; esac
}

# qemu_frame_args N...: frames' arguments, at least one frame number, each a whole number.
qemu_frame_args() {
  local n
  [ $# -ge 1 ] || die "frames wants at least one frame number"
  for n in "$@"; do
    case "$n" in *[!0-9]*) die "frame '$n' is not a whole number" ;; esac
  done
}

# qemu_bench_args ARGS...: bench's arguments, FIRST LAST STEP.
qemu_bench_args() { [ $# -eq 3 ] || die "bench wants FIRST LAST STEP"; }

# semihosting ARGS...: QEMU's -semihosting-config value giving the guest the argument list
# `intro ARGS...`.
semihosting() { printf 'enable=on,target=native,arg=intro'; printf ',arg=%s' "$@"; }
#
# qemu_settings ARGS... checks each argument's characters, then splits them: render's settings
# (--depth, --mode, --grid, --threshold, --min-contrib, --octaves, --footprint; as `--opt value`
# or `--opt=value`) go to the array `settings`, in order; the other words go to `args`, in order.
# The board parses and checks the settings' values. Any other option is an error (die, defined
# by the caller).
qemu_settings() {
  local a
  for a in "$@"; do
    case "$a" in *[!A-Za-z0-9/_.=-]*|'') die "argument '$a': use letters, digits and / _ . = - only" ;; esac
  done
  settings=()
  args=()
  while [ $# -gt 0 ]; do
    case "$1" in
      --depth|--mode|--grid|--threshold|--min-contrib|--octaves|--footprint)
        [ $# -ge 2 ] || die "$1 needs a value"
        settings+=("$1" "$2")
        shift 2 ;;
      --depth=*|--mode=*|--grid=*|--threshold=*|--min-contrib=*|--octaves=*|--footprint=*)
        settings+=("$1")
        shift ;;
      -*) die "unknown option '$1' (settings: --depth, --mode, --grid, --threshold, --min-contrib, --octaves, --footprint)" ;;
      *) args+=("$1"); shift ;;
    esac
  done
}

# qemu_log_split: copies the guest's log (its UART) from standard input to standard output, but
# its error lines (`intro: error: ...`, `error: ...`) to standard error, line by line.
qemu_log_split() {
  awk '/^(intro: )?error: / { print > "/dev/stderr"; fflush("/dev/stderr"); next } { print; fflush() }'
}

# qemu_run COMMAND...: runs QEMU's command line with the guest's UART on standard output through
# qemu_log_split, and QEMU's own standard error less its notice "Timer with period zero,
# disabling" (the lm3s6965evb's timers, at every start); returns the command's status.
qemu_run() {
  local -
  set -o pipefail
  { "$@" 2>&1 1>&3 3>&- | sed -u '/Timer with period zero, disabling/d' >&2; } 3>&1 | qemu_log_split
}
