#!/usr/bin/env bash
# arm_check.sh: the static budgets of the ARM926 images: no floating point in the fixed image (with positive controls), code and RAM sizes.
#
# Usage: tests/arm_check.sh [--print]
#   Prints `ok ...` / `FAIL ...` lines (tests/run.sh counts them) and exits 1 if any check fails.
#   --print only prints the sizes of both images (make arm), checking nothing.
# Checks:
#   - build/arm/intro-fixed.elf has no VFP/coprocessor instruction (objdump) and no soft-float
#     helper or libm function (its symbol table); the same scans do find soft-float helpers in
#     intro-float.elf, and VFP instructions in a small object assembled here;
#   - code + read-only data + initialised data of the fixed image <= 64 KiB (the original's limit);
#   - .data + .bss + the reserved stack of the fixed image <= 32 KiB (the measured stack peak is
#     checked by tests/arm.sh from a run).
set -u
cd "$(dirname "$0")/.."

B=build
FIXED=$B/arm/intro-fixed.elf
FLOAT=$B/arm/intro-float.elf
CODE_LIMIT=65536
RAM_LIMIT=32768
status=0
pass() { echo "ok   $*"; }
fail() { echo "FAIL $*"; status=1; }

for f in "$FIXED" "$FLOAT"; do
  [ -f "$f" ] || { echo "FAIL $f is missing (make arm)"; exit 1; }
done

# Section sizes in bytes, by name, from `size -A`.
section() { arm-none-eabi-size -A "$1" | awk -v s="$2" '$1 == s { print $2 + 0; found = 1 } END { if (!found) print 0 }'; }
code_bytes() { echo $(($(section "$1" .text) + $(section "$1" .rodata) + $(section "$1" .ARM.exidx) + $(section "$1" .data))); }
ram_bytes() { echo $(($(section "$1" .data) + $(section "$1" .bss) + $(section "$1" .stack))); }

print_sizes() {
  local f
  for f in "$FIXED" "$FLOAT"; do
    printf '%s: code+rodata+data %d B (limit %d), data %d + bss %d + stack reserve %d = %d B RAM (limit %d), framebuffers %d B\n' \
      "$f" "$(code_bytes "$f")" "$CODE_LIMIT" "$(section "$f" .data)" "$(section "$f" .bss)" \
      "$(section "$f" .stack)" "$(ram_bytes "$f")" "$RAM_LIMIT" "$(section "$f" .fb)"
  done
}

if [ "${1:-}" = --print ]; then
  print_sizes
  exit 0
fi

# Instructions that use the floating-point unit or any coprocessor: VFP mnemonics (v..., and the
# old f... forms) and the generic coprocessor operations. Integer ARM mnemonics never start with
# v or f. Prints the count.
fp_instructions() {
  arm-none-eabi-objdump -d "$1" |
    awk -F'\t' 'NF >= 3 { m = $3; sub(/[ \t].*/, "", m);
                  if (m ~ /^(v|f)[a-z]/ || m ~ /^(cdp|ldc|stc|mcr|mrc|mcrr|mrrc)2?l?$/) n++ }
                END { print n + 0 }'
}
# Soft-float helpers (AEABI and libgcc names) and libm functions, in the symbol table.
fp_symbols() {
  arm-none-eabi-nm "$1" |
    awk '{ s = $NF }
         s ~ /^__aeabi_([fd](add|sub|rsub|mul|div|neg|cmp|cmpeq|cmplt|cmple|cmpge|cmpgt|cmpun|2)|[ul]?[il]2[fd]|[fd]2)/ ||
         s ~ /^__(add|sub|mul|div|neg|cmp|eq|ne|lt|le|gt|ge|unord)[sdt]f[23]$/ ||
         s ~ /^__(fix|fixuns)[sdt]f[sdt]i$/ || s ~ /^__float(un)?[sdt]i[sdt]f$/ ||
         s ~ /^__(extend|trunc)[sdt]f[sdt]f2$/ ||
         s ~ /^(sqrt|sin|cos|tan|atan2?|exp|log|pow|floor|ceil|fabs|fmod)f?$/ { print s }' | sort -u
}

n=$(fp_instructions "$FIXED")
[ "$n" -eq 0 ] && pass "arm: fixed image has no floating-point or coprocessor instruction" ||
  fail "arm: fixed image has $n floating-point/coprocessor instructions: $(arm-none-eabi-objdump -d "$FIXED" | grep -E '\s(v|f)[a-z]' | head -3)"
syms=$(fp_symbols "$FIXED")
[ -z "$syms" ] && pass "arm: fixed image calls no soft-float helper or libm function" ||
  fail "arm: fixed image contains floating-point functions: $(echo $syms)"

# Positive controls: the float image is full of soft-float helpers, and the instruction scan
# finds VFP instructions in an object that has some.
syms=$(fp_symbols "$FLOAT" | wc -l)
[ "$syms" -ge 5 ] && pass "arm: positive control: the scan finds $syms soft-float/libm functions in the float image" ||
  fail "arm: positive control: the scan finds only $syms floating-point functions in the float image"
ctl=$B/arm/vfp-control.o
printf '\t.arm\n\t.fpu vfp\n\tvadd.f32 s0, s0, s1\n\tvmul.f64 d0, d1, d2\n\tmrc p15, 0, r0, c0, c0, 0\n' |
  arm-none-eabi-as -mcpu=arm926ej-s -o "$ctl" -
n=$(fp_instructions "$ctl")
[ "$n" -eq 3 ] && pass "arm: positive control: the scan finds the 3 VFP/coprocessor instructions of a test object" ||
  fail "arm: positive control: the scan finds $n of the 3 VFP/coprocessor instructions of a test object"

code=$(code_bytes "$FIXED")
[ "$code" -le "$CODE_LIMIT" ] && pass "arm: fixed image code+rodata+data $code B <= $CODE_LIMIT B" ||
  fail "arm: fixed image code+rodata+data $code B > $CODE_LIMIT B"
ram=$(ram_bytes "$FIXED")
[ "$ram" -le "$RAM_LIMIT" ] && pass "arm: fixed image data+bss+stack reserve $ram B <= $RAM_LIMIT B (framebuffers apart)" ||
  fail "arm: fixed image data+bss+stack reserve $ram B > $RAM_LIMIT B"
exit $status
