#!/usr/bin/env bash
# m3_check.sh: the static budgets of the Cortex-M3 image: no floating point (with positive controls), flash and RAM sizes.
#
# Usage: tests/m3_check.sh [--print]
#   Prints `ok ...` / `FAIL ...` lines (tests/run.sh counts them) and exits 1 if any check fails.
#   --print only prints the image's sizes (make m3), checking nothing.
# Checks:
#   - build/m3/intro-fixed.elf has no floating-point or coprocessor instruction (objdump: every
#     32-bit Thumb-2 instruction whose first halfword has bits 15:13 = 111 and 11:10 = 11 is a
#     coprocessor one, VFP included; plus any v.../f... mnemonic), no soft-float helper or libm
#     function (its symbol table, the same patterns as tests/arm_check.sh) and only the allowed
#     library members; the scans do find VFP/coprocessor instructions in a Thumb object assembled
#     here and soft-float helpers in a Cortex-M3 object compiled from float C;
#   - flash: vector table + code + read-only data + initialised data <= 64 KiB;
#   - RAM: .data + .bss + the 8 KiB stack reserve <= 32 KiB here (the budget, 24 KiB with the
#     measured stack peak instead of the reserve, is checked by tests/m3.sh from a run).
set -u
cd "$(dirname "$0")/.."

B=build
ELF=$B/m3/intro-fixed.elf
FLASH_LIMIT=65536
RESERVE_LIMIT=32768
status=0
pass() { echo "ok   $*"; }
fail() { echo "FAIL $*"; status=1; }

[ -f "$ELF" ] || { echo "FAIL $ELF is missing (make m3)"; exit 1; }
section() { arm-none-eabi-size -A "$1" | awk -v s="$2" '$1 == s { print $2 + 0; found = 1 } END { if (!found) print 0 }'; }
[ "$(section "$ELF" .text)" -gt 0 ] || { echo "FAIL $ELF: no .text section (size -A failed?)"; exit 1; }
flash_bytes() { echo $(($(section "$1" .vectors) + $(section "$1" .text) + $(section "$1" .rodata) + $(section "$1" .ARM.exidx) + $(section "$1" .data))); }
ram_bytes() { echo $(($(section "$1" .data) + $(section "$1" .bss) + $(section "$1" .stack))); }

if [ "${1:-}" = --print ]; then
  printf '%s: flash (vectors+code+rodata+data) %d B (limit %d of the chip'"'"'s 256 KiB), RAM data %d + bss %d + stack reserve %d = %d B of 64 KiB (make qemu-m3-frames prints the measured peak)\n' \
    "$ELF" "$(flash_bytes "$ELF")" "$FLASH_LIMIT" "$(section "$ELF" .data)" "$(section "$ELF" .bss)" \
    "$(section "$ELF" .stack)" "$(ram_bytes "$ELF")"
  exit 0
fi

# Thumb-2 coprocessor instructions (VFP is coprocessors 10 and 11): 32-bit encodings whose first
# halfword is 111x 11xx xxxx xxxx, whatever the condition of an IT block; plus VFP mnemonics.
# Literal-pool data (.word) is skipped. Prints the count. (No {n} intervals: mawk has none.)
fp_instructions() {
  arm-none-eabi-objdump -d "$1" |
    awk -F'\t' 'NF >= 3 && $3 !~ /^\./ {
                  w = $2; gsub(/ +$/, "", w); m = $3; sub(/[ \t].*/, "", m)
                  if (length(w) == 9 && substr(w, 5, 1) == " " && w ~ /^[ef][c-f]/) n++
                  else if (m ~ /^(v|f)[a-z]/) n++ }
                END { print n + 0 }'
}
# Soft-float helpers and libm functions in the symbol table (defined or called).
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
members() { awk '/^Archive member included/,/^Discarded input sections/' "$1.map" | grep -o '[^/ ]*\.a([^)]*)' | sort -u; }
ALLOWED='^(libfixmath\.a\(.*\)|libc\.a\(lib_a-(memcmp|memcpy|memcpy-stub|memset|memmove)\.o\)|libgcc\.a\(_(aeabi_u?ldivmod|clz[sd]i2|u?divsi3|dvmd_tls|u?divmoddi4|u?divdi3|u?moddi3|ashldi3|ashrdi3|lshrdi3|muldi3)\.o\))$'

n=$(fp_instructions "$ELF")
[ "$n" -eq 0 ] && pass "m3: image has no floating-point or coprocessor instruction" ||
  fail "m3: image has $n floating-point/coprocessor instructions"
syms=$(fp_symbols "$ELF")
[ -z "$syms" ] && pass "m3: image calls no soft-float helper or libm function" ||
  fail "m3: image contains floating-point functions: $(echo $syms)"
others=$(members "$ELF" | grep -Ev "$ALLOWED" || true)
nm_=$(members "$ELF" | wc -l)
[ "$nm_" -gt 0 ] && [ -z "$others" ] && pass "m3: image links only allowed library code ($nm_ members: libfixmath, memcpy/memset/memcmp, integer division)" ||
  fail "m3: image links other library code: $(echo $others) ($nm_ members)"

# Positive controls: VFP and coprocessor instructions in a Thumb object (in and out of an IT
# block) are found, its bkpt, add and 32-bit load are not; float C compiled for the M3 calls
# soft-float helpers that the symbol scan finds.
mkdir -p $B/m3
ctl=$B/m3/vfp-control.o
printf '\t.syntax unified\n\t.cpu cortex-m4\n\t.fpu fpv4-sp-d16\n\t.thumb\n\tvadd.f32 s0, s0, s1\n\tvmul.f32 s2, s0, s1\n\tmrc p15, 0, r0, c0, c0, 0\n\tit eq\n\tvaddeq.f32 s0, s0, s1\n\tldc p1, c0, [r0]\n\tcdp p10, 0, c0, c1, c2, 0\n\tvmov r0, s0\n\tbkpt 0xab\n\tadd r0, r0, r1\n\tldr.w r3, [r2], #4\n' |
  arm-none-eabi-as -o "$ctl" -
n=$(fp_instructions "$ctl")
[ "$n" -eq 7 ] && pass "m3: positive control: the scan finds the 7 VFP/coprocessor instructions of a Thumb test object (one in an IT block), and not its bkpt, add and ldr.w" ||
  fail "m3: positive control: the scan finds $n, not 7, VFP/coprocessor instructions in a Thumb test object"
fctl=$B/m3/float-control.o
printf 'float m3_control(float a, float b) { return a * b + (float)(int)a / b; }\n' |
  arm-none-eabi-gcc -mcpu=cortex-m3 -mthumb -mfloat-abi=soft -O2 -x c -c -o "$fctl" -
syms=$(fp_symbols "$fctl" | wc -l)
[ "$syms" -ge 3 ] && pass "m3: positive control: the scan finds $syms soft-float helpers in float C compiled for the M3" ||
  fail "m3: positive control: the scan finds only $syms soft-float helpers in float C compiled for the M3"

flash=$(flash_bytes "$ELF")
[ "$flash" -le "$FLASH_LIMIT" ] && pass "m3: flash (vectors+code+rodata+data) $flash B <= $FLASH_LIMIT B" ||
  fail "m3: flash (vectors+code+rodata+data) $flash B > $FLASH_LIMIT B"
ram=$(ram_bytes "$ELF")
[ "$ram" -le "$RESERVE_LIMIT" ] && pass "m3: data+bss+stack reserve $ram B <= $RESERVE_LIMIT B" ||
  fail "m3: data+bss+stack reserve $ram B > $RESERVE_LIMIT B"
exit $status
