#!/usr/bin/env bash
# bench_effects.sh: effects on demand against every effect forced on, per example scene, side by
# side (make bench-effects). Usage: tests/bench_effects.sh [ROUNDS] [SIZE]
# For each scene: frames at 0%, 25%, 50%, 75% and 100% of its timeline, each rendered with
# --effects auto and --effects all alternately for ROUNDS rounds (best of the rounds counts, so
# noise from other work on the machine weighs less); both builds. "tests" counts the object
# intersection tests made by shadow rays over the 5 frames.
set -u
cd "$(dirname "$0")/.."
ROUNDS=${1:-3}
SIZE=${2:-320x240}
B=build
T=$B/bench
mkdir -p "$T"
echo "effects on demand vs all effects forced on: $SIZE, $ROUNDS rounds, best ms per frame summed over 5 frames"
printf '%-10s %-6s %-44s %10s %10s %7s %12s %12s\n' scene real "effects (derived)" "auto ms" "all ms" "saved" "tests auto" "tests all"
for scene in scenes/*.scene; do
  name=$(basename "${scene%.scene}")
  dur=$(awk '$1 == "duration" { print $2 }' "$scene")
  dur_ms=$(awk -v d="${dur:-0}" 'BEGIN { printf "%d", d * 1000 }')
  for real in float fixed; do
    sum_auto=0 sum_all=0 sh_auto=0 sh_all=0 fx=""
    for q in 0 1 2 3 4; do
      ms=$((dur_ms * q / 4))
      t=$((ms / 1000)).$(printf '%03d' $((ms % 1000)))
      best_auto="" best_all=""
      for r in $(seq "$ROUNDS"); do
        for e in auto all; do
          out=$($B/rt-$real render --threads 1 --scene "$scene" --time "$t" --size "$SIZE" --effects $e --stats -o "$T/eff.ppm" 2>/dev/null)
          m=$(sed -n 's/^ms=//p' <<<"$out")
          if [ $e = auto ]; then
            best_auto=$(awk -v a="$best_auto" -v b="$m" 'BEGIN { print (a == "" || b < a) ? b : a }')
            [ "$r" = 1 ] && { sh_auto=$((sh_auto + $(sed -n 's/^shadow_tests=//p' <<<"$out"))); [ $q = 2 ] && fx=$(sed -n 's/^effects=//p' <<<"$out"); }
          else
            best_all=$(awk -v a="$best_all" -v b="$m" 'BEGIN { print (a == "" || b < a) ? b : a }')
            [ "$r" = 1 ] && sh_all=$((sh_all + $(sed -n 's/^shadow_tests=//p' <<<"$out")))
          fi
        done
      done
      sum_auto=$(awk -v a="$sum_auto" -v b="$best_auto" 'BEGIN { print a + b }')
      sum_all=$(awk -v a="$sum_all" -v b="$best_all" 'BEGIN { print a + b }')
    done
    awk -v n="$name" -v r="$real" -v fx="$fx" -v a="$sum_auto" -v b="$sum_all" -v sa="$sh_auto" -v sb="$sh_all" \
      'BEGIN { printf "%-10s %-6s %-44s %10.2f %10.2f %6.1f%% %12d %12d\n", n, r, fx, a, b, (b - a) * 100 / b, sa, sb }'
  done
done
