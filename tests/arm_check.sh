#!/usr/bin/env bash
# arm_check.sh: the static budgets of the ARM926 images: no floating point in the fixed image (with positive controls), code and RAM sizes.
#
# Usage: tests/arm_check.sh [--print]
#   Prints `ok ...` / `FAIL ...` lines (tests/run.sh counts them) and exits 1 if any check fails.
#   --print only prints the sizes of both images (make arm), checking nothing.
# Checks:
#   - build/arm/intro-fixed.elf has no VFP/coprocessor instruction (objdump) and no soft-float
#     helper or libm function (its symbol table); the same scans do find soft-float helpers in
#     intro-float.elf, and VFP instructions in a small object assembled here; intro-fixed16.elf
#     (unit in Q16.16) passes the same scans;
#   - code + read-only data + initialised data of the fixed image <= 64 KiB (the original's limit);
#   - .data + .bss + the reserved stack of the fixed image <= 32 KiB (the measured stack peak is
#     checked by tests/arm.sh from a run).
set -u
cd "$(dirname "$0")/.."

B=build
FIXED=$B/arm/intro-fixed.elf
FLOAT=$B/arm/intro-float.elf
FIXED16=$B/arm/intro-fixed16.elf
CODE_LIMIT=65536
RAM_LIMIT=32768
status=0
pass() { echo "ok   $*"; }
fail() { echo "FAIL $*"; status=1; }

for f in "$FIXED" "$FLOAT"; do
  [ -f "$f" ] || { echo "FAIL $f is missing (make arm)"; exit 1; }
done

# Section sizes in bytes, by name, from `size -A` (0 for a section the image does not have).
section() { arm-none-eabi-size -A "$1" | awk -v s="$2" '$1 == s { print $2 + 0; found = 1 } END { if (!found) print 0 }'; }
for f in "$FIXED" "$FLOAT"; do
  [ "$(section "$f" .text)" -gt 0 ] || { echo "FAIL $f: no .text section (size -A failed?)"; exit 1; }
done
code_bytes() { echo $(($(section "$1" .text) + $(section "$1" .rodata) + $(section "$1" .ARM.exidx) + $(section "$1" .data))); }
ram_bytes() { echo $(($(section "$1" .data) + $(section "$1" .bss) + $(section "$1" .stack))); }

print_sizes() {
  local f
  for f in "$FIXED" "$FIXED16" "$FLOAT"; do
    [ -f "$f" ] || continue
    # the 64 KiB limit is the fixed images' (the soft-float image is the comparison build)
    local limit="limit $CODE_LIMIT" ram_limit="limit $RAM_LIMIT"
    [ "$f" = "$FLOAT" ] && limit="comparison build, no limit" && ram_limit="no limit"
    printf '%s: code+rodata+data %d B (%s), data %d + bss %d + stack reserve %d = %d B RAM (%s), framebuffers %d B\n' \
      "$f" "$(code_bytes "$f")" "$limit" "$(section "$f" .data)" "$(section "$f" .bss)" \
      "$(section "$f" .stack)" "$(ram_bytes "$f")" "$ram_limit" "$(section "$f" .fb)"
  done
}

if [ "${1:-}" = --print ]; then
  print_sizes
  exit 0
fi

# Instructions that use the floating-point unit or any coprocessor, whatever their condition
# and however objdump names them: every ARM instruction word whose bits 27:26 are 11, other than
# SVC (bits 27:24 = 1111), is a coprocessor instruction (VFP, FPA, CP15 alike); plus anything
# objdump shows with a VFP mnemonic (v..., f...). Data in code (.word) is skipped. Prints the
# count.
fp_instructions() {
  arm-none-eabi-objdump -d "$1" |
    awk -F'\t' 'NF >= 3 && $3 !~ /^\./ {
                  w = $2; gsub(/ /, "", w); m = $3; sub(/[ \t].*/, "", m)
                  if (length(w) == 8 && index("cde", substr(w, 2, 1)) > 0) n++
                  else if (m ~ /^(v|f)[a-z]/) n++ }
                END { print n + 0 }'
}
# Soft-float helpers (AEABI, libgcc and half-precision names) and libm functions, in the
# symbol table.
fp_symbols() {
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

# Library code linked in (the map's archive members): the fixed image may only contain
# libfixmath, newlib's memory functions, libgcc's integer division, multiplication and bit
# counting, and the switch-table helpers of the Thumb code (Makefile: ARM_COLD_SRCS).
members() { awk '/^Archive member included/,/^Discarded input sections/' "$1.map" | grep -o '[^/ ]*\.a([^)]*)' | sort -u; }
ALLOWED='^(libfixmath\.a\(.*\)|libc\.a\(lib_a-(memcmp|memcpy|memcpy-stub|memset|memmove)\.o\)|libgcc\.a\(_(aeabi_u?ldivmod|clz[sd]i2|u?divsi3|dvmd_tls|u?divmoddi4|u?divdi3|u?moddi3|ashldi3|ashrdi3|lshrdi3|muldi3|thumb1_case_[su]?[qh]i)\.o\))$'

n=$(fp_instructions "$FIXED")
[ "$n" -eq 0 ] && pass "arm: fixed image has no floating-point or coprocessor instruction" ||
  fail "arm: fixed image has $n floating-point/coprocessor instructions: $(arm-none-eabi-objdump -d "$FIXED" | grep -E '\s(v|f)[a-z]' | head -3)"
syms=$(fp_symbols "$FIXED")
[ -z "$syms" ] && pass "arm: fixed image calls no soft-float helper or libm function" ||
  fail "arm: fixed image contains floating-point functions: $(echo $syms)"

if [ -f "$FIXED16" ]; then
  n=$(fp_instructions "$FIXED16")
  syms=$(fp_symbols "$FIXED16")
  if [ "$n" -eq 0 ] && [ -z "$syms" ]; then
    pass "arm: fixed16 image has no floating-point instruction, soft-float helper or libm function (code+rodata+data $(code_bytes "$FIXED16") B)"
  else
    fail "arm: fixed16 image: $n floating-point/coprocessor instructions, functions: $(echo "$syms" | tr '\n' ' ')"
  fi
else
  fail "arm: $FIXED16 is missing (make arm)"
fi

others=$(members "$FIXED" | grep -Ev "$ALLOWED" || true)
nm_=$(members "$FIXED" | wc -l)
[ "$nm_" -gt 0 ] && [ -z "$others" ] && pass "arm: fixed image links only allowed library code ($nm_ members: libfixmath, memcpy/memset/memcmp, integer division, Thumb switch tables)" ||
  fail "arm: fixed image links other library code: $(echo $others) ($nm_ members)"

# Positive controls: the float image is full of soft-float helpers and libm, and the
# instruction scan finds VFP/coprocessor instructions, conditional ones too, in an object that
# has some.
others=$(members "$FLOAT" | grep -Ev "$ALLOWED" | wc -l)
[ "$others" -ge 5 ] && pass "arm: positive control: the float image links $others library members outside the allow-list" ||
  fail "arm: positive control: the float image links only $others library members outside the allow-list"
syms=$(fp_symbols "$FLOAT" | wc -l)
[ "$syms" -ge 5 ] && pass "arm: positive control: the scan finds $syms soft-float/libm functions in the float image" ||
  fail "arm: positive control: the scan finds only $syms floating-point functions in the float image"
ctl=$B/arm/vfp-control.o
printf '\t.arm\n\t.fpu vfp\n\tvadd.f32 s0, s0, s1\n\tvmul.f64 d0, d1, d2\n\tmrc p15, 0, r0, c0, c0, 0\n\tvaddeq.f32 s0, s0, s1\n\tmrceq p15, 0, r0, c0, c0, 0\n\tldceq p1, c0, [r0]\n\tcdpne p10, 0, c0, c1, c2, 0\n\tsvc 0x123456\n\tadd r0, r0, r1\n' |
  arm-none-eabi-as -mcpu=arm926ej-s -o "$ctl" -
n=$(fp_instructions "$ctl")
[ "$n" -eq 7 ] && pass "arm: positive control: the scan finds the 7 VFP/coprocessor instructions of a test object (conditional ones too), and not its svc and add" ||
  fail "arm: positive control: the scan finds $n, not 7, VFP/coprocessor instructions in a test object"

code=$(code_bytes "$FIXED")
[ "$code" -le "$CODE_LIMIT" ] && pass "arm: fixed image code+rodata+data $code B <= $CODE_LIMIT B" ||
  fail "arm: fixed image code+rodata+data $code B > $CODE_LIMIT B"
ram=$(ram_bytes "$FIXED")
[ "$ram" -le "$RAM_LIMIT" ] && pass "arm: fixed image data+bss+stack reserve $ram B <= $RAM_LIMIT B (framebuffers apart)" ||
  fail "arm: fixed image data+bss+stack reserve $ram B > $RAM_LIMIT B"
exit $status
