#!/usr/bin/env bash
# fuzz.sh: runs the scene fuzzer (tests/fuzz_scene.c, libFuzzer + ASan + UBSan) on both builds, after replaying every kept crash.
# Usage: tests/fuzz.sh SECONDS [--smoke]
#   SECONDS   fuzzing time per build (float, then fixed)
#   --smoke   start from the seeds alone in a fresh folder, with a fixed random seed (make test);
#             otherwise the corpus grows across runs in build/fuzz/corpus-<real> (make fuzz)
# Seeds: scenes/, tests/scenes/, tests/fuzz-regress/ and the cases of tests/bad_scenes.txt.
# A crash, a hang (an input running over 10 s), a leak or a sanitizer report ends the run with
# exit status 1 and leaves the input in build/fuzz/<real>-crash-* (or -timeout-, -leak-): fix
# the code, then keep the input in tests/fuzz-regress/ (README there).
set -u
cd "$(dirname "$0")/.."
secs=${1:?usage: tests/fuzz.sh SECONDS [--smoke]}
smoke=0
[ "${2:-}" = --smoke ] && smoke=1
F=build/fuzz
mkdir -p "$F"
seeds=$F/seeds
rm -rf "$seeds" && mkdir -p "$seeds"
cp scenes/*.scene tests/scenes/*.scene tests/fuzz-regress/*.scene "$seeds"/
awk -v dir="$seeds" '/^===/ { n++; f = sprintf("%s/bad%02d.scene", dir, n); printf "" > f; next }
                     n > 0 { print >> f }' tests/bad_scenes.txt
status=0
for real in float fixed; do
  prog=build/fuzz-$real/fuzz_scene
  # every kept crash first: each must now pass
  if ! "$prog" tests/fuzz-regress/*.scene >"$F/$real-regress.log" 2>&1; then
    echo "fuzz-$real: a kept input of tests/fuzz-regress/ fails again:"
    grep -E 'fuzz_scene:|ERROR|runtime error|Running:' "$F/$real-regress.log" | tail -5 | sed 's/^/    /'
    status=1
    continue
  fi
  if [ $smoke -eq 1 ]; then
    corpus=$F/smoke-$real && rm -rf "$corpus"
    opts=(-seed=1)
  else
    corpus=$F/corpus-$real
    opts=()
  fi
  mkdir -p "$corpus"
  "$prog" "${opts[@]}" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -max_len=16384 \
    -dict=tests/fuzz/scene.dict -print_final_stats=1 -artifact_prefix="$F/$real-" \
    "$corpus" "$seeds" >"$F/$real.log" 2>&1
  rc=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$F/$real.log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$F/$real.log")
  rss=$(sed -n 's/^stat::peak_rss_mb: *//p' "$F/$real.log")
  units=$(ls "$corpus" | wc -l)
  if [ $rc -eq 0 ] && ! grep -q 'ERROR: \|runtime error\|fuzz_scene: ' "$F/$real.log"; then
    echo "fuzz-$real: ${secs} s, ${execs:-?} executions (${rate:-?}/s), corpus $units inputs, peak RSS ${rss:-?} MB: no crash, hang, leak or sanitizer report"
  else
    status=1
    echo "fuzz-$real: FAILED after ${execs:-?} executions (exit $rc); input and log in $F/:"
    grep -E 'fuzz_scene: |ERROR|runtime error|SUMMARY|Test unit written' "$F/$real.log" | head -8 | sed 's/^/    /'
  fi
done
exit $status
