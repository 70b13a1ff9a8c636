# qemu-cycles.sh: the cycle estimate shared by the boards' platform/arm/qemu.sh, platform/m3/qemu.sh and platform/m0/qemu.sh (sourced, not run): loads the timing plugin and adds its cycles to the board's frame lines.
#
# cycles_plugin ELF CPU sets the array `plugin` to the -plugin arguments of build/arm/qemu_profile.so
# (platform/arm/qemu_profile.c) for that image and core (arm926, m3 or m0): the window from
# rt_render_band_into's entry to plat_time_ns's (the band's rendering, as the board times it),
# one record a frame at plat_band_begin, the plugin's counts into the file `cycles_out`
# (QEMU_CYCLES_OUT if set, else a temporary file), and QEMU_CYCLES_OPTS (comma-separated plugin
# options such as dcache=8192,dmiss=40) appended. cycles_merge LOG prints the guest's log LOG with
# ` cycles=C` after each `frame=N instructions=M` line and after the `frames=K mean=M` and
# `worst=M` lines (the cycles' own mean and worst), then a `cycles:` line with the frames' cycles
# per instruction and the estimated frames per second at the board's clock, CYCLES_MHZ (a list).
# With CYCLES=0 (and no QEMU_CYCLES_OUT) no plugin is loaded and cycles_merge prints the log as it
# is, instructions only: for runs that check frames, not cycles (QEMU runs faster without the
# plugin's per-instruction callbacks). die is the caller's.
cycles_plugin() {
  local elf=$1 cpu=$2 so=build/arm/qemu_profile.so s a
  cycles_on=1
  case "${CYCLES:-1}" in
    0) [ -n "${QEMU_CYCLES_OUT:-}" ] || cycles_on=0 ;;
    1) ;;
    *) die "CYCLES must be 0 (no cycle estimate) or 1, not '$CYCLES'" ;;
  esac
  if [ "$cycles_on" = 0 ]; then
    cycles_out="" plugin=()
    return
  fi
  [ -f "$so" ] || die "$so is missing: run make $so (make arm and make m3 build it)"
  command -v arm-none-eabi-nm >/dev/null || die "arm-none-eabi-nm is missing: run ./setup.sh --arm"
  a=$(arm-none-eabi-nm "$elf" | awk '$3 == "rt_render_band_into" && !s { s = "0x" $1 }
    $3 == "plat_time_ns" && !t { t = "0x" $1 } $3 == "plat_band_begin" && !f { f = "0x" $1 }
    END { if (s && t && f) print "start=" s ",stop=" t ",frame=" f }')
  [ -n "$a" ] || die "rt_render_band_into, plat_time_ns or plat_band_begin not found in $elf"
  if [ -n "${QEMU_CYCLES_OUT:-}" ]; then
    cycles_out=$QEMU_CYCLES_OUT
  else
    cycles_out=$(mktemp) # the caller removes it
  fi
  rm -f "$cycles_out"
  s="$so,out=$cycles_out,cpu=$cpu,$a"
  [ -z "${QEMU_CYCLES_OPTS:-}" ] || s="$s,$QEMU_CYCLES_OPTS"
  # shellcheck disable=SC2034  # the caller's
  plugin=(-plugin "$s")
}

cycles_merge() {
  local log=$1
  if [ "$cycles_on" = 0 ]; then
    cat "$log"
    return
  fi
  if [ ! -s "$cycles_out" ]; then
    cat "$log"
    echo "qemu.sh: error: the cycle plugin wrote nothing ($cycles_out)" >&2
    return 1
  fi
  awk -v mhz="$CYCLES_MHZ" 'FNR == 1 { file++ }
    file == 1 && $1 == "frame" { cyc[++nf] = $3; next }
    file == 1 { next }
    /^frame=[0-9]+ instructions=[0-9]+$/ {
      k++
      if (k in cyc) { sum += cyc[k]; if (cyc[k] > worst) worst = cyc[k]; ins += substr($2, 14) + 0; print $0 " cycles=" cyc[k] }
      else print $0 " cycles=?"
      next
    }
    /^frames=[0-9]+ mean=[0-9]+$/ { print $0 " cycles=" (k ? int(sum / k) : 0); next }
    /^worst=[0-9]+$/ {
      print $0 " cycles=" worst
      if (k && ins) {
        n = split(mhz, m, " ")
        line = sprintf("cycles: %.3f a instruction (the model'\''s estimate), fps", sum / ins)
        for (i = 1; i <= n; i++)
          line = line sprintf("%s at %s MHz mean %.2f worst %.2f", i > 1 ? "," : "", m[i], m[i] * 1e6 * k / sum, m[i] * 1e6 / worst)
        print line
      }
      next
    }
    { print }
    END { if (k != nf) { printf "qemu.sh: error: the board logged %d frames, the cycle plugin %d\n", k, nf > "/dev/stderr"; exit 1 } }' \
    "$cycles_out" "$log"
}
