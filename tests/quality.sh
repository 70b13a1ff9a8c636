#!/usr/bin/env bash
# quality.sh: the subsampled modes against full mode on every example and hard scene (make quality).
# Usage: tests/quality.sh [--short] [--doc FILE] [--builds "fixed float"]
# Every scene of scenes/ at three moments, (2k+1)/6 of its duration, and every scene of
# tests/hard/ that renders, at 0 s, all at 320x240: adaptive and probe mode (default settings)
# are compared by rt-cmp with `--mode full --min-contrib 0` of the same build. Targets, in
# each build:
#   every frame >= 40 dB in adaptive and in probe mode, and the mean over the frames >= 45 dB;
#   probe mode never more than 1 dB below adaptive mode on any frame.
# Where full mode itself aliases (detail finer than a pixel), a frame under 40 dB passes when it
# is at least as close as full mode to the 4x4-supersampled reference (full mode at 1280x960,
# `rt-cmp --box 4`): a sampled mode need not copy full mode's aliasing.
# Prints a table and the summary; --doc FILE writes them as Markdown too (docs/quality.md).
# --short (make test): the middle moment of each example scene only, and the scenes of
# tests/quality-known.txt reported as KNOWN instead of failing. Exits 1 below a target.
set -u
cd "$(dirname "$0")/.."
B=build
T=$B/test/quality
mkdir -p "$T"
short=0 doc="" builds="fixed float"
while [ $# -gt 0 ]; do
  case $1 in
    --short) short=1 ;;
    --doc) doc=$2; shift ;;
    --builds) builds=$2; shift ;;
    *) echo "usage: tests/quality.sh [--short] [--doc FILE] [--builds \"fixed float\"]" >&2; exit 2 ;;
  esac
  shift
done
SIZE=320x240

cases=() # scene:time
for s in scenes/*.scene; do
  d=$(sed -n 's/^duration[[:space:]]\+\([0-9.]*\).*/\1/p' "$s")
  for k in 0 1 2; do
    [ $short = 1 ] && [ $k != 1 ] && continue
    cases+=("$s:$(awk -v d="${d:-0}" -v k=$k 'BEGIN { printf "%.2f", d * (2 * k + 1) / 6 }')")
  done
done
for s in tests/hard/*.scene; do cases+=("$s:0"); done

psnr_of() { sed -n 's/.*psnr_db=\([^ ]*\).*/\1/p' <<<"$1"; }
val() { sed -n "s/.*$2=\([^ ]*\).*/\1/p" <<<"$1"; }
num() { [ "$1" = inf ] && echo 99 || echo "$1"; } # identical frames count as 99 dB in means

# scenes known to miss the targets: reported, not failed, by --short (make test)
known=$(sed -n 's/^\([a-z0-9-][a-z0-9-]*\)[[:space:]].*/\1/p' tests/quality-known.txt)
status=0
rows=() fails=()
declare -A sum cnt worst worstat
for real in $builds; do
  for c in "${cases[@]}"; do
    scene=${c%:*} t=${c##*:}
    name=$(basename "${scene%.scene}")
    base="$T/$name-$t-$real"
    if ! $B/rt-$real render --scene "$scene" --time "$t" --size $SIZE --mode full --min-contrib 0 \
      -o "$base-full.ppm" 2>/dev/null; then
      continue # a scene that does not render at this size (none today) is left out
    fi
    line="| $name | $t | $real |"
    declare -A p=()
    bad=""
    for mode in adaptive probe; do
      $B/rt-$real render --scene "$scene" --time "$t" --size $SIZE --mode $mode -o "$base-$mode.ppm" 2>/dev/null
      out=$($B/rt-cmp "$base-full.ppm" "$base-$mode.ppm")
      p[$mode]=$(psnr_of "$out")
      line="$line ${p[$mode]} / $(val "$out" max_abs) / $(val "$out" over8) |"
    done
    # aliasing: the frames under 40 dB against the supersampled reference
    box="" alias_ok=""
    if awk -v a="$(num "${p[adaptive]}")" -v b="$(num "${p[probe]}")" 'BEGIN { exit !(a < 40 || b < 40) }'; then
      w=${SIZE%x*} h=${SIZE#*x}
      $B/rt-$real render --scene "$scene" --time "$t" --size $((4 * w))x$((4 * h)) --mode full \
        --min-contrib 0 -o "$base-box.ppm" 2>/dev/null
      pf=$(psnr_of "$($B/rt-cmp "$base-box.ppm" "$base-full.ppm" --box 4)")
      box="full $pf"
      alias_ok=1
      for mode in adaptive probe; do
        if awk -v a="$(num "${p[$mode]}")" 'BEGIN { exit !(a < 40) }'; then
          pm=$(psnr_of "$($B/rt-cmp "$base-box.ppm" "$base-$mode.ppm" --box 4)")
          box="$box, $mode $pm"
          awk -v m="$pm" -v f="$pf" 'BEGIN { exit !(m >= f) }' || { alias_ok=""; bad="$bad $mode ${p[$mode]} dB;"; }
        fi
      done
    fi
    line="$line ${box:--} |"
    for mode in adaptive probe; do
      v=$(num "${p[$mode]}")
      k="$real-$mode"
      sum[$k]=$(awk -v s="${sum[$k]:-0}" -v v="$v" 'BEGIN { print s + v }')
      cnt[$k]=$((${cnt[$k]:-0} + 1))
      if [ -z "${worst[$k]:-}" ] || awk -v v="$v" -v w="${worst[$k]}" 'BEGIN { exit !(v < w) }'; then
        worst[$k]=$v worstat[$k]="$name $t s"
      fi
    done
    awk -v a="$(num "${p[adaptive]}")" -v b="$(num "${p[probe]}")" 'BEGIN { exit !(b >= a - 1) }' ||
      bad="$bad probe ${p[probe]} < adaptive ${p[adaptive]} - 1;"
    if [ -n "$bad" ] && [ $short = 1 ] && grep -qx "$name" <<<"$known"; then
      line="$line known:$bad |"
      echo "KNOWN $name $t s $real:$bad (tests/quality-known.txt)"
    elif [ -n "$bad" ]; then
      line="$line **FAIL**:$bad |"
      fails+=("$name $t s $real:$bad")
      status=1
    else
      grep -qx "$name" <<<"$known" && echo "NOTE $name $t s $real meets the targets: take it out of tests/quality-known.txt"
      line="$line ok${alias_ok:+ (aliasing)} |"
    fi
    rows+=("$line")
    echo "$line"
  done
done

summary=()
for real in $builds; do
  for mode in adaptive probe; do
    k="$real-$mode"
    [ -n "${cnt[$k]:-}" ] || continue
    mean=$(awk -v s="${sum[$k]}" -v n="${cnt[$k]}" 'BEGIN { printf "%.2f", s / n }')
    verdict=ok
    awk -v m="$mean" 'BEGIN { exit !(m >= 45) }' || { verdict="**FAIL** (mean < 45 dB)"; status=1; fails+=("$k mean $mean dB"); }
    summary+=("| $real | $mode | ${cnt[$k]} | $mean | ${worst[$k]} (${worstat[$k]}) | $verdict |")
  done
done
echo
printf '%s\n' "| build | mode | frames | mean dB | worst frame dB | target |" "${summary[@]}"
for f in ${fails[@]+"${fails[@]}"}; do echo "FAIL $f"; done

if [ -n "$doc" ]; then
  {
    echo "# Quality of the subsampled modes on every scene"
    echo
    echo "Written by \`make quality\` (\`tests/quality.sh --doc docs/quality.md\`) from one run; do not"
    echo "edit by hand. Every scene of \`scenes/\` at three moments, (2k+1)/6 of its duration, and every"
    echo "scene of \`tests/hard/\` at 0 s, at $SIZE, in both builds: adaptive and probe mode (default"
    echo "settings) against \`--mode full --min-contrib 0\` of the same build (\`rt-cmp\`: PSNR in dB,"
    echo "largest channel error, pixels with a channel off by more than 8; identical frames count as"
    echo "99 dB in the means)."
    echo
    echo "Targets, in each build: every frame at least 40 dB in adaptive and in probe mode, the mean at"
    echo "least 45 dB, and probe mode never more than 1 dB below adaptive mode. Where full mode itself"
    echo "aliases (detail finer than a pixel), a frame under 40 dB passes when it is at least as close"
    echo "as full mode to the 4x4-supersampled reference (\`rt-cmp --box 4\`, last but one column)."
    echo "\`make test\` runs the same checks on the middle moment of each example scene and on the hard"
    echo "scenes (\`tests/quality.sh --short\`)."
    echo "There the scenes of \`tests/quality-known.txt\`, which still miss the targets, are reported"
    echo "as known misses instead of failing; \`make quality\` fails on them."
    echo
    echo "| build | mode | frames | mean dB | worst frame dB | target |"
    echo "| --- | --- | --- | --- | --- | --- |"
    printf '%s\n' "${summary[@]}"
    echo
    echo "| scene | time s | build | adaptive dB / max / over8 | probe dB / max / over8 | against 4x4 reference (dB) | targets |"
    echo "| --- | --- | --- | --- | --- | --- | --- |"
    printf '%s\n' "${rows[@]}"
  } >"$doc"
fi
exit $status
