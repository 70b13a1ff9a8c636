#!/usr/bin/env bash
# qemu_bench.sh: instructions per intro frame on the emulated ARM926, fixed point against soft-float, from QEMU's exact instruction counting (make qemu-bench).
#
# Usage: tests/qemu_bench.sh [FIRST LAST STEP]   (default 0 1200 24: two frames a second of the intro)
# Both images render the same frames at 320x240 under `-icount shift=0`, where the guest's clock
# advances 1 ns per instruction; the counts are exact to the clock's 125/3 ns step and repeat
# run after run. Prints per-build mean and worst instructions per frame, their ratio, and frames
# per second on a 200 MHz ARM926 assuming one instruction per cycle (a real ARM926 needs more
# cycles than instructions: read those fps as an upper bound). Progress goes to standard error.
# With BENCH_ROWS=FILE, one tab-separated line per image is also appended to FILE for
# tests/bench_all.sh:   arm926 <fixed|float> 320x240 1 <mean instructions> <worst instructions> instructions
set -euo pipefail
cd "$(dirname "$0")/.."

first=${1:-0}
last=${2:-1200}
step=${3:-24}
[ $# -eq 0 ] || [ $# -eq 3 ] || { echo "usage: tests/qemu_bench.sh [FIRST LAST STEP]" >&2; exit 2; }
[[ "$first$last$step" =~ ^[0-9]+$ ]] && [ "$step" -gt 0 ] && [ "$last" -ge "$first" ] ||
  { echo "qemu-bench: error: FIRST LAST STEP must be whole numbers, FIRST <= LAST, STEP > 0" >&2; exit 2; }
CLOCK_MHZ=200
# The soft-float image's 51 frames under the cycle plugin took 530 s on a loaded 2-core machine,
# near qemu.sh's 600 s default limit: this run allows an hour unless told otherwise.
export QEMU_TIMEOUT=${QEMU_TIMEOUT:-3600}
out=build/bench
mkdir -p "$out"

nframes=$(( (last - first) / step + 1 ))
declare -A mean worst ram
for real in fixed float; do
  log=$out/qemu-$real.log
  start=$(date +%s)
  platform/arm/qemu.sh bench "$real" "$first" "$last" "$step" >"$log" 2>&1 &
  pid=$!
  # progress: the frames the guest has reported so far, once a second
  while kill -0 "$pid" 2>/dev/null; do
    printf '\rqemu-bench: %s image, frames %s..%s every %s: frame %d/%d, %d s ' "$real" "$first" "$last" \
      "$step" "$(grep -c '^frame=' "$log" || true)" "$nframes" "$(($(date +%s) - start))" >&2
    sleep 1
  done
  if ! wait "$pid"; then
    echo >&2
    echo "qemu-bench: error: the $real run failed:" >&2
    tail -3 "$log" >&2
    exit 1
  fi
  printf '\rqemu-bench: %s image, frames %s..%s every %s: %d frames in %d s of host time\n' "$real" "$first" \
    "$last" "$step" "$(grep -c '^frame=' "$log")" "$(($(date +%s) - start))" >&2
  mean[$real]=$(sed -n 's/^frames=.* mean=\([0-9]*\).*/\1/p' "$log")
  worst[$real]=$(sed -n 's/^worst=\([0-9]*\).*/\1/p' "$log")
  ram[$real]=$(sed -n 's/^ram: //p' "$log")
done

frames=$(grep -c '^frame=' "$out/qemu-fixed.log")
echo "intro at 320x240, frames $first..$last every $step ($frames frames), ARM926 (versatilepb) under qemu-system-arm -icount shift=0"
echo
awk -v mhz=$CLOCK_MHZ -v fm="${mean[fixed]}" -v fw="${worst[fixed]}" -v sm="${mean[float]}" -v sw="${worst[float]}" 'BEGIN {
  printf "| image | instructions per frame, mean | worst | fps at %d MHz, 1 instruction/cycle: mean | worst |\n", mhz
  printf "|---|---:|---:|---:|---:|\n"
  printf "| fixed point (Q16.16) | %.1f M | %.1f M | %.2f | %.2f |\n", fm / 1e6, fw / 1e6, mhz * 1e6 / fm, mhz * 1e6 / fw
  printf "| soft-float | %.1f M | %.1f M | %.2f | %.2f |\n", sm / 1e6, sw / 1e6, mhz * 1e6 / sm, mhz * 1e6 / sw
  printf "\nsoft-float / fixed: %.2fx the instructions on the mean frame, %.2fx on the worst\n", sm / fm, sw / fw
}'
echo "RAM besides the framebuffers (fixed): ${ram[fixed]}"
if [ -n "${BENCH_ROWS:-}" ]; then
  printf 'arm926\t%s\t320x240\t1\t%s\t%s\tinstructions\n' fixed "${mean[fixed]}" "${worst[fixed]}" \
    float "${mean[float]}" "${worst[float]}" >>"$BENCH_ROWS"
fi
echo "per-frame counts: $out/qemu-fixed.log, $out/qemu-float.log"
