#!/usr/bin/env bash
# cycles.sh: the cycle model (platform/arm/qemu_profile.c) against hand counts: small ARM926, Cortex-M3 and Cortex-M0 programs give exactly the cycles and cache misses worked out below, and the intro's frames the board's own instruction counts.
#
# Expects make arm m3 m0 (the plugin build/arm/qemu_profile.so and the intro images). Builds the
# programs of tests/cycles/arm926.S, m3.S and m0.S (one per CASE_*), runs each under
# qemu-system-arm -icount shift=0 with the plugin's window on its t_start..t_stop part, and
# compares the plugin's instructions, cycles and D-cache read misses in the window with the
# figures counted by hand from docs/arm.md's, docs/m3.md's and docs/m0.md's cycle tables (the sums are written
# out beside each case). Prints `ok ...` / `FAIL ...` lines (tests/run.sh counts them), exits 1
# if any check fails.
set -u
cd "$(dirname "$0")/.."

B=build
T=$B/test/cycles
rm -rf "$T" && mkdir -p "$T"
PLUGIN=$B/arm/qemu_profile.so
status=0
pass() { echo "ok   $*"; }
fail() { echo "FAIL $*"; status=1; }

[ -f "$PLUGIN" ] || { fail "cycles: $PLUGIN is missing (make arm builds it)"; exit 1; }

cat >"$T/arm926.ld" <<'EOF'
ENTRY(_start)
SECTIONS { . = 0x10000; .text : { *(.text*) } .data : { *(.data*) } .bss : { *(.bss*) } }
EOF
cat >"$T/m3.ld" <<'EOF'
ENTRY(_start)
SECTIONS { . = 0; .text : { *(.vectors) *(.text*) *(.data*) } . = 0x20000000; .bss : { *(.bss*) } }
EOF
cp "$T/m3.ld" "$T/m0.ld"

# run CPU NAME OPTS DEFINES...: builds the case, runs it with plugin options OPTS; sets ins, cyc
# and dmiss to the window's figures (empty on failure).
run() {
  local cpu=$1 name=$2 opts=$3 elf=$T/$1-$2.elf out=$T/$1-$2.txt a s e
  shift 3
  ins="" cyc="" dmiss=""
  case $cpu in
    arm926) a=(-mcpu=arm926ej-s -marm) ;;
    m3) a=(-mcpu=cortex-m3 -mthumb) ;;
    *) a=(-mcpu=cortex-m0 -mthumb) ;;
  esac
  if ! arm-none-eabi-gcc "${a[@]}" -nostdlib -nostartfiles -T "$T/$cpu.ld" -Wl,--no-warn-rwx-segments \
       "$@" "tests/cycles/$cpu.S" -o "$elf" 2>"$T/$cpu-$name.build"; then
    fail "cycles: $cpu $name does not build: $(head -3 "$T/$cpu-$name.build" | tr '\n' ' ')"
    return
  fi
  s=$(arm-none-eabi-nm "$elf" | awk '$3 == "t_start" { print "0x" $1 }')
  e=$(arm-none-eabi-nm "$elf" | awk '$3 == "t_stop" { print "0x" $1 }')
  case $cpu in
    arm926) m=(-M versatilepb -m 16) ;;
    m3) m=(-M lm3s6965evb) ;;
    *) m=(-M microbit) ;;
  esac
  if ! timeout -k 5 60 qemu-system-arm "${m[@]}" -display none -serial null -monitor none -kernel "$elf" \
       -semihosting-config enable=on,target=native -icount shift=0,align=off,sleep=off \
       -plugin "$PLUGIN,out=$out,cpu=$cpu,start=$s,stop=$e,$opts" </dev/null >"$T/$cpu-$name.log" 2>&1; then
    fail "cycles: $cpu $name: QEMU failed: $(tail -2 "$T/$cpu-$name.log" | tr '\n' ' ')"
    return
  fi
  ins=$(awk '$1 == "window_total" { print $2 }' "$out")
  cyc=$(awk '$1 == "window_cycles" { print $2 }' "$out")
  dmiss=$(awk '$1 == "window_dmiss" { print $2 }' "$out")
}

# check CPU NAME OPTS INSNS CYCLES DMISSES WHY DEFINES...
check() {
  local cpu=$1 name=$2 opts=$3 wi=$4 wc=$5 wd=$6 why=$7
  shift 7
  run "$cpu" "$name" "$opts" "$@"
  [ -n "$ins" ] || return
  if [ "$ins" = "$wi" ] && [ "$cyc" = "$wc" ] && [ "$dmiss" = "$wd" ]; then
    pass "cycles: $cpu $name: $ins instructions, $cyc cycles, $dmiss D-cache misses, as counted by hand ($why)"
  else
    fail "cycles: $cpu $name: $ins instructions, $cyc cycles, $dmiss D-misses; by hand $wi, $wc, $wd ($why)"
  fi
}

NOCACHE=icache=0,dcache=0
# ---- ARM926EJ-S, caches off: the core's table alone ---------------------------------------
check arm926 ldchain $NOCACHE 32 63 0 "32 LDR r0,[r0]: 32 x 1 + 31 load-use interlocks" -DCASE_LDCHAIN
check arm926 ldbyte $NOCACHE 40 64 0 "8 x (LDRB; ADD using it: 1 + 2 + 1) + 8 x (LDRB; MOV; ADD: 1 + 1 + 1 + 1)" -DCASE_LDBYTE
check arm926 mul $NOCACHE 16 47 0 "16 dependent MUL: 16 x 2 + 15 result interlocks" -DCASE_MUL
check arm926 smull $NOCACHE 16 63 0 "16 dependent SMULL: 16 x 3 + 15 result interlocks" -DCASE_SMULL
check arm926 loop $NOCACHE 101 199 0 "MOV + 50 SUBS + 49 taken BNE x 3 + 1 not taken" -DCASE_LOOP
check arm926 ldmstm $NOCACHE 8 38 0 "LDM 4 + STM 7 + LDM of 1 register 2 + STM 2 + LDM 3 + ADD 1 + interlock 1 + PUSH 9 + POP 9" -DCASE_LDMSTM
check arm926 thumb $NOCACHE 50 104 0 "Thumb: PUSH 5 + POP 4 + POP of 1 register 2 + MOVS 1 + 20 SUBS + 19 taken BNE x 3 + 1 + LDR, ADDS using it 3 + LDRB, ADDS using it 4 + BL pair 4 + BX LR 3" -DCASE_THUMB
# ---- ARM926 D-cache: 16 KiB, 4 ways, 32-byte lines (128 sets), round-robin, 24-cycle fill --
# Two passes of L reads, each pass 5L cycles of instructions (2 MOV, L LDR, L SUBS, L-1 taken
# BNE at 3, 1 not taken); the misses add 24 each.
D=icache=0,dcache=16384,ways=4,line=32,dmiss=24,repl=rr
check arm926 walk8k $D 1540 8704 256 "256 lines of 32 B (2 a set, within 4 ways): 256 misses, all in the first pass; 10 x 256 + 24 x 256" \
  -DCASE_WALK -DWALK_LINES=256 "-DWALK_STRIDE=#32"
check arm926 walk32k $D 6148 59392 2048 "1024 lines (8 a set): round-robin evicts each line before its second read: 2048 misses; 10 x 1024 + 24 x 2048" \
  -DCASE_WALK -DWALK_LINES=1024 "-DWALK_STRIDE=#32"
check arm926 walk1set $D 34 290 10 "5 lines 4096 B apart, all in one set of 4 ways: every read misses, 10; 10 x 5 + 24 x 10" \
  -DCASE_WALK -DWALK_LINES=5 -DWALK_STRIDE=r7
check arm926 walk1set-lru "${D/repl=rr/repl=lru}" 34 290 10 "the same under LRU: 10 misses" \
  -DCASE_WALK -DWALK_LINES=5 -DWALK_STRIDE=r7
check arm926 walk4set $D 28 136 4 "4 lines 4096 B apart fit the set's 4 ways: 4 misses, all in the first pass; 10 x 4 + 24 x 4" \
  -DCASE_WALK -DWALK_LINES=4 -DWALK_STRIDE=r7

# The default caches (16 KiB each, 4 ways, 32-byte lines, 24-cycle fills) on the load chain: its
# 128 bytes of code are 4 lines fetched for the first time (4 I-misses, 96 cycles, of which the
# first instruction of lines 2-4 hides the one-cycle interlock it waits for anyway: 93 more); the
# word it reads shares its line with the literal loaded before the window: no D-miss. 63 + 93.
check arm926 ldchain-caches "" 32 156 0 "63 + 4 I-misses x 24 - 3 interlocks hidden under them" -DCASE_LDCHAIN

# ---- Cortex-M3 (no caches; P = 2, UMULL 5, UDIV 12: the plugin's defaults) -----------------
check m3 ldchain "" 32 64 0 "32 LDR r0,[r0]: each address waits for the load before: 2 cycles each" -DCASE_LDCHAIN
check m3 ldindep "" 32 33 0 "32 independent LDR: 2 + 31 pipelined at 1" -DCASE_LDINDEP
check m3 umull "" 16 80 0 "16 UMULL at the table's upper 5" -DCASE_UMULL
check m3 umull3 lmul=3 16 48 0 "16 UMULL with lmul=3" -DCASE_UMULL
check m3 udiv "" 8 96 0 "8 UDIV at the table's upper 12" -DCASE_DIV
check m3 loop "" 101 199 0 "MOVS + 50 SUBS + 49 taken BNE x (1 + P) + 1 not taken" -DCASE_LOOP
check m3 loop-p1 refill=1 101 150 0 "the same with P = 1: 1 + 50 + 49 x 2 + 1" -DCASE_LOOP
check m3 ldmstm "" 6 33 0 "PUSH 5 regs 6 + POP 4: 5 + POP 1: 2 + LDMIA 3: 4 + STMIA 3: 4 + LDMIA.W 11: 12" -DCASE_LDMSTM

# ---- Cortex-M0 (no caches, no wait states; MULS 1, the single-cycle multiplier) -----------
check m0 ldchain "" 32 64 0 "32 LDR r0,[r0] at 2" -DCASE_LDCHAIN
check m0 ldindep "" 32 64 0 "32 independent LDR, still 2 each: no pipelining on the M0" -DCASE_LDINDEP
check m0 muls "" 16 16 0 "16 MULS at 1" -DCASE_MULS
check m0 muls32 muls=32 16 512 0 "16 MULS on the small multiplier, muls=32" -DCASE_MULS
check m0 loop "" 101 199 0 "MOVS + 50 SUBS + 49 taken BNE x 3 + 1 not taken" -DCASE_LOOP
check m0 ldmstm "" 5 21 0 "PUSH 5 regs 6 + POP 4: 5 + POP 1: 2 + LDMIA 3: 4 + STMIA 3: 4" -DCASE_LDMSTM
check m0 calls "" 6 23 0 "BL 4 + PUSH 2 regs 3 + POP with the PC 4 + 2 + BL 4 + BX LR 3 + B 3" -DCASE_CALLS

# ---- the intro: the plugin's instructions a frame against the board's icount figures --------
# The board times each band of a frame from a clock read before it to one after it; the plugin
# counts from rt_render_band_into's entry to plat_time_ns's: the difference is the same few
# instructions each band (the calls around the clock reads), seen through the clock's step (125/3
# ns on the ARM926, 20 ns on the M3). Each band's time is the difference of two readings of that
# clock, each rounded down to a step, so it is within one step either side of the true count:
# with B bands a frame (the plugin's windows over its frames: 1 on the ARM926, 8 on the M3, 16 on
# the M0, whose clock steps 62.5 instructions), all
# frames' differences lie within 2 B steps of each other, and below 100 B. A second run gives the
# same instructions and cycles for every frame (the estimate repeats exactly).
intro() { # BOARD SCRIPT STEP ARGS...
  local board=$1 script=$2 step=$3
  shift 3
  if QEMU_CYCLES_OUT="$T/$board-intro.txt" "$script" bench "$@" >"$T/$board-intro.log" 2>&1; then
    local d
    d=$(awk 'FNR == 1 { f++ } f == 1 && $1 == "windows" { w = $2 } f == 1 && $1 == "frame" { p[++n] = $2 }
      f == 2 && /^frame=/ { split($2, a, "="); b[++m] = a[2] }
      END { if (n != m || n == 0 || w % n) { print "frames: plugin " n ", board " m ", windows " w; exit }
            lo = 1e18; hi = -1e18; for (i = 1; i <= n; i++) { x = b[i] - p[i]; s = s " " x; if (x < lo) lo = x; if (x > hi) hi = x }
            print lo, hi, w / n, s }' "$T/$board-intro.txt" "$T/$board-intro.log")
    read -r lo hi bands _ <<<"$d"
    if [[ "$lo" =~ ^[0-9]+$ ]] && [[ "$hi" =~ ^[0-9]+$ ]] && [ $((hi - lo)) -le $((2 * bands * step)) ] && [ "$hi" -lt $((bands * 100)) ]; then
      pass "cycles: $board intro frames $*: the board's icount minus the plugin's count, $bands band(s) a frame:${d#* * * } (within 2 x $bands x the $step-instruction clock step)"
    else
      fail "cycles: $board intro frames $*: the board's icount minus the plugin's count: $d"
    fi
    if ! grep -q '^cycles: [0-9.]* a instruction' "$T/$board-intro.log" || ! grep -q '^worst=[0-9]* cycles=[0-9]*$' "$T/$board-intro.log"; then
      fail "cycles: $board bench prints no cycles line: $(tail -3 "$T/$board-intro.log" | tr '\n' ' ')"
    fi
    if CYCLES=1 "$script" bench "$@" >"$T/$board-intro-2.log" 2>&1 &&
       [ "$(grep -c '^frame=[0-9]* instructions=[0-9]* cycles=[0-9]*$' "$T/$board-intro.log")" -gt 0 ] &&
       diff <(grep '^frame=' "$T/$board-intro.log") <(grep '^frame=' "$T/$board-intro-2.log") >/dev/null; then
      pass "cycles: $board intro frames $*: a second run gives the same instructions and cycles for every frame ($(grep '^frame=' "$T/$board-intro.log" | sed 's/.*cycles=//' | tr '\n' ' '))"
    else
      fail "cycles: $board intro frames $*: the second run's instructions or cycles differ: $(diff <(grep '^frame=' "$T/$board-intro.log") <(grep '^frame=' "$T/$board-intro-2.log") | head -2 | tr '\n' ' ')"
    fi
  else
    fail "cycles: $board bench $*: $(tail -2 "$T/$board-intro.log" | tr '\n' ' ')"
  fi
}
intro arm926 platform/arm/qemu.sh 42 fixed 400 700 100
intro m3 platform/m3/qemu.sh 20 0 1200 300
intro m0 platform/m0/qemu.sh 63 0 1200 300

exit $status
