#!/usr/bin/env bash
# run-intro.sh: what `make run` does: plays the intro in a window when there is a display; without one, renders it headless into a folder and prints frames per second.
#
# Usage: src/tools/run-intro.sh [fixed|float]   (make run REAL=fixed; default float)
# Expects make all. Headless, the frames go to build/out/intro/intro-NNNN.png (640x480, every
# frame of the intro at its 25 fps), rendered on every core, and one still per part of the intro
# is compared between the fixed and the float build.
set -euo pipefail
cd "$(dirname "$0")/../.."

real=${1:-float}
case "$real" in fixed|float) ;; *) echo "run: error: REAL must be fixed or float, not '$real'" >&2; exit 2 ;; esac
B=build
size=640x480

if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  echo "run: playing the intro with build/rt-$real play ($size, every core): Esc or Q quits, Space pauses, F full screen, S traced points, Left/Right seek, G grid"
  if "$B/rt-$real" play --size "$size"; then
    exit 0
  fi
  echo "run: the window could not be opened; rendering headless instead"
else
  echo "run: no display (DISPLAY is not set), so no window: rendering the intro headless into $B/out/intro/ instead"
fi

out=$B/out/intro
mkdir -p "$out"
rm -f "$out"/intro-*.png
start=$(date +%s%N)
"$B/rt-$real" render --frames all --size "$size" --progress -o "$out/intro-%04d.png"
ns=$(($(date +%s%N) - start))
n=$(ls "$out"/intro-*.png | wc -l)
awk -v n="$n" -v ns="$ns" -v r="$real" -v s="$size" -v c="$(nproc)" 'BEGIN {
  printf "run: %d frames of the intro at %s in %.1f s: %.1f frames per second (rt-%s, %d cores, PNG files included)\n", n, s, ns / 1e9, n / (ns / 1e9), r, c }'

# One still per part of the intro, fixed against float: what fixed point costs in accuracy.
for t in 8 17 25 35 44; do
  f=$((t * 25))
  "$B/rt-fixed" render --size "$size" --frame "$f" -o "$B/out/intro-$t-fixed.png" 2>/dev/null
  "$B/rt-float" render --size "$size" --frame "$f" -o "$B/out/intro-$t-float.png" 2>/dev/null
  printf 'run: intro t=%2ss, fixed vs float: %s\n' "$t" "$("$B/rt-cmp" "$B/out/intro-$t-fixed.png" "$B/out/intro-$t-float.png")"
done
echo "run: frames in $out/; fixed and float stills in $B/out/intro-T-fixed.png and intro-T-float.png"
