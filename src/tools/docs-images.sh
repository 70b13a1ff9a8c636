#!/usr/bin/env bash
# docs-images.sh: renders the pictures of README.md and docs/ with the current build (make docs-images), or checks that those of the fixed-point build are current (--check, in make test).
#
# Usage: src/tools/docs-images.sh [--check]   (expects make all)
# Writes docs/images/: intro-fixed.png (35 s, 640x480, rt-fixed; README), intro-diff.png (it
# against rt-float, rt-cmp --diff; usage.md), intro-08/17/25/35/44.png (one still per part,
# 320x240, rt-fixed; usage.md), intro-samples.png and probe-samples.png (35 s, 640x480, one
# thread, --show-samples in adaptive and probe mode; tracer.md, probe.md), m3-oled.png (frame
# 875 as the Cortex-M3's OLED shows it: rt-cmp --oled, byte for byte QEMU's screendump, which
# make test checks; README, m3.md). It prints the figures the captions quote. tradeoff.png is
# make tradeoff's. --check renders the fixed-point pictures (bit-identical on every machine)
# into a temporary folder and fails, naming them, where docs/images/ holds another picture;
# the float one (intro-diff.png) is left out, as a host's libm may round otherwise.
set -euo pipefail
cd "$(dirname "$0")/../.."

check=0
case "${1:-}" in
  --check) check=1 ;;
  "") ;;
  *) echo "docs-images: error: unknown argument '$1' (usage: src/tools/docs-images.sh [--check])" >&2; exit 2 ;;
esac
B=build
for p in rt-fixed rt-float rt-cmp; do
  [ -x "$B/$p" ] || { echo "docs-images: error: $B/$p is missing (run make first)" >&2; exit 2; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=docs/images
if [ "$check" = 1 ]; then out=$tmp/images; fi
mkdir -p "$out"

# name: render options (rt-fixed)
pictures=(
  "intro-fixed|--size 640x480 --time 35"
  "intro-08|--time 8"
  "intro-17|--time 17"
  "intro-25|--time 25"
  "intro-35|--time 35"
  "intro-44|--time 44"
  "intro-samples|--size 640x480 --time 35 --threads 1 --show-samples"
  "probe-samples|--size 640x480 --time 35 --threads 1 --show-samples --mode probe"
)
for entry in "${pictures[@]}"; do
  name=${entry%%|*}
  # shellcheck disable=SC2086 # the options are words
  "$B/rt-fixed" render ${entry#*|} -o "$out/$name.png" >/dev/null 2>&1 ||
    { echo "docs-images: error: rt-fixed render ${entry#*|} failed" >&2; exit 1; }
done
"$B/rt-fixed" render --size 128x64 --frame 875 -o "$tmp/m3.png" >/dev/null 2>&1
"$B/rt-cmp" --oled "$tmp/m3.png" "$out/m3-oled.png"

if [ "$check" = 1 ]; then
  stale=()
  for f in "$out"/*.png; do
    name=$(basename "$f")
    if [ ! -f "docs/images/$name" ]; then
      stale+=("$name (missing)")
    elif ! "$B/rt-cmp" "docs/images/$name" "$f" | grep -q ' differing=0 '; then
      stale+=("$name")
    fi
  done
  if [ ${#stale[@]} -gt 0 ]; then
    echo "docs-images: not the current build's pictures: ${stale[*]} (make docs-images renders them again)" >&2
    exit 1
  fi
  echo "docs-images: the $(ls "$out" | wc -l) fixed-point pictures in docs/images are the current build's"
  exit 0
fi

"$B/rt-float" render --size 640x480 --time 35 -o "$tmp/float.png" >/dev/null 2>&1
echo "docs-images: README's picture against rt-float (its caption quotes psnr_db and over8):"
"$B/rt-cmp" "$out/intro-fixed.png" "$tmp/float.png" --diff "$out/intro-diff.png"
echo "docs-images: the samples pictures at 35 s, 640x480 (tracer.md's and probe.md's captions):"
for m in adaptive probe; do
  # one render: the picture as PPM for the counts below, and its --stats (which count twice a
  # point traced twice, on an edge two squares share; the picture paints it once)
  stats=$("$B/rt-fixed" render --size 640x480 --time 35 --threads 1 --mode "$m" --show-samples \
    --stats -o "$tmp/$m.ppm" 2>/dev/null | grep -E '^(samples_traced|probes|local_points)=' | tr '\n' ' ')
  echo "  $m: pixels $(python3 - "$tmp/$m.ppm" <<'PY'
import sys
d = open(sys.argv[1], 'rb').read().split(b'\n', 3)[3]
px = [d[i:i + 3] for i in range(0, len(d), 3)]
print('white %d cyan %d magenta %d' % (px.count(b'\xff\xff\xff'), px.count(b'\x00\xff\xff'),
                                       px.count(b'\xff\x00\xff')))
PY
); stats $stats"
done
echo "docs-images: wrote $(ls "$out"/intro-*.png "$out"/probe-samples.png "$out"/m3-oled.png | wc -l) pictures in $out"
