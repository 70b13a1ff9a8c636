#!/usr/bin/env bash
# bench_intro.sh: desktop frames per second of the intro at one or more sizes, both builds, one thread and every core, measured side by side (part of make bench).
#
# Usage: tests/bench_intro.sh [SIZES] [ROUNDS] [STEP_S]   (defaults 640x480, 1, 2: the intro
# every 2 s, 25 frames). SIZES is one size or several separated by commas, e.g. 320x240,640x480.
# Each sample frame is rendered by every (size, build, threads) configuration in turn before the
# next frame, so all see the same machine load. Times are the tracer's own (--stats ms:
# rendering, without writing the file), per frame; mean and worst over the frames and rounds.
# Progress goes to standard error, the table to standard output. With BENCH_ROWS=FILE, one
# tab-separated line per configuration is also appended to FILE for tests/bench_all.sh:
#   desktop <build> <size> <threads> <mean ms> <worst ms> ms
set -eu
cd "$(dirname "$0")/.."
sizes=${1:-640x480}
rounds=${2:-1}
step=${3:-2}
cores=$(nproc)
threads="1"
[ "$cores" -gt 1 ] && threads="1 $cores"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
declare -A sum worst
configs=()
for size in ${sizes//,/ }; do
  [[ $size =~ ^[0-9]+x[0-9]+$ ]] || { echo "bench: error: '$size' is not a size WxH" >&2; exit 2; }
  for real in float fixed; do
    for th in $threads; do
      configs+=("$size/$real/$th")
      sum[$size/$real/$th]=0
      worst[$size/$real/$th]=0
    done
  done
done
n=0
times=$(seq 0 "$step" 48)
nt=$(wc -w <<<"$times")
echo "bench: the intro at ${sizes//,/ and }, every $step s ($nt frames), $rounds round(s); builds float and fixed on 1 and $cores threads; $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1), $cores cores"
for r in $(seq "$rounds"); do
  k=0
  for t in $times; do
    for c in "${configs[@]}"; do
      IFS=/ read -r size real th <<<"$c"
      ms=$(build/rt-$real render --time "$t" --size "$size" --threads "$th" --stats -o "$out/f.ppm" 2>/dev/null | sed -n 's/^ms=//p')
      [ -n "$ms" ] || { echo "bench: error: rt-$real render --time $t --size $size failed" >&2; exit 1; }
      sum[$c]=$(awk -v a="${sum[$c]}" -v b="$ms" 'BEGIN { print a + b }')
      worst[$c]=$(awk -v a="${worst[$c]}" -v b="$ms" 'BEGIN { print (b > a ? b : a) }')
    done
    n=$((n + 1))
    k=$((k + 1))
    printf '\rbench: desktop, round %d/%d, frame %d/%d (t = %s s) ' "$r" "$rounds" "$k" "$nt" "$t" >&2
  done
done
echo >&2
echo
echo "| size | build | threads | mean ms/frame | worst ms/frame | mean fps | worst-frame fps |"
echo "| --- | --- | ---: | ---: | ---: | ---: | ---: |"
for c in "${configs[@]}"; do
  IFS=/ read -r size real th <<<"$c"
  awk -v s="${sum[$c]}" -v n="$n" -v w="${worst[$c]}" -v size="$size" -v r="$real" -v th="$th" \
    'BEGIN { m = s / n; printf "| %s | %s | %d | %.2f | %.2f | %.1f | %.1f |\n", size, r, th, m, w, 1000 / m, 1000 / w }'
  if [ -n "${BENCH_ROWS:-}" ]; then
    awk -v s="${sum[$c]}" -v n="$n" -v w="${worst[$c]}" -v size="$size" -v r="$real" -v th="$th" \
      'BEGIN { printf "desktop\t%s\t%s\t%d\t%.4f\t%.4f\tms\n", r, size, th, s / n, w }' >>"$BENCH_ROWS"
  fi
done
echo
for size in ${sizes//,/ }; do
  for th in $threads; do
    awk -v a="${sum[$size/fixed/$th]}" -v b="${sum[$size/float/$th]}" -v th="$th" -v size="$size" \
      'BEGIN { printf "%s, %d thread%s: fixed takes %.2fx float'"'"'s time\n", size, th, (th > 1 ? "s" : ""), a / b }'
  done
  if [ "$cores" -gt 1 ]; then
    for real in float fixed; do
      awk -v a="${sum[$size/$real/1]}" -v b="${sum[$size/$real/$cores]}" -v r="$real" -v c="$cores" -v size="$size" \
        'BEGIN { printf "%s, %s: %d threads give a %.2fx speed-up over 1\n", size, r, c, a / b }'
    done
  fi
done
