#!/usr/bin/env bash
# tradeoff.sh: accuracy against cost on the intro, one knob at a time, float, fixed and fixed16: host ms, and ARM926 instructions and estimated cycles per frame; table in docs/tradeoff.md, plot in docs/images/tradeoff.png (make tradeoff).
#
# Usage: tests/tradeoff.sh [-o FILE]   (default docs/tradeoff.md and docs/images/tradeoff.png;
#                                       with QUICK=1 build/tradeoff/tradeoff-quick.md and .png)
# Every configuration changes one render option from the intro's default (adaptive, --grid 8,
# --threshold 0.0625, the scene's depth 5, --min-contrib 0.01, each texture's own noise
# octaves, at most 4) and runs in rt-float, rt-fixed and rt-fixed16 (the cheaper fixed variant:
# unit vectors in Q16.16, docs/numerics.md). Each sample frame (TIMES, seconds of
# the intro, at 320x240) is rendered by every configuration in turn, ROUNDS rounds, on one
# thread (--threads 1 --stats: the tracer's ms=).
# Error: rt-cmp against the reference (rt-float --mode full --min-contrib 0 --depth 8).
# ARM926: then every configuration renders the same frames on the emulated board
# (platform/arm/qemu.sh bench with the same settings, one frame per run): the fixed (fixed16)
# image for the fixed (fixed16) rows, the soft-float image for the float rows; exact counts, and
# the cycle model's cycles beside them (docs/arm.md, Cycle model): the board's panel of the plot
# and its Pareto front are by the estimated time a frame at ARM_MHZ (default 200) MHz, cycles
# divided by the clock. Grids 2 and 16 do not fit the board's RAM (n/a). Without qemu-system-arm
# the ARM columns stay empty, with a note (ARM=0 does the same).
# Defaults: TIMES="4 14 25 35 44" (on whole frames, 25 fps), ROUNDS=5: 42 configurations, 33
# minutes on the 2-core build machine loaded 5 deep (host timing 4 minutes, ARM926 29 minutes under
# the cycle plugin, mostly the soft-float image). QUICK=1: two configurations on one frame, one round, the board's fixed
# default as the base (make test's smoke run, a few seconds).
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
  "probe|--mode probe"
  "grid 4|--grid 4"
  "grid 16|--grid 16"
  "threshold 0.03|--threshold 0.03"
  "threshold 0.125|--threshold 0.125"
  "depth 1|--depth 1"
  "depth 2|--depth 2"
  "depth 3|--depth 3"
  "depth 4|--depth 4"
  "octaves 1|--octaves 1"
  "octaves 2|--octaves 2"
  "octaves 3|--octaves 3"
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

# The ARM926 column: skipped, with a note, only when QEMU is not installed (or ARM=0).
FPS=$(awk '$1 == "fps" { print $2 }' scenes/intro.scene)
MHZ=${ARM_MHZ:-200}
[[ "$MHZ" =~ ^[1-9][0-9]*$ ]] || die "ARM_MHZ must be a whole number of MHz, 1 or more, not '$MHZ'"
arm=1 arm_note=""
if [ "${ARM:-1}" = 0 ]; then
  arm=0 arm_note="ARM=0 was given: the ARM926 columns are left empty."
elif ! command -v qemu-system-arm >/dev/null; then
  arm=0 arm_note="qemu-system-arm is not installed (./setup.sh --arm installs it): the ARM926 columns are left empty."
fi
[ -n "$arm_note" ] && echo "tradeoff: note: $arm_note" >&2
# frame_of SECONDS: the intro's frame at that moment (the board renders whole frames)
frame_of() {
  local ms
  ms=$(awk -v t="$1" 'BEGIN { printf "%d", t * 1000 + 0.5 }')
  [ $((ms * FPS % 1000)) = 0 ] || return 1
  echo $((ms * FPS / 1000))
}
if [ "$arm" = 1 ]; then
  for f in build/arm/intro-fixed.elf build/arm/intro-float.elf; do
    [ -f "$f" ] || die "$f is missing: run make arm first"
  done
  for t in $times; do
    frame_of "$t" >/dev/null || die "TIMES: $t s is not on a frame of the intro ($FPS fps), which the ARM926 renders"
  done
fi

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

# ARM926: every configuration on the same frames, one QEMU run per frame (qemu.sh bench N N 1),
# after the host timings so as not to disturb them. The board's fixed default is the base of
# the "x ARM fixed default" column; QUICK=1 measures it apart, as it is not one of its rows.
armt=$work/arm.tsv   # run (or base), time, instructions, cycles; n/a n/a where the board refuses
: >"$armt"
arm_run() { # key real options
  local t f out st n c
  for t in $times; do
    f=$(frame_of "$t")
    # shellcheck disable=SC2086  # options are words on purpose
    out=$(platform/arm/qemu.sh bench "$2" $3 "$f" "$f" 1 2>&1) && st=0 || st=$?
    n=$(sed -n "s/^frame=$f instructions=\([0-9]*\) cycles=[0-9]*$/\1/p" <<<"$out")
    c=$(sed -n "s/^frame=$f instructions=[0-9]* cycles=\([0-9]*\)$/\1/p" <<<"$out")
    if [ "$st" = 0 ] && [ -n "$n" ] && [ -n "$c" ]; then
      echo "tradeoff: ARM926 $2 ${3:-(defaults)}, frame $f: $n instructions, $c cycles" >&2
    elif [ "$st" = 2 ] && grep -q "working storage holds grids" <<<"$out"; then
      echo "tradeoff: ARM926 $2 $3: not on the board ($(grep -o 'holds grids.*' <<<"$out"))" >&2
      n=n/a c=n/a
    else
      die "ARM926 $2 image, bench $3 $f $f 1 failed: $(tr '\n' ' ' <<<"$out")"
    fi
    printf '%s\t%s\t%s\t%s\n' "$1" "$t" "$n" "$c" >>"$armt"
  done
}
arm_start=$(date +%s)
base_key=base
if [ "$arm" = 1 ]; then
  for k in "${!runs[@]}"; do
    read -r real ci <<<"${runs[$k]}"
    [ "$real" = fixed ] && [ -z "${CONFIGS[$ci]#*|}" ] && base_key=$k
  done
  [ "$base_key" != base ] || arm_run base fixed ""
  for k in "${!runs[@]}"; do
    read -r real ci <<<"${runs[$k]}"
    echo "tradeoff: ARM926 configuration $((k + 1))/${#runs[@]}: $real, ${CONFIGS[$ci]%%|*}" >&2
    arm_run "$k" "$real" "${CONFIGS[$ci]#*|}"
  done
fi
took_arm=$(($(date +%s) - arm_start))

# One row per configuration: run index, real, name, options, mean ms, worst-frame ms, mean PSNR
# (of the mean squared error over the frames), worst-frame PSNR, over8 % of all pixels, worst
# frame's over8 %, Pareto fronts, ARM926 mean instructions (M; n/a; empty without the board),
# x the board's fixed default (by cycles), ARM926 mean cycles (M), the estimated ms a frame at
# MHZ, cycles per instruction. Fronts: desktop (all rows, by host ms), board (the rows counted on
# the ARM926, by estimated cycles).
labels=$work/labels.tsv
for k in "${!runs[@]}"; do
  read -r real ci <<<"${runs[$k]}"
  opts=${CONFIGS[$ci]#*|}
  printf '%s\t%s\t%s\t%s\n' "$k" "$real" "${CONFIGS[$ci]%%|*}" "${opts:-(none)}"
done >"$labels"
rows=$work/rows.tsv
awk -F'\t' -v OFS='\t' -v base_key="$base_key" -v basef="$work/arm-base" -v mhz="$MHZ" '
  FILENAME == ARGV[1] { real[$1] = $2; name[$1] = $3; opts[$1] = $4; n++; next }
  FILENAME == ARGV[2] {   # cost: per frame the mean over rounds
    fs[$1 SUBSEP $2] += $4; fc[$1 SUBSEP $2]++; sum[$1] += $4; cnt[$1]++; next }
  FILENAME == ARGV[4] {   # ARM926 instructions
    if ($3 == "n/a") na[$1] = 1; else { asum[$1] += $3; csum[$1] += $4; acnt[$1]++ }
    next }
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
    abase = (base_key in acnt) ? asum[base_key] / acnt[base_key] : 0
    cbase = (base_key in acnt) ? csum[base_key] / acnt[base_key] : 0
    printf "%s\t%s\t%s\n", (abase > 0 ? sprintf("%.1f", abase / 1e6) : ""), (cbase > 0 ? sprintf("%.1f", cbase / 1e6) : ""),
      (cbase > 0 ? sprintf("%.0f", cbase / (mhz * 1e3)) : "") > basef
    for (k = 0; k < n; k++) {
      ms[k] = sum[k] / cnt[k]
      mse = msum[k] / nf[k]
      ps[k] = (mse == 0) ? 1e9 : 10 * log(65025 / mse) / log(10)
      onb[k] = (k in acnt) && !(k in na)
      if (onb[k]) { ai[k] = asum[k] / acnt[k]; ac[k] = csum[k] / acnt[k] }
    }
    for (k = 0; k < n; k++) {
      desk = 1; board = onb[k]
      for (j = 0; j < n; j++) {
        if (j == k) continue
        if (ms[j] <= ms[k] && ps[j] >= ps[k] && (ms[j] < ms[k] || ps[j] > ps[k])) desk = 0
        if (board && onb[j] && ac[j] <= ac[k] && ps[j] >= ps[k] && (ac[j] < ac[k] || ps[j] > ps[k])) board = 0
      }
      front = (desk && board) ? "desktop, board" : desk ? "desktop" : board ? "board" : ""
      am = onb[k] ? sprintf("%.1f", ai[k] / 1e6) : (k in na) ? "n/a" : ""
      ax = (onb[k] && cbase > 0) ? sprintf("%.2f", ac[k] / cbase) : ""
      cm = onb[k] ? sprintf("%.1f", ac[k] / 1e6) : (k in na) ? "n/a" : ""
      cms = onb[k] ? sprintf("%.0f", ac[k] / (mhz * 1e3)) : (k in na) ? "n/a" : ""
      cpi = onb[k] ? sprintf("%.2f", ac[k] / ai[k]) : (k in na) ? "n/a" : ""
      printf "%d\t%s\t%s\t%s\t%.3f\t%.3f\t%s\t%s\t%.3f\t%.3f\t%s\t%s\t%s\t%s\t%s\t%s\n", k, real[k], name[k], opts[k], ms[k], wms[k],
        (ps[k] >= 1e9 ? "inf" : sprintf("%.2f", ps[k])), (worst[k] >= 1e9 ? "inf" : sprintf("%.2f", worst[k])),
        100 * osum[k] / pix[k], 100 * ow[k], front, am, ax, cm, cms, cpi
    }
  }' "$labels" "$cost" "$err" "$armt" >"$rows"
IFS=$'\t' read -r arm_base arm_base_cyc arm_base_ms <"$work/arm-base" || true

# The plot: mean PSNR against the cost, float and fixed points labelled, the fronts drawn; with
# the ARM926 counts, a second panel against the board's estimated ms per frame (cycles / clock).
# Configurations with no error at all (PSNR inf) are drawn at the top edge, marked inf.
pdat=$work/plot.dat   # ms, PSNR (inf: at the top), real, label, desktop front, board front, ARM est. ms
awk -F'\t' '
  { ms[NR] = $5; ps[NR] = $7; real[NR] = $2; name[NR] = $3; front[NR] = $11; am[NR] = $15
    if ($7 != "inf" && (top == "" || $7 + 0 > top)) top = $7 + 0 }
  END {
    if (top == "") top = 50
    for (i = 1; i <= NR; i++) {
      y = (ps[i] == "inf") ? top + 4 : ps[i]
      lab = name[i] (ps[i] == "inf" ? " (inf)" : "")
      printf "%s\t%s\t%s\t%s\t%d\t%d\t%s\n", ms[i], y, real[i], lab, front[i] ~ /desktop/, front[i] ~ /board/,
        (am[i] ~ /^[0-9]/ ? am[i] : "NaN")
    }
  }' "$rows" >"$pdat"
# Each panel: the points by build, its front as a line, the points labelled. Its data are the
# rows sorted by the panel's cost (column $3: 1 host ms, 7 ARM926 estimated ms), so that the
# front is drawn from left to right.
panel() { # title xlabel x-column legend-float legend-fixed front-column front-title line-style
  local data=$pdat.$3
  sort -t "$(printf '\t')" -g -k"$3,$3" "$pdat" >"$data"
  cat <<EOF
set title "$1"
set xlabel "$2"
set ylabel "PSNR against float, full, depth 8, min-contrib 0 (dB, higher is better)"
plot "< awk -F'\t' '\$3 == \"float\" && \$$3 != \"NaN\"' $data" using $3:2 with points pt 7 ps 1.3 lc rgb "#1f77b4" title "$4", \\
     "< awk -F'\t' '\$3 == \"fixed\" && \$$3 != \"NaN\"' $data" using $3:2 with points pt 5 ps 1.3 lc rgb "#d62728" title "$5", \\
     "< awk -F'\t' '\$3 == \"fixed16\" && \$$3 != \"NaN\"' $data" using $3:2 with points pt 9 ps 1.4 lc rgb "#9467bd" title "$5, unit in Q16.16 (fixed16)", \\
     "< awk -F'\t' '\$$6 == 1' $data" using $3:2 with lines lw 2 $8 title "$7", \\
     "< awk -F'\t' '\$$3 != \"NaN\"' $data" using $3:2:4 with labels offset 0.8,0.6 left font "sans,7" notitle
EOF
}
{
  if [ "$arm" = 1 ]; then
    echo 'set terminal pngcairo size 1500,680 font "sans,10"'
  else
    echo 'set terminal pngcairo size 960,640 font "sans,10"'
  fi
  echo "set output \"$plot\""
  echo 'set grid'
  echo 'set key bottom right'
  printf '%s\n' 'set datafile separator "\t"'
  echo 'set offsets graph 0.02, graph 0.14, graph 0.04, graph 0.04'
  [ "$arm" = 1 ] && echo "set multiplot layout 1,2 title \"fixray intro, $SIZE, $nt frame(s): error against the reference vs cost per frame\""
  panel "desktop: host ms per frame, 1 thread" "host ms per frame (mean)" 1 float fixed 5 \
    "Pareto front (desktop)" 'lc rgb "#2ca02c"'
  if [ "$arm" = 1 ]; then
    echo 'set logscale x'
    echo 'set autoscale xfix'   # no widening to the next power of ten: the offsets give the room
    echo 'set xtics (100, 150, 200, 300, 500, 700, 1000, 1500, 2000, 3000, 5000, 7000, 10000, 15000)'
    panel "FPU-less ARM926 (QEMU, cycle model): estimated ms per frame at $MHZ MHz" "ARM926 estimated ms per frame at $MHZ MHz (cycles / clock, mean, log scale)" 7 \
      "soft-float image" "fixed image" 6 "Pareto front (board)" 'dt 2 lc rgb "#ff7f0e"'
    echo 'unset multiplot'
  fi
} | gnuplot
[ -s "$plot" ] || die "gnuplot wrote no $plot"

plot_rel=${plot#"$(dirname "$out")"/}   # the plot as the table's file links it
base_ms=$(awk -F'\t' '$2 == "float" && $3 == "default" { print $5 }' "$rows")
arm_frames=""
for t in $times; do arm_frames+="${arm_frames:+, }$(frame_of "$t" || true)"; done
{
  echo "# Accuracy against cost: the intro"
  echo
  echo "Written by \`make tradeoff\` (\`tests/tradeoff.sh\`${QUICK:+, QUICK=$QUICK}) on $(date -u '+%Y-%m-%d %H:%M UTC'): host timings in $took s, ARM926 runs in $took_arm s."
  echo
  echo "- CPU: $cpu, $(nproc) cores; load average when it started: $load"
  echo "- $(uname -sr), $(gcc --version | head -1) -O2"
  echo "- Frames: the intro at t = ${times// /, } s, $SIZE; $rounds round(s), each frame rendered by every configuration in turn (the order reversed every other round)"
  echo "- Reference: \`rt-float render $REF_OPTS\` (every pixel, every ray, the deepest recursion)"
  if [ "$arm" = 1 ]; then
    echo "- ARM926 (\`qemu-system-arm -M versatilepb -icount shift=0\`: exact instruction counts, and the cycle model's estimate, [arm.md](arm.md#cycle-model)): the same frames ($arm_frames) with the same settings, \`platform/arm/qemu.sh bench fixed|float|fixed16 SETTINGS N N 1\`; the fixed image with the default settings: $arm_base M instructions and $arm_base_cyc M estimated cycles per frame, $arm_base_ms ms at $MHZ MHz"
  else
    echo "- ARM926: not measured in this run. $arm_note"
  fi
  echo
  echo "![PSNR against cost per frame]($plot_rel)"
  echo
  echo "| build | configuration | render options | mean ms | worst-frame ms | x float default | ARM est. ms at $MHZ MHz | x ARM fixed default | ARM Mcycles/frame | ARM Minstr/frame | ARM CPI | mean PSNR | worst PSNR | over8 | worst-frame over8 | Pareto front |"
  echo "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"
  awk -F'\t' -v base="$base_ms" '{
    x = (base > 0) ? sprintf("%.2f", $5 / base) : ""
    o = ($4 == "(none)") ? "(none)" : "`" $4 "`"
    printf "| %s | %s | %s | %.2f | %.2f | %s | %s | %s | %s | %s | %s | %s dB | %s dB | %.3f %% | %.3f %% | %s |\n",
      $2, $3, o, $5, $6, x, $15, $13, $14, $12, $16, $7, $8, $9, $10, $11 }' "$rows"
  echo
  echo "Every configuration changes one option of \`rt-float\`/\`rt-fixed\`/\`rt-fixed16 render\` from the intro's"
  echo "default (adaptive, \`--grid 8 --threshold 0.0625\`, the scene's depth 5, \`--min-contrib 0.01\`,"
  echo "each noise texture's own octaves: 4 for marble and lava, 3 for wood)."
  echo "**ms**: the tracer's own time per frame on one thread (\`--threads 1 --stats\`, its \`ms=\`:"
  echo "rendering, without writing the file), mean over frames and rounds; worst-frame: the slowest"
  echo "frame's mean over rounds. **ARM est. ms**: the FPU-less ARM926's estimated time per frame"
  echo "at $MHZ MHz, its **Mcycles/frame** (million cycles a frame, mean over the frames: the cycle"
  echo "model's estimate, an ARM926EJ-S with 16 KiB I- and D-caches, [arm.md](arm.md#cycle-model))"
  echo "divided by the clock; **ARM Minstr/frame**: million instructions per frame under QEMU (exact),"
  echo "and **CPI** the cycles per instruction; counted across the board's rendering:"
  echo "the fixed (fixed16) image for the fixed (fixed16) rows, the soft-float image (the float build compiled with"
  echo "\`-mfloat-abi=soft\`) for the float rows; n/a: grids 2 and 16 need more working storage"
  echo "than the board's 32 KiB RAM budget holds, and it refuses them. **x ARM fixed default**:"
  echo "the estimated cycles against the fixed image's with the default settings. **PSNR** (\`rt-cmp\` against the"
  echo "reference): mean is the PSNR of the mean squared error over the frames (so a frame without"
  echo "error does not make it infinite), worst is the lowest frame's; inf means identical"
  echo "pictures. **over8**: pixels with a channel off by more than 8 of 255, as a share of all"
  echo "pixels, and of the worst frame's. **Pareto front**: no other configuration is both as cheap"
  echo "and as accurate: \`desktop\` by host ms among all rows, \`board\` by the ARM926's estimated cycles"
  echo "among the rows the board ran (all three images). **fixed16** is the cheaper fixed variant: unit"
  echo "vectors in Q16.16 instead of Q2.30 (\`-DFX_UNIT_FRAC=16\`, docs/numerics.md)."
  echo
  echo "## How to reproduce"
  echo
  echo '```sh'
  echo "make tradeoff                              # builds what is missing, then writes this file and the plot"
  echo "QUICK=1 tests/tradeoff.sh                  # smoke run: two configurations, one frame (make test runs it)"
  echo "TIMES=\"4 25 44\" ROUNDS=1 tests/tradeoff.sh -o /tmp/t.md   # shorter; the plot goes to /tmp/t.png"
  echo "ARM=0 tests/tradeoff.sh -o /tmp/t.md       # the host only, without the ARM926 runs"
  echo "platform/arm/qemu.sh bench fixed --octaves 2 350 350 1    # one ARM926 count by hand"
  echo '```'
  echo
  echo "The times depend on what else the machine is doing (see the load average above); the"
  echo "PSNR, over8 and ARM926 figures (instructions and the model's cycles) do not, and repeat exactly."
} >"$out"
echo "tradeoff: wrote $out and $plot (host timings $took s, ARM926 $took_arm s)" >&2
cat "$out"
