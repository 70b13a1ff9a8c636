#!/usr/bin/env bash
# bench_intro.sh: desktop frames per second of the intro, both builds, one thread and every core, measured side by side (make bench).
#
# Usage: tests/bench_intro.sh [SIZE] [ROUNDS] [STEP_S]   (defaults 640x480, 1, 2: the intro every
# 2 s, 25 frames). Each sample frame is rendered by every (build, threads) pair in turn before
# the next frame, so all see the same machine load. Times are the tracer's own (--stats ms:
# rendering, without writing the file), per frame; mean and worst over the frames and rounds.
set -eu
cd "$(dirname "$0")/.."
size=${1:-640x480}
rounds=${2:-1}
step=${3:-2}
cores=$(nproc)
threads="1"
[ "$cores" -gt 1 ] && threads="1 $cores"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
declare -A sum worst
configs=()
for real in float fixed; do
  for th in $threads; do
    configs+=("$real/$th")
    sum[$real/$th]=0
    worst[$real/$th]=0
  done
done
n=0
times=$(seq 0 "$step" 48)
nt=$(wc -w <<<"$times")
echo "bench: the intro at $size, every $step s ($nt frames), $rounds round(s); builds float and fixed on 1 and $cores threads; $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1), $cores cores"
for r in $(seq "$rounds"); do
  k=0
  for t in $times; do
    for c in "${configs[@]}"; do
      real=${c%/*}
      th=${c#*/}
      ms=$(build/rt-$real render --time "$t" --size "$size" --threads "$th" --stats -o "$out/f.ppm" 2>/dev/null | sed -n 's/^ms=//p')
      [ -n "$ms" ] || { echo "bench: error: rt-$real render --time $t failed" >&2; exit 1; }
      sum[$c]=$(awk -v a="${sum[$c]}" -v b="$ms" 'BEGIN { print a + b }')
      worst[$c]=$(awk -v a="${worst[$c]}" -v b="$ms" 'BEGIN { print (b > a ? b : a) }')
    done
    n=$((n + 1))
    k=$((k + 1))
    printf '\rbench: round %d/%d, frame %d/%d ' "$r" "$rounds" "$k" "$nt" >&2
  done
done
echo >&2
echo
echo "| build | threads | mean ms/frame | worst ms/frame | mean fps | worst-frame fps |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
for c in "${configs[@]}"; do
  awk -v s="${sum[$c]}" -v n="$n" -v w="${worst[$c]}" -v r="${c%/*}" -v th="${c#*/}" \
    'BEGIN { m = s / n; printf "| %s | %d | %.2f | %.2f | %.1f | %.1f |\n", r, th, m, w, 1000 / m, 1000 / w }'
done
echo
for th in $threads; do
  awk -v a="${sum[fixed/$th]}" -v b="${sum[float/$th]}" -v th="$th" \
    'BEGIN { printf "fixed/float time, %d thread(s): %.2f\n", th, a / b }'
done
if [ "$cores" -gt 1 ]; then
  for real in float fixed; do
    awk -v a="${sum[$real/1]}" -v b="${sum[$real/$cores]}" -v r="$real" -v c="$cores" \
      'BEGIN { printf "%s: %d threads are %.2fx faster than 1\n", r, c, a / b }'
  done
fi
