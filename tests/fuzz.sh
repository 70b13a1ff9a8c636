#!/usr/bin/env bash
# fuzz.sh: runs every libFuzzer target (ASan + UBSan) after replaying every kept crash: the scene parser, timeline and tracer on both builds, the command line, the image readers and the render settings.
# Usage: tests/fuzz.sh SECONDS [--smoke]
#   SECONDS   fuzzing time per target (scene: per build, float then fixed)
#   --smoke   start from the seeds alone in a fresh folder, with a fixed random seed (make test);
#             otherwise the corpus grows across runs in build/fuzz/corpus-<float|fixed|cli|image|knobs>,
#             and every scene of both scene corpora that render accepts then goes through
#             the differential oracle (tests/fuzz_oracle.sh: release vs event-counting bytes) (make fuzz)
# Targets: fuzz-float, fuzz-fixed (tests/fuzz_scene.c), fuzz-cli (tests/fuzz_cli.c: words of a
# command line through cli.c's option table), fuzz-image (tests/fuzz_image.c: img_load on PNG and
# PPM bytes), fuzz-knobs (tests/fuzz_knobs.c: knobs_parse and the number syntax against a
# reference). Seeds: scenes/, tests/scenes/, the cases of tests/bad_scenes.txt; tests/fuzz/cli,
# image, knobs; and tests/fuzz-regress/ (*.scene, *.cli, *.img, *.knobs by target).
# A crash, a hang (an input running over 10 s), a leak or a sanitizer report ends that target's
# run with exit status 1 and leaves the input in build/fuzz/<float|fixed|cli|...>-crash-* (or -timeout-,
# -leak-): fix the code, then keep the input in tests/fuzz-regress/ (README there).
# Each target prints one line: executions, their rate, coverage (libFuzzer's cov: edges), the
# corpus and the peak RSS.
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

# fuzz_target NAME PROGRAM REGRESS-EXTENSION SEED-DIR [LIBFUZZER OPTIONS...]
fuzz_target() {
  local name=$1 prog=$2 ext=$3 seed=$4
  shift 4
  local kept=(tests/fuzz-regress/*."$ext")
  # every kept crash first: each must now pass
  if [ -e "${kept[0]}" ] && ! "$prog" "${kept[@]}" >"$F/$name-regress.log" 2>&1; then
    echo "$name: a kept input of tests/fuzz-regress/ fails again:"
    grep -E 'fuzz_[a-z]*:|ERROR|runtime error|Running:' "$F/$name-regress.log" | tail -5 | sed 's/^/    /'
    status=1
    return
  fi
  local corpus opts=()
  if [ $smoke -eq 1 ]; then
    corpus=$F/smoke-${name#fuzz-} && rm -rf "$corpus"
    opts=(-seed=1)
  else
    corpus=$F/corpus-${name#fuzz-}
  fi
  mkdir -p "$corpus"
  [ -e "${kept[0]}" ] && cp "${kept[@]}" "$corpus"/
  "$prog" "${opts[@]}" "$@" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$F/${name#fuzz-}-" "$corpus" "$seed" >"$F/$name.log" 2>&1
  local rc=$?
  local execs rate rss cov units
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$F/$name.log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$F/$name.log")
  rss=$(sed -n 's/^stat::peak_rss_mb: *//p' "$F/$name.log")
  cov=$(grep -o 'cov: [0-9]*' "$F/$name.log" | tail -1 | sed 's/cov: //')
  units=$(ls "$corpus" | wc -l)
  if [ $rc -eq 0 ] && ! grep -q 'ERROR: \|runtime error\|^fuzz_[a-z]*: ' "$F/$name.log"; then
    echo "$name: ${secs} s, ${execs:-?} executions (${rate:-?}/s), coverage ${cov:-?} edges, corpus $units inputs, peak RSS ${rss:-?} MB: no crash, hang, leak or sanitizer report"
  else
    status=1
    echo "$name: FAILED after ${execs:-?} executions (exit $rc); input and log in $F/:"
    grep -E '^fuzz_[a-z]*: |ERROR|runtime error|SUMMARY|Test unit written' "$F/$name.log" | head -8 | sed 's/^/    /'
  fi
}

for real in float fixed; do
  fuzz_target fuzz-$real build/fuzz-$real/fuzz_scene scene "$seeds" -max_len=16384 -dict=tests/fuzz/scene.dict
done
# -close_fd_mask=1: --help and --version print the usage on standard output at every turn
fuzz_target fuzz-cli $F/fuzz_cli cli tests/fuzz/cli -max_len=2048 -dict=tests/fuzz/cli.dict -close_fd_mask=1
fuzz_target fuzz-image $F/fuzz_image img tests/fuzz/image -max_len=65536
fuzz_target fuzz-knobs $F/fuzz_knobs knobs tests/fuzz/knobs -max_len=256 -dict=tests/fuzz/knobs.dict

# make fuzz: the corpus's scenes through the release and the event-counting fixed builds
if [ $smoke -eq 0 ]; then
  tests/fuzz_oracle.sh "$F/corpus-fixed" "$F/corpus-float" || status=1
fi
exit $status
