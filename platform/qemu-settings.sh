# qemu-settings.sh: the render-settings parsing and the output filter shared by platform/arm/qemu.sh,
# platform/m3/qemu.sh and platform/m0/qemu.sh (sourced, not run).
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
