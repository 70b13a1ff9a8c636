#!/usr/bin/env bash
# bench_modes.sh: what each mode (full, adaptive, probe) costs: exact instruction counts on the desktop (callgrind) and on the ARM926 (QEMU icount), and the desktop's tracing time (make bench-modes).
# Instruction counts are exact and repeatable (the tracing column exactly; the whole run's start-up
# varies by a few hundred instructions): they answer 1% questions that wall-clock times on a
# shared machine cannot. On the board they are the time (the ARM926 runs about one instruction a
# cycle); on an x86-64 core they are not, so the desktop's tracing time is measured too (best of
# RUNS runs). For each build it runs `render --frames RANGE --step STEP --threads 1 --checksum
# --mode M` under callgrind and prints the whole run's instructions and the tracing's own
# (frame_render and what it calls: the frames' pixels, without start-up, scene evaluation and the
# checksum), then the tracing time, then the same frames on the board (platform/arm/qemu.sh bench
# fixed, the fixed image, instructions per frame). Ratios are full / mode, taken in this one run.
# Usage: tests/bench_modes.sh [FIRST LAST STEP]   (default 0 1200 100: issue 18's 13 frames)
#        BOARD=0 skips the board; MODES="full probe" chooses the modes; RUNS=N the timed runs
#        per build and mode (default 5, the best counts).
set -eu
cd "$(dirname "$0")/.."
first=${1:-0} last=${2:-1200} step=${3:-100}
for v in "$first" "$last" "$step"; do
  case $v in '' | *[!0-9]*)
    echo "bench_modes.sh: FIRST LAST STEP must be frame numbers, e.g. 0 1200 100 (got '$v')" >&2
    exit 2
    ;;
  esac
done
modes=${MODES:-full adaptive probe}
for m in $modes; do
  case $m in full | adaptive | probe) ;; *)
    echo "bench_modes.sh: MODES: '$m' is not a mode (full, adaptive or probe)" >&2
    exit 2
    ;;
  esac
done
runs=${RUNS:-5}
case $runs in '' | *[!0-9]* | 0)
  echo "bench_modes.sh: RUNS must be a whole number of runs, 1 or more (got '$runs')" >&2
  exit 2
  ;;
esac
command -v valgrind >/dev/null || {
  echo "bench_modes.sh: valgrind is missing (./setup.sh --test installs it)" >&2
  exit 2
}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# callgrind's total and frame_render's inclusive count, from one profile
counts() {
  local total tracing
  total=$(callgrind_annotate "$1" 2>/dev/null | sed -n 's/^ *\([0-9,]*\) .*PROGRAM TOTALS.*/\1/p' | tr -d ,)
  tracing=$(callgrind_annotate --inclusive=yes "$1" 2>/dev/null |
              sed -n 's/^ *\([0-9,]*\) .*:frame_render \[.*/\1/p' | head -1 | tr -d ,)
  echo "${total:-0} ${tracing:-0}"
}

echo "bench-modes: intro frames $first..$last step $step, 320x240, default settings, one thread"
printf '%-22s %-9s %15s %9s %15s %9s\n' where mode instructions x_full tracing x_full
for real in fixed float; do
  declare -A tot=() trc=()
  for m in $modes; do
    echo "bench-modes: rt-$real --mode $m under callgrind..." >&2
    valgrind --tool=callgrind --callgrind-out-file="$out/cg.$real.$m" "build/rt-$real" render \
      --frames "$first-$last" --step "$step" --threads 1 --checksum --mode "$m" >/dev/null 2>"$out/log" || {
      echo "bench_modes.sh: rt-$real render --mode $m failed under callgrind:" >&2
      grep -v '^==' "$out/log" | tail -5 >&2
      exit 1
    }
    read -r tot[$m] trc[$m] <<<"$(counts "$out/cg.$real.$m")"
    if [ "${tot[$m]}" = 0 ] || [ "${trc[$m]}" = 0 ]; then
      echo "bench_modes.sh: no instruction count in callgrind's profile of rt-$real --mode $m" >&2
      exit 1
    fi
  done
  for m in $modes; do
    awk -v w="x86-64 rt-$real" -v m="$m" -v t="${tot[$m]}" -v r="${trc[$m]}" \
      -v ft="${tot[full]:-0}" -v fr="${trc[full]:-0}" 'BEGIN {
        xt = ft > 0 ? sprintf("%.3f", ft / t) : "-"; xr = fr > 0 ? sprintf("%.3f", fr / r) : "-"
        printf "%-22s %-9s %15.0f %9s %15.0f %9s\n", w, m, t, xt, r, xr }'
  done
  unset tot trc
done
# Tracing time on this machine: render's own ms= (--stats: frame_render's wall-clock time summed
# over the frames, the scope of the tracing column above), one thread, the best of RUNS runs per
# build and mode (the least disturbed by other work on a shared machine). Instruction counts do
# not give time on an out-of-order core: the points the subsampled modes shade are the branchy,
# incoherent ones (edges, secondary rays), so they run at fewer instructions per cycle than full
# mode's (docs/probe.md), and the time ratio is below the instruction ratio.
printf '%-22s %-9s %15s %9s\n' where mode tracing_ms x_full
for real in fixed float; do
  declare -A ms=()
  for m in $modes; do
    echo "bench-modes: rt-$real --mode $m, tracing time, best of $runs runs..." >&2
    best=""
    for _ in $(seq "$runs"); do
      t=$("build/rt-$real" render --frames "$first-$last" --step "$step" --threads 1 --checksum \
            --stats --mode "$m" 2>/dev/null | tr ' ' '\n' | sed -n 's/^ms=//p')
      [ -n "$t" ] || {
        echo "bench_modes.sh: rt-$real render --mode $m printed no ms= figure" >&2
        exit 1
      }
      best=$(awk -v a="$t" -v b="$best" 'BEGIN { print (b == "" || a + 0 < b + 0) ? a : b }')
    done
    ms[$m]=$best
  done
  for m in $modes; do
    awk -v w="x86-64 rt-$real" -v m="$m" -v t="${ms[$m]}" -v f="${ms[full]:-0}" 'BEGIN {
        x = f > 0 ? sprintf("%.3f", f / t) : "-"
        printf "%-22s %-9s %15.1f %9s\n", w, m, t, x }'
  done
  unset ms
done
if [ "${BOARD:-1}" != 0 ]; then
  declare -A mean=() worst=()
  for m in $modes; do
    echo "bench-modes: the ARM926 board, --mode $m..." >&2
    platform/arm/qemu.sh bench fixed --mode "$m" "$first" "$last" "$step" >"$out/board.$m" 2>&1 || {
      echo "bench_modes.sh: the board run for --mode $m failed:" >&2
      tail -5 "$out/board.$m" >&2
      exit 1
    }
    mean[$m]=$(sed -n 's/^frames=[0-9]* mean=\([0-9]*\).*/\1/p' "$out/board.$m")
    worst[$m]=$(sed -n 's/^worst=\([0-9]*\).*/\1/p' "$out/board.$m")
    if [ -z "${mean[$m]}" ] || [ -z "${worst[$m]}" ]; then
      echo "bench_modes.sh: no instruction count in the board's output for --mode $m" >&2
      exit 1
    fi
  done
  printf '%-22s %-9s %15s %9s %15s %9s\n' where mode mean x_full worst x_full
  for m in $modes; do
    awk -v m="$m" -v t="${mean[$m]}" -v w="${worst[$m]}" -v ft="${mean[full]:-0}" \
      -v fw="${worst[full]:-0}" 'BEGIN {
        xt = ft > 0 ? sprintf("%.3f", ft / t) : "-"; xw = fw > 0 ? sprintf("%.3f", fw / w) : "-"
        printf "%-22s %-9s %15.0f %9s %15.0f %9s\n", "ARM926 fixed image", m, t, xt, w, xw }'
  done
fi
echo "x86-64: instructions of the whole run and of the tracing alone (frame_render, inclusive), all frames;"
echo "tracing_ms: the tracing's wall-clock time on this machine, one thread, best of $runs runs (RUNS=N);"
echo "ARM926: instructions a frame (QEMU icount), mean and worst frame; x_full: full / this"
