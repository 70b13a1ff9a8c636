#!/usr/bin/env bash
# bench_all.sh: the intro's frames per second per platform in one table, desktop, ARM926, Cortex-M3 and Cortex-M0 under QEMU, written to docs/bench.md (make bench).
#
# Usage: tests/bench_all.sh [-o FILE]        (default docs/bench.md; with QUICK=1 build/bench/bench-quick.md)
# Desktop: tests/bench_intro.sh at 320x240 and 640x480, float and fixed, 1 thread and every
# core, each sample frame rendered by every configuration in turn (the intro every STEP_S
# seconds, ROUNDS rounds). ARM926: tests/qemu_bench.sh, the fixed and the soft-float image at
# 320x240, instructions per frame counted by QEMU (frames QEMU_FRAMES = "FIRST LAST STEP").
# Cortex-M3: platform/m3/qemu.sh bench, the fixed image at the OLED's 128x64, the same frames,
# fps at the board's 50 MHz. Cortex-M0: platform/m0/qemu.sh bench, the same frames (16 KiB of
# RAM), fps at the nRF51's 16 MHz and at 133 MHz (an RP2040's clock).
# The boards' fps are the cycle model's (the boards' qemu.sh print each frame's estimated cycles,
# docs/arm.md, Cycle model): cycles divided by the clock, with the one-instruction-a-cycle figure,
# an upper bound, in brackets.
# Defaults: STEP_S=2 (25 frames), ROUNDS=3, QEMU_FRAMES="0 1200 24" (51 frames); 16 minutes
# on the loaded 2-core build machine, most of it the soft-float image under QEMU with the cycle
# plugin. QUICK=1: 3 desktop frames in 1 round and 2 ARM frames, a smoke run of a few
# seconds (make test). Progress goes to standard error; the file is also printed.
set -euo pipefail
cd "$(dirname "$0")/.."

die() { printf 'bench: error: %s\n' "$*" >&2; exit 2; }
SIZES=320x240,640x480
CLOCK_MHZ=200   # the clock of tests/qemu_bench.sh's fps
M3_MHZ=50       # the LM3S6965's clock
M0_MHZ=16       # the nRF51822's clock
M0_FAST_MHZ=133 # an RP2040-class Cortex-M0+
if [ "${QUICK:-0}" = 1 ]; then
  out=build/bench/bench-quick.md
  rounds=${ROUNDS:-1} step=${STEP_S:-24} qemu_frames=${QEMU_FRAMES:-0 24 24}
else
  out=docs/bench.md
  rounds=${ROUNDS:-3} step=${STEP_S:-2} qemu_frames=${QEMU_FRAMES:-0 1200 24}
fi
case $# in
  0) ;;
  2) [ "$1" = -o ] || die "unknown option '$1' (usage: tests/bench_all.sh [-o FILE])"; out=$2 ;;
  *) die "usage: tests/bench_all.sh [-o FILE]" ;;
esac
[[ "$rounds" =~ ^[1-9][0-9]*$ ]] || die "ROUNDS must be a whole number >= 1, not '$rounds'"
[[ "$step" =~ ^[1-9][0-9]*$ ]] || die "STEP_S must be a whole number of seconds >= 1, not '$step'"
read -r q_first q_last q_step extra <<<"$qemu_frames" || true
[ -n "$q_step" ] && [ -z "${extra:-}" ] || die "QEMU_FRAMES must be 'FIRST LAST STEP', not '$qemu_frames'"
for f in build/rt-float build/rt-fixed build/arm/intro-fixed.elf build/arm/intro-float.elf build/m3/intro-fixed.elf build/m0/intro-fixed.elf; do
  [ -x "$f" ] || [ -f "$f" ] || die "$f is missing: run make all arm m3 m0 first"
done
mkdir -p build/bench "$(dirname "$out")"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
rows=$work/rows.tsv
: >"$rows"
cpu=$(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1)
cores=$(nproc)
load=$(cut -d' ' -f1-3 /proc/loadavg)
start=$(date +%s)
echo "bench: $cpu, $cores cores, load average $load; desktop first, then QEMU" >&2

BENCH_ROWS=$rows tests/bench_intro.sh "$SIZES" "$rounds" "$step" >"$work/desktop.txt"
# shellcheck disable=SC2086  # QEMU_FRAMES is three words on purpose
BENCH_ROWS=$rows tests/qemu_bench.sh $q_first $q_last $q_step >"$work/qemu.txt"
echo "bench: Cortex-M3 image, frames $q_first..$q_last every $q_step" >&2
# shellcheck disable=SC2086
platform/m3/qemu.sh bench $q_first $q_last $q_step >build/bench/qemu-m3.log 2>&1 ||
  die "the M3 image failed (build/bench/qemu-m3.log): $(tail -1 build/bench/qemu-m3.log)"
printf 'm3\tfixed\t128x64\t1\t%s\t%s\n' "$(sed -n 's/^frames=.* mean=\([0-9]*\).*/\1/p' build/bench/qemu-m3.log)" \
  "$(sed -n 's/^worst=\([0-9]*\).*/\1/p' build/bench/qemu-m3.log)" >>"$rows"
echo "bench: Cortex-M0 image, frames $q_first..$q_last every $q_step" >&2
# shellcheck disable=SC2086
platform/m0/qemu.sh bench $q_first $q_last $q_step >build/bench/qemu-m0.log 2>&1 ||
  die "the M0 image failed (build/bench/qemu-m0.log): $(tail -1 build/bench/qemu-m0.log)"
printf 'm0\tfixed\t128x64\t1\t%s\t%s\n' "$(sed -n 's/^frames=.* mean=\([0-9]*\).*/\1/p' build/bench/qemu-m0.log)" \
  "$(sed -n 's/^worst=\([0-9]*\).*/\1/p' build/bench/qemu-m0.log)" >>"$rows"
# cyc LOG: the mean and worst frame's estimated cycles from a board's bench log
cyc() {
  local m w
  m=$(sed -n 's/^frames=[0-9]* mean=[0-9]* cycles=\([0-9]*\)$/\1/p' "$1")
  w=$(sed -n 's/^worst=[0-9]* cycles=\([0-9]*\)$/\1/p' "$1")
  if [ -z "$m" ] || [ -z "$w" ]; then die "no cycles in $1"; fi
  echo "$m $w"
}
cycles="fixed $(cyc build/bench/qemu-fixed.log) float $(cyc build/bench/qemu-float.log) m3 $(cyc build/bench/qemu-m3.log) m0 $(cyc build/bench/qemu-m0.log)"
took=$(($(date +%s) - start))
q_n=$(grep -c '^frame=' build/bench/qemu-fixed.log)
d_n=$(seq 0 "$step" 48 | wc -l)

# What follows the marker in the file (the other measurements, docs/bench.md) is kept.
MARK='<!-- make bench writes everything above this line and keeps what follows -->'
kept=""
[ -f "$out" ] && grep -qxF "$MARK" "$out" && kept=$(sed "1,/^<!-- make bench writes everything above this line/d" "$out")
{
  echo "# Frames per second per platform: the intro"
  echo
  echo "Written by \`make bench\` (\`tests/bench_all.sh\`${QUICK:+, QUICK=$QUICK}) on $(date -u '+%Y-%m-%d %H:%M UTC'), in $took s."
  echo
  echo "- CPU: $cpu, $cores cores (\`nproc\`); load average when it started: $load"
  echo "- $(uname -sr), $(gcc --version | head -1) -O2; $(qemu-system-arm --version | head -1)"
  echo
  echo "| platform | build | size | threads | mean frame | worst frame | mean fps | worst-frame fps |"
  echo "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: |"
  awk -F'\t' -v mhz=$CLOCK_MHZ -v m3mhz=$M3_MHZ -v m0mhz=$M0_MHZ -v m0fast=$M0_FAST_MHZ -v cycles="$cycles" '
    BEGIN { n = split(cycles, c, " "); for (i = 1; i + 2 <= n; i += 3) { cm[c[i]] = c[i + 1]; cw[c[i]] = c[i + 2] } }
    function frame(ins, cy) { return sprintf("%.1f M cycles (%.1f M instructions)", cy / 1e6, ins / 1e6) }
    function fps(clock, ins, cy) { return sprintf("%.2f (%.2f)", clock * 1e6 / cy, clock * 1e6 / ins) }
    $1 == "desktop" { printf "| desktop | %s | %s | %d | %.2f ms | %.2f ms | %.1f | %.1f |\n", $2, $3, $4, $5, $6, 1000 / $5, 1000 / $6 }
    $1 == "arm926"  { printf "| ARM926, QEMU | %s | %s | %d | %s | %s | %s* | %s* |\n",
                             ($2 == "float" ? "soft-float" : "fixed"), $3, $4, frame($5, cm[$2]), frame($6, cw[$2]),
                             fps(mhz, $5, cm[$2]), fps(mhz, $6, cw[$2]) }
    $1 == "m3"      { printf "| Cortex-M3, QEMU | fixed | %s | %d | %s | %s | %s** | %s** |\n",
                             $3, $4, frame($5, cm["m3"]), frame($6, cw["m3"]), fps(m3mhz, $5, cm["m3"]), fps(m3mhz, $6, cw["m3"]) }
    $1 == "m0"      { printf "| Cortex-M0, QEMU | fixed | %s | %d | %s | %s | %s / %s*** | %s / %s*** |\n",
                             $3, $4, frame($5, cm["m0"]), frame($6, cw["m0"]), fps(m0mhz, $5, cm["m0"]), fps(m0fast, $5, cm["m0"]),
                             fps(m0mhz, $6, cw["m0"]), fps(m0fast, $6, cw["m0"]) }' "$rows"
  echo
  echo "The boards' frames: **estimated cycles** (the cycle model of [arm.md](arm.md#cycle-model),"
  echo "[m3.md](m3.md#cycle-model) and [m0.md](m0.md#cycle-model): each instruction charged its"
  echo "core's timing table, interlocks, taken branches and the ARM926's caches; an estimate, exact"
  echo "and repeatable, not a measurement on silicon) with the exact instruction counts in brackets;"
  echo "their fps are the cycles at the clock, and in brackets the fps if every instruction took one"
  echo "cycle, an upper bound no real part reaches."
  echo
  echo "\\* ARM926 fps: **at a $CLOCK_MHZ MHz clock** (an ARM926EJ-S with 16 KiB I- and D-caches)."
  echo
  echo "\\*\\* Cortex-M3 fps: **at the LM3S6965's $M3_MHZ MHz**: the"
  echo "intro at the OLED's 128x64, rendered band by band (no frame in RAM), the same frames as the"
  echo "ARM926's; sending the bands to the OLED is not counted (docs/m3.md)."
  echo
  echo "\\*\\*\\* Cortex-M0 fps: **at the nRF51822's $M0_MHZ MHz / at $M0_FAST_MHZ MHz (an RP2040-class"
  echo "clock; the RP2040's M0+ has its own, slightly faster, table)**: the same frames at the default"
  echo "settings, in 16 KiB of RAM, with no long multiply, no divide and no CLZ (docs/m0.md)."
  echo
  echo "Desktop: the tracer's own time per frame (\`render --time T --size S --threads N --stats\`,"
  echo "its \`ms=\`: rendering, without writing the file), default adaptive mode, the intro every"
  echo "$step s (T = 0 to 48 s: $d_n frames), $rounds round(s); each sample frame is rendered by"
  echo "every desktop configuration in turn, so all see the same machine load. Mean and worst are"
  echo "over all frames and rounds. ARM926: the fixed-point and the soft-float image on QEMU's"
  echo "versatilepb board under \`-icount shift=0\` (exact, repeatable counts), intro frames"
  echo "$q_first to $q_last every $q_step ($q_n frames, at 25 frames per second of the intro)."
  echo
  grep -E 'fixed takes|speed-up over' "$work/desktop.txt" | sed 's/^/- /'
  grep -E '^soft-float / fixed' "$work/qemu.txt" | sed 's/^/- ARM926: /'
  echo
  echo "## How to reproduce"
  echo
  echo '```sh'
  echo "make bench                        # builds what is missing, then writes this file (16 minutes on the loaded 2-core build machine, most of it the soft-float image under the cycle plugin)"
  echo "QUICK=1 tests/bench_all.sh        # smoke run in seconds: build/bench/bench-quick.md (make test runs it)"
  echo "ROUNDS=1 STEP_S=4 QEMU_FRAMES=\"0 1200 48\" tests/bench_all.sh -o /tmp/bench.md   # shorter"
  echo "tests/bench_intro.sh 640x480 3 2  # the desktop part alone, any sizes (comma-separated)"
  echo "make qemu-bench                   # the ARM926 part alone; per-frame counts in build/bench/qemu-*.log"
  echo '```'
  echo
  echo "The desktop times depend on what else the machine is doing: the gain from a second thread"
  echo "shrinks to nothing when the other core is busy (see the load average above). The QEMU"
  echo "instruction counts do not depend on the machine."
  if [ -n "$kept" ]; then
    echo
    echo "$MARK"
    printf '%s\n' "$kept"
  fi
} >"$out"
echo "bench: wrote $out in $took s" >&2
cat "$out"
