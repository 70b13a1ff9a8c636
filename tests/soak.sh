#!/usr/bin/env bash
# soak.sh: renders every frame of the intro (or every STEP-th) twice with both builds, one process per pass: the same pictures both times, and peak memory that does not grow with the number of frames.
# Usage: tests/soak.sh [STEP] [SIZE]   (defaults: 1, i.e. all 1201 frames, and 320x240)
# Each pass is one `render --frames all --step STEP --checksum` (64-bit FNV-1a of each frame's
# RGB bytes); the two passes must print the same checksums. Peak memory (max RSS, from
# /usr/bin/time -v) of a full pass is compared with an 11-frame run of the same program, one
# frame from every 120 (so that it runs the code of every part of the intro, whose pages count
# too; the larger of two runs): a full pass may exceed it by at most 512 KiB, and the check fails
# when both passes do (single runs vary by up to ~500 KiB; a leak of 440-850 bytes a frame or
# more shows in both, depending on that noise). Exit status 1 when a check fails.
set -u
cd "$(dirname "$0")/.."
step=${1:-1}
size=${2:-320x240}
B=build
S=$B/soak
mkdir -p "$S"
status=0
# "<max RSS in KiB> <wall seconds>" of the command whose /usr/bin/time -v output is in $1
time_fields() {
  awk -F': ' '/Maximum resident set size/ { rss = $2 }
              /Elapsed \(wall clock\)/ { n = split($2, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i]; wall = s }
              END { print rss, wall }' "$1"
}
for real in float fixed; do
  prog=$B/rt-$real
  # the 11-frame reference twice, its larger peak kept (single runs vary by up to ~500 KiB)
  rss11=0
  for ref in 1 2; do
    /usr/bin/time -v "$prog" render --size "$size" --frames all --step 120 --checksum >"$S/$real-11.txt" 2>"$S/$real-11.time" ||
      { echo "soak rt-$real: 11-frame run failed"; status=1; continue 2; }
    read -r r wall11 < <(time_fields "$S/$real-11.time")
    [ "$r" -gt "$rss11" ] && rss11=$r
  done
  line="soak rt-$real $size:"
  for pass in 1 2; do
    if ! /usr/bin/time -v "$prog" render --size "$size" --frames all --step "$step" --checksum \
         >"$S/$real-pass$pass.txt" 2>"$S/$real-pass$pass.time"; then
      echo "soak rt-$real: pass $pass failed:"; tail -3 "$S/$real-pass$pass.time" | sed 's/^/    /'
      status=1
      continue 2
    fi
    read -r rss wall < <(time_fields "$S/$real-pass$pass.time")
    eval "rss$pass=$rss wall$pass=$wall"
  done
  frames=$(wc -l <"$S/$real-pass1.txt")
  line="$line $frames frames (every ${step}), pass 1 ${wall1} s, pass 2 ${wall2} s; max RSS ${rss11} KiB for 11 frames, ${rss1} / ${rss2} KiB for all"
  if ! cmp -s "$S/$real-pass1.txt" "$S/$real-pass2.txt"; then
    echo "$line: FAIL: the two passes differ ($(diff "$S/$real-pass1.txt" "$S/$real-pass2.txt" | grep -c '^<') frames)"
    status=1
  elif [ "$frames" -lt 2 ] || ! head -10 "$S/$real-pass1.txt" | grep -q ' fnv64=[0-9a-f]\{16\}$'; then
    echo "$line: FAIL: no checksums"
    status=1
  elif [ "$rss1" -gt $((rss11 + 512)) ] && [ "$rss2" -gt $((rss11 + 512)) ]; then
    echo "$line: FAIL: peak memory grows with the number of frames"
    status=1
  else
    echo "$line: identical passes, no growth"
  fi
done
exit $status
