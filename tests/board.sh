# board.sh: the checks the boards share (sourced by tests/arm.sh and tests/m3.sh after tests/lib.sh): an image's static budgets and its runs under QEMU.
#
# Static: no floating-point or coprocessor instruction (per instruction set), no soft-float helper
# or libm function, only allowed library code, sizes within limits; with positive controls that
# show the scans find what they look for. Runs: frames twice against the host's, RAM, refused
# settings, a CPU exception.
LIB_FILES="$LIB_FILES board.sh"

# Section sizes in bytes, by name, from `size -A` (0 for a section the image does not have).
board_section() { arm-none-eabi-size -A "$1" | awk -v s="$2" '$1 == s { print $2 + 0; found = 1 } END { if (!found) print 0 }'; }
board_ram_bytes() { echo $(($(board_section "$1" .data) + $(board_section "$1" .bss) + $(board_section "$1" .stack))); }
# code + read-only data + initialised data (what counts against the ARM926's 64 KiB; the M3's
# flash holds its vector table besides)
board_code_bytes() {
  echo $(($(board_section "$1" .text) + $(board_section "$1" .rodata) + $(board_section "$1" .ARM.exidx) +
          $(board_section "$1" .data)))
}

# board_image ELF: stops the script with one FAIL line when the image is missing or unreadable.
board_image() {
  [ -f "$1" ] || { fail "$1 is missing (make arm / make m3)"; exit 1; }
  [ "$(board_section "$1" .text)" -gt 0 ] || { fail "$1: no .text section (size -A failed?)"; exit 1; }
}

# board_fp_instructions ISA FILE: the count of instructions that use the floating-point unit or
# any coprocessor, whatever their condition and however objdump names them, plus anything objdump
# shows with a VFP mnemonic (v..., f...); data in code (.word) is skipped. ISA arm: every ARM
# instruction word whose bits 27:26 are 11, other than SVC (bits 27:24 = 1111). ISA thumb2: the
# 32-bit encodings whose first halfword is 111x 11xx xxxx xxxx (VFP is coprocessors 10 and 11).
# (No {n} intervals: mawk has none.)
board_fp_instructions() {
  arm-none-eabi-objdump -d "$2" |
    awk -F'\t' -v isa="$1" 'NF >= 3 && $3 !~ /^\./ {
                  w = $2; m = $3; sub(/[ \t].*/, "", m)
                  if (isa == "arm") { gsub(/ /, "", w); cop = length(w) == 8 && index("cde", substr(w, 2, 1)) > 0 }
                  else { gsub(/ +$/, "", w); cop = length(w) == 9 && substr(w, 5, 1) == " " && w ~ /^[ef][c-f]/ }
                  if (cop || m ~ /^(v|f)[a-z]/) n++ }
                END { print n + 0 }'
}
# Soft-float helpers (AEABI, libgcc and half-precision names) and libm functions in the symbol
# table (defined or called).
board_fp_symbols() {
  arm-none-eabi-nm "$1" |
    awk '{ s = $NF }
         s ~ /^__aeabi_([fd](add|sub|rsub|mul|div|neg|cmp|cmpeq|cmplt|cmple|cmpge|cmpgt|cmpun|2)|[ul]?[il]2[fd]|[fd]2|c[fd](cmp|rcmp))/ ||
         s ~ /^__gnu_(f2h|h2f|d2h)/ || s ~ /^__powi[sdt]f2$/ || s ~ /^__gnu_(sat)?fract/ ||
         s ~ /^(__ieee754_|__kernel_)/ ||
         s ~ /^(round|trunc|copysign|ldexp|frexp|modf|scalbn|hypot|cbrt|expm1|log1p|log10|log2|exp2|sinh|cosh|tanh|asin|acos|fmin|fmax|rint|nearbyint|lrint|lround)f?$/ ||
         s ~ /^__(add|sub|mul|div|neg|cmp|eq|ne|lt|le|gt|ge|unord)[sdt]f[23]$/ ||
         s ~ /^__(fix|fixuns)[sdt]f[sdt]i$/ || s ~ /^__float(un)?[sdt]i[sdt]f$/ ||
         s ~ /^__(extend|trunc)[sdt]f[sdt]f2$/ ||
         s ~ /^(sqrt|sin|cos|tan|atan2?|exp|log|pow|floor|ceil|fabs|fmod)f?$/ { print s }' | sort -u
}
# Library code linked in: the map's archive members.
board_members() { awk '/^Archive member included/,/^Discarded input sections/' "$1.map" | grep -o '[^/ ]*\.a([^)]*)' | sort -u; }
# What a fixed image may link: libfixmath, newlib's memory functions, libgcc's integer division,
# multiplication and bit counting, and EXTRA (a board's own libgcc members, '|'-separated).
board_allowed() {
  echo '^(libfixmath\.a\(.*\)|libc\.a\(lib_a-(memcmp|memcpy|memcpy-stub|memset|memmove)\.o\)|libgcc\.a\(_(aeabi_u?ldivmod|clz[sd]i2|u?divsi3|dvmd_tls|u?divmoddi4|u?divdi3|u?moddi3|ashldi3|ashrdi3|lshrdi3|muldi3'"${1:+|$1}"')\.o\))$'
}

# board_no_float LABEL ISA ELF: no floating-point instruction, no floating-point function.
board_no_float() {
  local n syms
  n=$(board_fp_instructions "$2" "$3")
  [ "$n" -eq 0 ] && pass "$1 has no floating-point or coprocessor instruction" ||
    fail "$1 has $n floating-point/coprocessor instructions: $(arm-none-eabi-objdump -d "$3" | grep -E '\s(v|f)[a-z]' | head -3 | tr '\n' ' ')"
  syms=$(board_fp_symbols "$3")
  [ -z "$syms" ] && pass "$1 calls no soft-float helper or libm function" ||
    fail "$1 contains floating-point functions: $(tr '\n' ' ' <<<"$syms")"
}
# board_only_allowed LABEL ELF ALLOWED WHAT: the image links only the allowed library members.
board_only_allowed() {
  local others count
  others=$(board_members "$2" | grep -Ev "$3" || true)
  count=$(board_members "$2" | wc -l)
  [ "$count" -gt 0 ] && [ -z "$others" ] && pass "$1 links only allowed library code ($count members: $4)" ||
    fail "$1 links other library code: $(tr '\n' ' ' <<<"$others")($count members)"
}
# board_scan_control LABEL ISA OBJECT WHAT: the instruction scan finds the 7 VFP/coprocessor
# instructions of a test object assembled by the caller, and not its other instructions.
board_scan_control() {
  local n
  n=$(board_fp_instructions "$2" "$3")
  [ "$n" -eq 7 ] && pass "$1: positive control: the scan finds the 7 VFP/coprocessor instructions of $4" ||
    fail "$1: positive control: the scan finds $n, not 7, VFP/coprocessor instructions of $4"
}
# board_within LABEL WHAT BYTES LIMIT
board_within() {
  [ "$3" -le "$4" ] && pass "$1 $2 $3 B <= $4 B" || fail "$1 $2 $3 B > $4 B"
}

# board_two_runs LABEL LOG PPM-OF HOST DESC COMMAND...: `COMMAND FRAMES...` renders the frames
# of the array FRAMES on the board, twice (logs $T/LOG-1.log and -2.log); each frame must be byte
# for byte the host's ($T/HOST-N.ppm, rendered by DESC), in both runs, and the two runs must count
# the same instructions (and, unless CYCLES=0, estimated cycles) for every frame. `PPM-OF N`
# prints where the board wrote frame N.
board_two_runs() {
  local label=$1 log=$2 ppm_of=$3 host=$4 desc=$5 run n same=0
  shift 5
  for run in 1 2; do
    if "$@" "${FRAMES[@]}" >"$T/$log-$run.log" 2>&1; then
      pass "$label: frames on the board, run $run ($(grep -c '^frame=' "$T/$log-$run.log") frames, mean $(sed -n 's/.* mean=\([0-9]*\).*/\1/p' "$T/$log-$run.log") instructions)"
    else
      fail "$label: frames on the board, run $run: $(tail -2 "$T/$log-$run.log" | tr '\n' ' ')"
    fi
    for n in "${FRAMES[@]}"; do
      cmp -s "$($ppm_of "$n")" "$T/$host-$n.ppm" || fail "$label: frame $n (run $run) differs from $desc --frame $n"
    done
  done
  for n in "${FRAMES[@]}"; do cmp -s "$($ppm_of "$n")" "$T/$host-$n.ppm" && same=$((same + 1)); done
  [ "$same" -eq ${#FRAMES[@]} ] && pass "$label: frames ${FRAMES[*]} bit-identical to $desc, in both runs"
  if [ "$(grep -c '^frame=' "$T/$log-1.log")" -eq ${#FRAMES[@]} ] &&
     diff <(grep '^frame=' "$T/$log-1.log") <(grep '^frame=' "$T/$log-2.log") >/dev/null; then
    pass "$label: two runs give identical instruction$([ "${CYCLES:-1}" = 0 ] || echo " and cycle") counts ($(grep '^frame=' "$T/$log-1.log" | sed 's/.*instructions=//' | tr '\n' ' '))"
  else
    fail "$label: instruction or cycle counts differ between two runs"
  fi
}

# board_ram LABEL LIMIT NOTE COMMAND...: COMMAND (a bench run) reports RAM as `ram: ... total=N
# bytes`: .data + .bss + the deepest stack use, within LIMIT bytes. NOTE, if given, is a function
# that prints a remark on the total.
board_ram() {
  local label=$1 limit=$2 note=$3 ram
  shift 3
  if "$@" >"$T/bench.log" 2>&1; then
    ram=$(sed -n 's/^ram: .* total=\([0-9]*\) bytes$/\1/p' "$T/bench.log")
    if [ -n "$ram" ] && [ "$ram" -le "$limit" ]; then
      pass "$label: RAM over 25 intro frames: $(grep '^ram:' "$T/bench.log" | sed 's/^ram: //') <= $limit${note:+ ($($note "$ram"))}"
    else
      fail "$label: RAM: $(grep '^ram:' "$T/bench.log") (limit $limit)"
    fi
  else
    fail "$label: $*: $(tail -2 "$T/bench.log" | tr '\n' ' ')"
  fi
}

# board_refused LABEL SETTING COMMAND...: `COMMAND SETTING 0 0 1` (a board's qemu.sh bench)
# refuses the setting: one error line naming its option, status 2, no frame.
board_refused() {
  local label=$1 setting=$2 out st
  shift 2
  # shellcheck disable=SC2086  # the setting is words on purpose
  out=$("$@" $setting 0 0 1 2>&1)
  st=$?
  if [ $st -eq 2 ] && grep -q "^intro: error: ${setting%%[ =]*}: " <<<"$out" && ! grep -q '^frame=' <<<"$out"; then
    pass "$label: bench $setting refused on the board: $(grep '^intro: error' <<<"$out")"
  else
    fail "$label: bench $setting: status $st: $(tr '\n' ' ' <<<"$out")"
  fi
}

# board_fault LABEL DIR CPU-FLAGS LINK-SCRIPT OBJ-DIR "BACKEND-OBJS" PATTERN QEMU-ARGS...: tests/arm_fault.c
# on the board's start-up code and backend executes an undefined instruction; the run must end
# through the exception vectors with status 3 and exactly one line matching PATTERN (the board's
# name of the exception), not restart the program (its first line once) nor go on after it.
board_fault() {
  local label=$1 dir=$2 cpu=$3 ld=$4 obj=$5 backend=$6 pattern=$7 st o objs=()
  shift 7
  for o in $backend; do objs+=("$obj/$o"); done
  # shellcheck disable=SC2086  # the CPU flags are words on purpose
  if arm-none-eabi-gcc -std=c11 -O2 $cpu -ffreestanding -Iplatform -c tests/arm_fault.c -o "$dir/fault.o" &&
     arm-none-eabi-gcc $cpu -nostartfiles -T "$ld" -Wl,--gc-sections -Wl,-z,noexecstack -Wl,--no-warn-rwx-segments \
       -o "$dir/fault.elf" "$dir/fault.o" "$obj/start.o" "$obj/platform/board.o" "${objs[@]}" -lc -lgcc; then
    timeout --foreground -k 5 30 qemu-system-arm "$@" -display none -serial stdio -monitor none \
      -semihosting-config enable=on,target=native,arg=fault -kernel "$dir/fault.elf" </dev/null >"$dir/fault.log" 2>&1
    st=$?
    if [ $st -eq 3 ] && [ "$(grep -c "$pattern" "$dir/fault.log")" -eq 1 ] &&
       [ "$(grep -c 'executing an undefined' "$dir/fault.log")" -eq 1 ] && ! grep -q 'still running' "$dir/fault.log"; then
      pass "$label: an undefined instruction ends the run with status 3: $(grep '^error' "$dir/fault.log")"
    else
      fail "$label: undefined instruction: status $st, $(tr '\n' ' ' <"$dir/fault.log" | cut -c1-200)"
    fi
  else
    fail "$label: could not build tests/arm_fault.c"
  fi
}
