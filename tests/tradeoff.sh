#!/usr/bin/env bash
# tradeoff.sh: accuracy against time on the intro, one knob at a time, float and fixed; table in docs/tradeoff.md, plot in docs/images/tradeoff.png (make tradeoff).
#
# Usage: tests/tradeoff.sh [-o FILE]   (default docs/tradeoff.md and docs/images/tradeoff.png;
#                                       with QUICK=1 build/tradeoff/tradeoff-quick.md and .png)
# Every configuration changes one render option from the intro's default (adaptive, --grid 8,
# --threshold 0.0625, the scene's depth 5, --min-contrib 0.01) and runs in rt-float and
# rt-fixed. Each sample frame (TIMES, seconds of the intro, at 320x240) is rendered by every
# configuration in turn, ROUNDS rounds, on one thread (--threads 1 --stats: the tracer's ms=).
# Error: rt-cmp against the reference (rt-float --mode full --min-contrib 0 --depth 8).
# Defaults: TIMES="4 14 25 35 44", ROUNDS=5: 20 configurations, about 15 s on the 2-core
# build machine. QUICK=1: two configurations on one frame, one round (make test's smoke run).
# Progress goes to standard error; the table is also printed.
set -euo pipefail
cd "$(dirname "$0")/.."

die() { printf 'tradeoff: error: %s\n' "$*" >&2; exit 2; }
SIZE=320x240
REF_OPTS="--mode full --min-contrib 0 --depth 8"
# name|options: the default first, then one knob at a time
CONFIGS=(
  "default|"
  "full|--mode full"
  "grid 4|--grid 4"
  "grid 16|--grid 16"
  "threshold 0.03|--threshold 0.03"
  "threshold 0.125|--threshold 0.125"
  "depth 1|--depth 1"
  "depth 2|--depth 2"
  "depth 3|--depth 3"
  "depth 4|--depth 4"
)
REALS=(float fixed fixed16)   # fixed16: rt-fixed16, unit vectors in Q16.16 (docs/numerics.md)
if [ "${QUICK:-0}" = 1 ]; then
  out=build/tradeoff/tradeoff-quick.md
  times=${TIMES:-14} rounds=${ROUNDS:-1}
  CONFIGS=("default|" "full|--mode full")
  runs=("float 0" "fixed 1")   # real, index into CONFIGS: two configurations
else
  out=docs/tradeoff.md
  times=${TIMES:-4 14 25 35 44} rounds=${ROUNDS:-5}
  runs=()
  for i in "${!CONFIGS[@]}"; do
    for real in "${REALS[@]}"; do runs+=("$real $i"); done
  done
fi
case $# in
  0) ;;
  2) [ "$1" = -o ] || die "unknown option '$1' (usage: tests/tradeoff.sh [-o FILE])"; out=$2 ;;
  *) die "usage: tests/tradeoff.sh [-o FILE]" ;;
esac
case $out in
  *.md) ;;
  *) die "the output file must end in .md (the plot goes next to it as .png), not '$out'" ;;
esac
if [ "$out" = docs/tradeoff.md ]; then plot=docs/images/tradeoff.png; else plot=${out%.md}.png; fi
[[ "$rounds" =~ ^[1-9][0-9]*$ ]] || die "ROUNDS must be a whole number >= 1, not '$rounds'"
for t in $times; do
  [[ "$t" =~ ^[0-9]+(\.[0-9]+)?$ ]] || die "TIMES must be seconds of the intro, e.g. '4 14 25', not '$times'"
done
[ -n "${times// /}" ] || die "TIMES is empty"
for f in build/rt-float build/rt-fixed build/rt-fixed16 build/rt-cmp; do
  [ -x "$f" ] || die "$f is missing: run make all first"
done
command -v gnuplot >/dev/null || die "gnuplot is missing: run ./setup.sh --test (package gnuplot-nox)"
mkdir -p "$(dirname "$out")" "$(dirname "$plot")"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cost=$work/cost.tsv    # run, time, round, ms
err=$work/err.tsv      # run, time, psnr_db, over8, pixels
: >"$cost"
: >"$err"
cpu=$(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1)
load=$(cut -d' ' -f1-3 /proc/loadavg)
nt=$(wc -w <<<"$times")
echo "tradeoff: ${#runs[@]} configurations, $nt frame(s), $rounds round(s); $cpu, load average $load" >&2
start=$(date +%s)

# field VALUE KEY: the value of key=value in a line of output
field() { sed -n "s/.*\\b$2=\\([^ ]*\\).*/\\1/p" <<<"$1" | head -1; }

fi_=0
for t in $times; do
  fi_=$((fi_ + 1))
  ref=$work/ref-$t.png
  # shellcheck disable=SC2086  # options are words on purpose
  build/rt-float render --time "$t" --size $SIZE $REF_OPTS -o "$ref" 2>/dev/null ||
    die "the reference frame at t=$t failed to render"
  for r in $(seq 1 "$rounds"); do
    echo "tradeoff: frame $fi_/$nt (t=$t s), round $r/$rounds" >&2
    # alternate the order from round to round, so drift in the machine's load evens out
    order=$(seq 0 $((${#runs[@]} - 1)))
    [ $((r % 2)) = 1 ] || order=$(tac <<<"$order")
    for k in $order; do
      read -r real ci <<<"${runs[$k]}"
      opts=${CONFIGS[$ci]#*|}
      img=$work/$k-$t.png
      # shellcheck disable=SC2086  # options are words on purpose
      stats=$(build/rt-$real render --time "$t" --size $SIZE --threads 1 --stats $opts -o "$img" 2>/dev/null) ||
        die "rt-$real render --time $t $opts failed"
      ms=$(grep '^ms=' <<<"$stats" | cut -d= -f2)
      [ -n "$ms" ] || die "rt-$real render --stats printed no ms="
      printf '%s\t%s\t%s\t%s\n' "$k" "$t" "$r" "$ms" >>"$cost"
      if [ "$r" = 1 ]; then
        line=$(build/rt-cmp "$img" "$ref")
        printf '%s\t%s\t%s\t%s\t%s\n' "$k" "$t" "$(field "$line" psnr_db)" "$(field "$line" over8)" \
          "$(field "$line" pixels)" >>"$err"
      fi
    done
  done
done
took=$(($(date +%s) - start))

# One row per configuration: run index, real, name, options, mean ms, worst-frame ms, mean PSNR
# (of the mean squared error over the frames), worst-frame PSNR, over8 % of all pixels, worst
# frame's over8 %. Then the Pareto fronts: over all runs, and over the fixed runs alone.
labels=$work/labels.tsv
for k in "${!runs[@]}"; do
  read -r real ci <<<"${runs[$k]}"
  opts=${CONFIGS[$ci]#*|}
  printf '%s\t%s\t%s\t%s\n' "$k" "$real" "${CONFIGS[$ci]%%|*}" "${opts:-(none)}"
done >"$labels"
rows=$work/rows.tsv
awk -F'\t' -v OFS='\t' '
  FILENAME == ARGV[1] { real[$1] = $2; name[$1] = $3; opts[$1] = $4; n++; next }
  FILENAME == ARGV[2] {   # cost: per frame the mean over rounds
    fs[$1 SUBSEP $2] += $4; fc[$1 SUBSEP $2]++; sum[$1] += $4; cnt[$1]++; next }
  {                       # error
    mse = ($3 == "inf") ? 0 : 65025 * 10 ^ (-$3 / 10)
    msum[$1] += mse; nf[$1]++
    p = ($3 == "inf") ? 1e9 : $3
    if (!($1 in worst) || p < worst[$1]) worst[$1] = p
    o = $4 / $5; osum[$1] += $4; pix[$1] += $5
    if (o > ow[$1]) ow[$1] = o
  }
  END {
    for (key in fs) { split(key, kt, SUBSEP); m = fs[key] / fc[key]; if (m > wms[kt[1]]) wms[kt[1]] = m }
    for (k = 0; k < n; k++) {
      ms[k] = sum[k] / cnt[k]
      mse = msum[k] / nf[k]
      ps[k] = (mse == 0) ? 1e9 : 10 * log(65025 / mse) / log(10)
    }
    for (k = 0; k < n; k++) {
      all = 1; fx = (real[k] ~ /^fixed/)
      for (j = 0; j < n; j++) {
        if (j == k || !(ms[j] <= ms[k] && ps[j] >= ps[k] && (ms[j] < ms[k] || ps[j] > ps[k]))) continue
        all = 0
        if (real[j] ~ /^fixed/) fx = 0
      }
      front = (all && fx) ? "all, fixed" : all ? "all" : fx ? "fixed" : ""
      printf "%d\t%s\t%s\t%s\t%.3f\t%.3f\t%s\t%s\t%.3f\t%.3f\t%s\n", k, real[k], name[k], opts[k], ms[k], wms[k],
        (ps[k] >= 1e9 ? "inf" : sprintf("%.2f", ps[k])), (worst[k] >= 1e9 ? "inf" : sprintf("%.2f", worst[k])),
        100 * osum[k] / pix[k], 100 * ow[k], front
    }
  }' "$labels" "$cost" "$err" >"$rows"

# The plot: mean PSNR against mean ms, float and fixed points labelled, the fronts drawn.
# Configurations with no error at all (PSNR inf) are drawn at the top edge, marked inf.
pdat=$work/plot.dat
awk -F'\t' '
  { ms[NR] = $5; ps[NR] = $7; real[NR] = $2; name[NR] = $3; front[NR] = $11
    if ($7 != "inf" && (top == "" || $7 + 0 > top)) top = $7 + 0 }
  END {
    if (top == "") top = 50
    for (i = 1; i <= NR; i++) {
      y = (ps[i] == "inf") ? top + 4 : ps[i]
      lab = name[i] (ps[i] == "inf" ? " (inf)" : "")
      printf "%s\t%s\t%s\t%s\t%d\t%d\n", ms[i], y, real[i], lab, front[i] ~ /all/, front[i] ~ /fixed/
    }
  }' "$rows" >"$pdat"
gnuplot <<EOF
set terminal pngcairo size 960,640 font "sans,10"
set output "$plot"
set title "fixray intro, $SIZE, $nt frame(s): error against the reference vs time per frame (1 thread)"
set xlabel "host ms per frame (mean)"
set ylabel "PSNR against float, full, depth 8, min-contrib 0 (dB, higher is better)"
set grid
set key bottom right
set datafile separator "\t"
set offsets graph 0.02, graph 0.12, graph 0.04, graph 0.04
plot "< awk -F'\t' '\$3 == \"float\"' $pdat | sort -g -k1,1" using 1:2 with points pt 7 ps 1.3 lc rgb "#1f77b4" title "float", \
     "< awk -F'\t' '\$3 == \"fixed\"' $pdat | sort -g -k1,1" using 1:2 with points pt 5 ps 1.3 lc rgb "#d62728" title "fixed", \
     "< awk -F'\t' '\$3 == \"fixed16\"' $pdat | sort -g -k1,1" using 1:2 with points pt 9 ps 1.4 lc rgb "#9467bd" title "fixed16 (unit in Q16.16)", \
     "< awk -F'\t' '\$5 == 1' $pdat | sort -g -k1,1" using 1:2 with lines lw 2 lc rgb "#2ca02c" title "Pareto front (all)", \
     "< awk -F'\t' '\$6 == 1' $pdat | sort -g -k1,1" using 1:2 with lines lw 2 dt 2 lc rgb "#ff7f0e" title "Pareto front (fixed only: an FPU-less board)", \
     "$pdat" using 1:2:4 with labels offset 0.8,0.6 left font "sans,8" notitle
EOF
[ -s "$plot" ] || die "gnuplot wrote no $plot"

plot_rel=${plot#"$(dirname "$out")"/}   # the plot as the table's file links it
base_ms=$(awk -F'\t' '$2 == "float" && $3 == "default" { print $5 }' "$rows")
{
  echo "# Accuracy against time: the intro"
  echo
  echo "Written by \`make tradeoff\` (\`tests/tradeoff.sh\`${QUICK:+, QUICK=$QUICK}) on $(date -u '+%Y-%m-%d %H:%M UTC'), in $took s."
  echo
  echo "- CPU: $cpu, $(nproc) cores; load average when it started: $load"
  echo "- $(uname -sr), $(gcc --version | head -1) -O2"
  echo "- Frames: the intro at t = ${times// /, } s, $SIZE; $rounds round(s), each frame rendered by every configuration in turn (the order reversed every other round)"
  echo "- Reference: \`rt-float render $REF_OPTS\` (every pixel, every ray, the deepest recursion)"
  echo
  echo "![PSNR against time per frame]($plot_rel)"
  echo
  echo "| build | configuration | render options | mean ms | worst-frame ms | x float default | mean PSNR | worst PSNR | over8 | worst-frame over8 | Pareto front |"
  echo "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"
  awk -F'\t' -v base="$base_ms" '{
    x = (base > 0) ? sprintf("%.2f", $5 / base) : ""
    o = ($4 == "(none)") ? "(none)" : "`" $4 "`"
    printf "| %s | %s | %s | %.2f | %.2f | %s | %s dB | %s dB | %.3f %% | %.3f %% | %s |\n",
      $2, $3, o, $5, $6, x, $7, $8, $9, $10, $11 }' "$rows"
  echo
  echo "Every configuration changes one option of \`rt-float\`/\`rt-fixed render\` from the intro's"
  echo "default (adaptive, \`--grid 8 --threshold 0.0625\`, the scene's depth 5, \`--min-contrib 0.01\`)."
  echo "**ms**: the tracer's own time per frame on one thread (\`--threads 1 --stats\`, its \`ms=\`:"
  echo "rendering, without writing the file), mean over frames and rounds; worst-frame: the slowest"
  echo "frame's mean over rounds. **PSNR** (\`rt-cmp\` against the reference): mean is the PSNR of"
  echo "the mean squared error over the frames (so a frame without error does not make it infinite),"
  echo "worst is the lowest frame's; inf means identical pictures. **over8**: pixels with a channel"
  echo "off by more than 8 of 255, as a share of all pixels, and of the worst frame's. **Pareto"
  echo "front**: no other configuration is both as fast and as accurate (\`all\`: among all rows;"
  echo "\`fixed\`: among the fixed-point rows, what an FPU-less board can choose from)."
  echo
  echo "Not measured yet:"
  echo
  echo "- A cheaper, less precise fixed-point variant (e.g. unit vectors in plain Q16.16): not yet"
  echo "  available; the fixed rows are the fixed layer as shipped."
  echo "- Noise octaves: \`render\` has no option for them (they are a material property in the"
  echo "  scene file, \`octaves N\`), so they are not swept."
  echo "- ARM instructions per frame: \`platform/arm/qemu.sh bench\` runs the default settings only;"
  echo "  \`make bench\` (docs/bench.md) has the default's count. The fixed rows' host times stand in"
  echo "  for the board's relative costs."
  echo
  echo "## How to reproduce"
  echo
  echo '```sh'
  echo "make tradeoff                              # builds what is missing, then writes this file and the plot"
  echo "QUICK=1 tests/tradeoff.sh                  # smoke run: two configurations, one frame (make test runs it)"
  echo "TIMES=\"4 25 44\" ROUNDS=1 tests/tradeoff.sh -o /tmp/t.md   # shorter; the plot goes to /tmp/t.png"
  echo '```'
  echo
  echo "The times depend on what else the machine is doing (see the load average above); the"
  echo "PSNR and over8 figures do not, and repeat exactly."
} >"$out"
echo "tradeoff: wrote $out and $plot in $took s" >&2
cat "$out"
