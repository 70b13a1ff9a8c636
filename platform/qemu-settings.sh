# qemu-settings.sh: the render-settings parsing shared by platform/arm/qemu.sh, platform/m3/qemu.sh and platform/m0/qemu.sh (sourced, not run).
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
