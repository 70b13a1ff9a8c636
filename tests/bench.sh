#!/usr/bin/env bash
# bench.sh: ms per frame of rt-float and rt-fixed on the demo scene, measured side by side (make bench-demo).
# Each round renders every sample time once with each build, alternating, so both see the same
# machine load. Times are the tracer's own (--stats ms), without image encoding.
# Usage: tests/bench.sh [SIZE] [ROUNDS] [RENDER OPTIONS...]    (defaults 320x240, 3, none:
# adaptive mode), e.g. tests/bench.sh 640x480 3 --mode full
set -eu
cd "$(dirname "$0")/.."
size=${1:-320x240}
rounds=${2:-3}
shift 2 || shift $#
extra=("$@")
# SCENE and TIMES (seconds) choose what is measured: by default the demo scene at six times.
scene=${SCENE:-scenes/demo.scene}
times=${TIMES:-0 4 8 12 16 20}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
declare -A sum worst
for real in float fixed; do sum[$real]=0; worst[$real]=0; done
n=0
echo "bench: $scene at $size${extra[*]:+ (${extra[*]})}, sample times: $times s, $rounds rounds; $(nproc) cores, $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1)"
for r in $(seq "$rounds"); do
  for t in $times; do
    for real in float fixed; do
      ms=$(build/rt-$real render --threads 1 --scene "$scene" --size "$size" --time "$t" ${extra[@]+"${extra[@]}"} --stats -o "$out/f.ppm" 2>/dev/null | sed -n 's/^ms=//p')
      sum[$real]=$(awk -v a="${sum[$real]}" -v b="$ms" 'BEGIN { print a + b }')
      worst[$real]=$(awk -v a="${worst[$real]}" -v b="$ms" 'BEGIN { print (b > a ? b : a) }')
    done
    n=$((n + 1))
  done
  printf 'bench: round %d/%d done\n' "$r" "$rounds" >&2
done
printf '%-6s %10s %10s %8s\n' build mean_ms worst_ms fps
for real in float fixed; do
  awk -v s="${sum[$real]}" -v n="$n" -v w="${worst[$real]}" -v r="$real" \
    'BEGIN { m = s / n; printf "%-6s %10.2f %10.2f %8.1f\n", r, m, w, 1000 / m }'
done
awk -v a="${sum[fixed]}" -v b="${sum[float]}" 'BEGIN { printf "fixed/float time ratio: %.2f\n", a / b }'
