#!/usr/bin/env bash
# bench_subsample.sh: what adaptive subsampling and recursion control save on the demo scene (make bench-subsample).
# For each size and build it renders the same demo times in three ways, alternating so that all
# see the same machine load:
#   full       every pixel traced, every ray cast (--mode full --min-contrib 0): the reference
#   full+rc    every pixel traced, adaptive recursion control at its default (--mode full)
#   adaptive   the defaults: adaptive subsampling and recursion control
#   probe      --mode probe: adaptive subsampling whose new points are probed first (docs/probe.md)
# and prints points traced (shaded in full; probe mode's probes in a column of their own), rays by kind, ms per frame (the tracer's own --stats ms, without
# image encoding) and PSNR against the reference frame. Ratios are full / adaptive. Per size it
# also prints the bound build/rt-edges gives: the x_samples of tracing nothing but the grid's
# corners and the pixels on the edges the split criteria see.
# Usage: tests/bench_subsample.sh [ROUNDS] [SIZES...]   (defaults: 3 rounds, 320x240 640x480)
set -eu
cd "$(dirname "$0")/.."
rounds=${1:-3}
shift || true
sizes=${*:-320x240 640x480}
# SCENE and TIMES (seconds) choose what is measured: by default the demo scene at six times.
scene=${SCENE:-scenes/demo.scene}
times=${TIMES:-0 4 8 12 16 20}
modes="full full+rc adaptive probe"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

opts() {
  case $1 in
  full) echo "--mode full --min-contrib 0" ;;
  full+rc) echo "--mode full" ;;
  adaptive) echo "" ;;
  probe) echo "--mode probe" ;;
  esac
}

echo "bench-subsample: $scene, times $times s, $rounds timing rounds, one thread;" \
  "$(nproc) cores, $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1)"
printf '%-8s %-6s %-9s %9s %9s %9s %9s %9s %9s %9s %8s %8s %9s %9s\n' size build mode samples probes \
  shadow reflect refract ms_mean ms_worst x_samples x_time psnr_min psnr_mean
for size in $sizes; do
  declare -A ms=() worst=() st=() psum=() pmin=()
  for real in float fixed; do
    for m in $modes; do
      ms[$real,$m]=0 worst[$real,$m]=0 psum[$real,$m]=0 pmin[$real,$m]=999
      st[$real,$m]="0 0 0 0 0"
    done
  done
  for r in $(seq "$rounds"); do
    for t in $times; do
      for real in float fixed; do
        for m in $modes; do
          # shellcheck disable=SC2046
          s=$(build/rt-$real render --threads 1 --scene "$scene" --size "$size" --time "$t" $(opts $m) --stats \
                -o "$out/$real-$m-$t.ppm" 2>/dev/null)
          v=$(sed -n 's/^ms=//p' <<<"$s")
          ms[$real,$m]=$(awk -v a="${ms[$real,$m]}" -v b="$v" 'BEGIN { print a + b }')
          worst[$real,$m]=$(awk -v a="${worst[$real,$m]}" -v b="$v" 'BEGIN { print (b > a ? b : a) }')
          if [ "$r" = 1 ]; then
            set -- ${st[$real,$m]}
            st[$real,$m]="$(($1 + $(sed -n 's/^samples_traced=//p' <<<"$s"))) \
$(($2 + $(sed -n 's/^rays_shadow=//p' <<<"$s"))) \
$(($3 + $(sed -n 's/^rays_reflect=//p' <<<"$s"))) \
$(($4 + $(sed -n 's/^rays_refract=//p' <<<"$s"))) \
$(($5 + $(sed -n 's/^probes=//p' <<<"$s" | grep . || echo 0)))"
            if [ "$m" != full ]; then
              p=$(build/rt-cmp "$out/$real-$m-$t.ppm" "$out/$real-full-$t.ppm" |
                    sed -n 's/.*psnr_db=\([^ ]*\).*/\1/p')
              [ "$p" = inf ] && p=99
              psum[$real,$m]=$(awk -v a="${psum[$real,$m]}" -v b="$p" 'BEGIN { print a + b }')
              pmin[$real,$m]=$(awk -v a="${pmin[$real,$m]}" -v b="$p" 'BEGIN { print (b < a ? b : a) }')
            fi
          fi
        done
      done
    done
    printf 'bench-subsample: %s round %d/%d done\n' "$size" "$r" "$rounds" >&2
  done
  nt=$(wc -w <<<"$times")
  for real in float fixed; do
    set -- ${st[$real,full]}
    full_samples=$1
    for m in $modes; do
      set -- ${st[$real,$m]}
      awk -v size="$size" -v real="$real" -v m="$m" -v nt="$nt" -v n="$((nt * rounds))" \
        -v s="$1" -v sh="$2" -v rf="$3" -v rr="$4" -v pr="$5" -v ms="${ms[$real,$m]}" -v w="${worst[$real,$m]}" \
        -v fs="$full_samples" -v fms="${ms[$real,full]}" -v ps="${psum[$real,$m]}" -v pm="${pmin[$real,$m]}" \
        'BEGIN {
           if (m == "full") { pmin = "-"; pmean = "-" } else { pmin = sprintf("%.2f", pm); pmean = sprintf("%.2f", ps / nt) }
           printf "%-8s %-6s %-9s %9d %9d %9d %9d %9d %9.2f %9.2f %8.2f %8.2f %9s %9s\n",
             size, real, m, s / nt, pr / nt, sh / nt, rf / nt, rr / nt, ms / n, w, fs / s, fms / ms, pmin, pmean
         }'
    done
  done
  # What any refinement of these squares must trace at the least: the pixels on an edge the
  # split criteria see, plus the grid's corners (src/tools/edges.c).
  bsum=0 esum=0
  for t in $times; do
    b=$(build/rt-edges --scene "$scene" --size "$size" --time "$t")
    bsum=$(awk -v a="$bsum" -v b="$(sed -n 's/^bound_x_samples=//p' <<<"$b")" 'BEGIN { print a + b }')
    esum=$(awk -v a="$esum" -v b="$(sed -n 's/^edge_share=//p' <<<"$b")" 'BEGIN { print a + b }')
  done
  awk -v size="$size" -v b="$bsum" -v e="$esum" -v nt="$nt" 'BEGIN {
    printf "%-8s bound: %.1f%% of the pixels lie on an edge the criteria see; tracing only them and the corners: x_samples %.2f\n",
      size, 100 * e / nt, b / nt }'
  unset ms worst st psum pmin
done
echo "samples (shaded in full), probes, rays: per frame, mean over the times; x_samples, x_time: full / this; psnr: against full, dB"
echo "bound: build/rt-edges on the float frames traced in full, mean over the times"
