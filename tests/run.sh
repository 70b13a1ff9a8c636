#!/usr/bin/env bash
# run.sh: fixray's test suite (make test): unit tests, frame comparison, determinism, command line.
# Expects `make all san` to have been run. Prints one line per check and a closing
# 'N passed, N failed' line; exits non-zero when any check fails.
set -u
cd "$(dirname "$0")/.."

B=build
T=$B/test
rm -rf "$T" && mkdir -p "$T"
passed=0
failed=0

# The frames of the tracer's own tests come from the demo scene.
DEMO="--scene scenes/demo.scene"

pass() { passed=$((passed + 1)); echo "ok   $*"; }
fail() { failed=$((failed + 1)); echo "FAIL $*"; }

# ---- who may include whom (docs/architecture.md) ------------------------------------------------
# The numeric layer and the tracer core include only each other; the scene language adds the
# core, never the programs or the platform. Each #include "X" must be a file of the allowed
# folders (a positive control checks that the rule sees an include of the programs).
layer_bad() { # allowed-folders files...: prints the includes outside the allowed folders
  local allowed=$1 f inc d ok
  shift
  for f in "$@"; do
    while read -r inc; do
      ok=""
      for d in $allowed; do [ -e "$d/$inc" ] && ok=1; done
      [ -n "$ok" ] || echo -n "$f includes $inc; "
    done < <(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$f")
  done
}
bad="$(layer_bad "fixed src/core" fixed/*.[ch] src/core/*.[ch])$(layer_bad "fixed src/core src/scene" src/scene/*.[ch])"
# and of the system's headers the core takes only these: no I/O, allocation, clock or threads
sys=$(sed -n 's/^#include <\([^>]*\)>.*/\1/p' fixed/*.[ch] src/core/*.[ch] | sort -u | grep -vxE 'stdint.h|stddef.h|string.h|math.h|fix16.h|arm_acle.h')
[ -n "$sys" ] && bad="$bad fixed/ or src/core/ include <$(tr '\n' ' ' <<<"$sys")>;"
printf '#include "rt.h"\n#include "cli.h"\n' >"$T/layer.c"
ctl=$(layer_bad "fixed src/core" "$T/layer.c")
if [ -z "$bad" ] && [[ $ctl == *"includes cli.h"* ]]; then
  pass "layers: fixed/ and src/core/ include only each other and stdint, stddef, string, math, fix16 (and ARM's intrinsics, arm_acle); src/scene/ adds only them ($(ls fixed/*.[ch] src/core/*.[ch] src/scene/*.[ch] | wc -l) files)"
else
  fail "layers: $bad (control: $ctl)"
fi

# ---- formatting and links ------------------------------------------------------------------------
# Every C file is as the checked-in .clang-format has it (setup.sh --test installs clang-format).
cfiles=$(find fixed src platform tests -name '*.[ch]' | sort)
if ! command -v clang-format >/dev/null; then
  fail "format: clang-format is not installed (./setup.sh --test)"
# shellcheck disable=SC2086  # one word per file
elif out=$(clang-format --dry-run --Werror $cfiles 2>&1); then
  pass "format: clang-format --dry-run --Werror passes on the $(wc -w <<<"$cfiles") C files of fixed/ src/ platform/ tests/"
else
  fail "format: files differ from .clang-format (run clang-format -i on them): $(grep -o '^[^:]*\.[ch]' <<<"$out" | sort -u | tr '\n' ' ')"
fi
# Every relative link of README.md and docs/*.md leads to a file, every #anchor to a heading.
if out=$(tests/links.sh 2>&1); then
  pass "$out (each resolves to a file, each #anchor to a heading)"
else
  fail "links: $(tr '\n' ';' <<<"$out")"
fi

# The pictures in docs/images are the current fixed-point build's (make docs-images).
if out=$(src/tools/docs-images.sh --check 2>&1); then
  pass "$out"
else
  fail "$out"
fi

# ---- unit tests (cmocka), both builds, under AddressSanitizer + UBSan ------------------------
for v in san-fixed san-float; do
  for t in test_numeric test_shapes test_noise test_subsample test_scene test_stability test_optics; do
    if "$B/$v/$t" >"$T/$v-$t.log" 2>&1; then
      pass "$v/$t ($(grep -c '^\[       OK \]' "$T/$v-$t.log") cases)"
      grep -E '^(noise|fbm|sphere|far|numeric|interpolation|object|shadow|reflected|min_contrib|plane|normalise|  )' "$T/$v-$t.log" | sed 's/^/       /'
    else
      fail "$v/$t"
      sed 's/^/       /' "$T/$v-$t.log" | tail -30
    fi
  done
done

# The ARM926's division-free path (FX_SOFT_DIVIDE=1) on the host, under the sanitizers: the unit
# tests, and frames through the whole intro byte for byte those of rt-fixed's hardware division.
bad=""
for t in test_numeric test_shapes test_subsample; do
  "$B/san-fixed-sd/$t" >"$T/san-fixed-sd-$t.log" 2>&1 || bad="$bad $t:$(tail -3 "$T/san-fixed-sd-$t.log" | tr '\n' ' ');"
done
sd=$("$B/san-fixed-sd/rt" render --frames 0-1200 --step 100 --size 96x72 --checksum 2>"$T/san-fixed-sd.err")
hw=$("$B/rt-fixed" render --frames 0-1200 --step 100 --size 96x72 --checksum 2>/dev/null)
[ "$sd" = "$hw" ] && [ "$(grep -c fnv64= <<<"$sd")" -eq 13 ] || bad="$bad frames differ from rt-fixed: $(tail -1 "$T/san-fixed-sd.err");"
# the division-free quotient is called there, and nowhere in san-fixed
calls=$(objdump -d "$B/san-fixed-sd/rt" | grep -c 'call.*<fx_udiv64>')
[ "$calls" -gt 0 ] && ! objdump -d "$B/san-fixed/rt" | grep -q 'call.*<fx_udiv64>' || bad="$bad fx_udiv64 called $calls times;"
[ -z "$bad" ] && pass "san-fixed-sd (-DFX_SOFT_DIVIDE=1, the ARM926's division path): test_numeric, test_shapes, test_subsample pass; 13 intro frames = rt-fixed's; fx_udiv64 called from $calls places (none in san-fixed)" ||
  fail "san-fixed-sd:$bad"

# The fixed-point format itself: U_ONE and friends follow FX_UNIT_FRAC (30 in rt-fixed, 16 in
# rt-fixed16), and each format's unit-vector operations stay within a few of its own steps.
for vf in san-fixed:30 san-fixed16:16; do
  v=${vf%:*} frac=${vf#*:}
  if "$B/$v/test_format" >"$T/$v-test_format.log" 2>&1 && grep -q "^  unit_frac=$frac U_ONE=$((1 << frac))\$" "$T/$v-test_format.log"; then
    pass "$v/test_format: unit has $frac fraction bits ($(grep -c '^\[       OK \]' "$T/$v-test_format.log") cases)"
    grep '^  ' "$T/$v-test_format.log" | sed 's/^/     /'
  else
    fail "$v/test_format (want unit_frac=$frac)"
    sed 's/^/       /' "$T/$v-test_format.log" | tail -30
  fi
done

# ---- frames: fixed vs float on the demo scene (scenes/demo.scene) --------------------------------------------------
# Full mode (every pixel traced, every ray cast): PSNR >= 40 dB and at most 0.5% of pixels with a
# channel off by more than 8. Adaptive mode (the default): PSNR >= 38 dB.
cmp_frames() { # label fixed.png float.png min-psnr max-over8-per-mille
  local line psnr over8 pixels
  line=$($B/rt-cmp "$2" "$3" --diff "${2%.png}-diff.png")
  psnr=$(sed -n 's/.*psnr_db=\([^ ]*\).*/\1/p' <<<"$line")
  over8=$(sed -n 's/.*over8=\([0-9]*\).*/\1/p' <<<"$line")
  pixels=$(sed -n 's/.*pixels=\([0-9]*\).*/\1/p' <<<"$line")
  if [ -n "$psnr" ] && awk -v p="$psnr" -v o="$over8" -v n="$pixels" -v min="$4" -v pm="$5" \
       'BEGIN { exit !((p == "inf" || p >= min) && o * 1000 <= n * pm) }'; then
    pass "$1: $line"
  else
    fail "$1: $line (want psnr_db >= $4, over8 <= $5 per mille; see ${2%.png}-diff.png)"
  fi
}
for time in 0 6 12.5 18; do
  for mode in full adaptive; do
    f=$T/float-$mode-$time.png x=$T/fixed-$mode-$time.png
    if ! $B/rt-float render $DEMO --mode $mode --time "$time" -o "$f" 2>/dev/null ||
       ! $B/rt-fixed render $DEMO --mode $mode --time "$time" -o "$x" 2>/dev/null; then
      fail "render demo at t=$time in $mode mode"
      continue
    fi
    if [ $mode = full ]; then
      cmp_frames "fixed vs float, full mode, demo t=${time}s 320x240" "$x" "$f" 40 5
    else
      cmp_frames "fixed vs float, adaptive mode, demo t=${time}s 320x240" "$x" "$f" 38 10
    fi
  done
done
# Adaptive mode with every criterion at its finest is full mode, but for interpolated squares
# whose corners agree exactly.
for real in fixed float; do
  $B/rt-$real render $DEMO --mode full --min-contrib 0 --time 9 -o "$T/$real-ref.png" 2>/dev/null
  $B/rt-$real render $DEMO --threshold 0 --min-contrib 0 --time 9 -o "$T/$real-thr0.png" 2>/dev/null
  cmp_frames "$real: adaptive with --threshold 0 vs full, t=9s" "$T/$real-thr0.png" "$T/$real-ref.png" 50 1
done

# ---- determinism: the same frame twice gives the same bytes ------------------------------------
for real in fixed float; do
  for ext in png ppm; do
    $B/rt-$real render $DEMO --time 3.5 --size 200x150 -o "$T/det1-$real.$ext" 2>/dev/null
    $B/rt-$real render $DEMO --time 3.5 --size 200x150 -o "$T/det2-$real.$ext" 2>/dev/null
    if cmp -s "$T/det1-$real.$ext" "$T/det2-$real.$ext"; then
      pass "deterministic: rt-$real renders t=3.5 twice to identical .$ext bytes"
    else
      fail "deterministic: rt-$real renders t=3.5 twice to different .$ext files"
    fi
  done
  for opts in "--mode full" "--grid 16 --threshold 0.2" "--grid 2 --size 97x61"; do
    $B/rt-$real render $DEMO --time 7.25 --size 150x100 $opts -o "$T/det3-$real.ppm" 2>/dev/null
    $B/rt-$real render $DEMO --time 7.25 --size 150x100 $opts -o "$T/det4-$real.ppm" 2>/dev/null
    if [ -s "$T/det3-$real.ppm" ] && cmp -s "$T/det3-$real.ppm" "$T/det4-$real.ppm"; then
      pass "deterministic: rt-$real $opts renders twice to identical bytes"
    else
      fail "deterministic: rt-$real $opts renders twice to different files"
    fi
  done
done
# --frame N is --time N/25
$B/rt-fixed render $DEMO --frame 50 --size 64x48 -o "$T/frame50.ppm" 2>/dev/null
$B/rt-fixed render $DEMO --time 2 --size 64x48 -o "$T/time2.ppm" 2>/dev/null
if cmp -s "$T/frame50.ppm" "$T/time2.ppm"; then pass "--frame 50 equals --time 2"; else fail "--frame 50 differs from --time 2"; fi

# ---- the whole tracer under the sanitizers, with numeric event counting ------------------------
for real in fixed float; do
  out=$($B/san-$real/rt render $DEMO --time 7 --size 160x120 --stats -o "$T/san-$real.png" 2>"$T/san-$real.err")
  rc=$?
  ov=$(sed -n 's/^fx_overflow=//p' <<<"$out")
  dm=$(sed -n 's/^fx_domain=//p' <<<"$out")
  if [ $rc -eq 0 ] && [ ! -s "$T/san-$real.err" -o "$(grep -c 'runtime error\|Sanitizer' "$T/san-$real.err")" = 0 ] &&
     [ "$ov" = 0 ] && [ "$dm" = 0 ]; then
    pass "sanitized $real render: no ASan/UBSan report, fx_overflow=$ov fx_domain=$dm"
  else
    fail "sanitized $real render: exit $rc, fx_overflow=$ov fx_domain=$dm"
    head -20 "$T/san-$real.err" | sed 's/^/       /'
  fi
done

# ---- --stats --------------------------------------------------------------------------------------
stats=$($B/rt-fixed render $DEMO --mode full --size 80x60 --stats -o "$T/stats.png" 2>/dev/null)
missing=""
for key in ms pixels samples_traced rays_primary rays_shadow rays_reflect rays_refract; do
  grep -q "^$key=[0-9.]*$" <<<"$stats" || missing="$missing $key"
done
if [ -z "$missing" ] && grep -q '^pixels=4800$' <<<"$stats" && grep -q '^samples_traced=4800$' <<<"$stats" &&
   grep -q '^mode=full$' <<<"$stats"; then
  pass "--stats in full mode: every pixel traced, rays by kind"
else
  fail "--stats (full mode) output lacks:$missing"
fi
stats=$($B/rt-fixed render $DEMO --threads 1 --size 320x240 --time 3 --stats -o "$T/stats-ad.ppm" 2>/dev/null)
missing=""
for key in samples_traced rays_primary rays_shadow rays_reflect rays_refract squares_8 split_8 \
           squares_4 split_4 squares_2 split_2 split_object split_light split_secondary \
           split_contrib work_bytes; do
  grep -q "^$key=[0-9]*$" <<<"$stats" || missing="$missing $key"
done
samples=$(sed -n 's/^samples_traced=//p' <<<"$stats")
sq8=$(sed -n 's/^squares_8=//p' <<<"$stats")
if [ -z "$missing" ] && grep -q '^mode=adaptive$' <<<"$stats" && grep -q '^grid=8$' <<<"$stats" &&
   [ "$sq8" = 1200 ] && [ "$samples" -lt 76800 ]; then
  pass "--stats in adaptive mode: $samples of 76800 points traced, 1200 8x8 squares, splits per level and reason"
else
  fail "--stats (adaptive mode) output lacks:$missing (samples=$samples squares_8=$sq8)"
fi
# --show-samples paints the traced points (white or cyan): at most as many changed pixels as
# points traced
$B/rt-fixed render $DEMO --size 320x240 --time 3 --show-samples -o "$T/dots.ppm" 2>/dev/null
line=$($B/rt-cmp "$T/dots.ppm" "$T/stats-ad.ppm")
changed=$(sed -n 's/.*differing=\([0-9]*\).*/\1/p' <<<"$line")
if [ -n "$changed" ] && [ "$changed" -le "$samples" ] && [ $((changed * 10)) -ge $((samples * 9)) ]; then
  pass "--show-samples marks $changed pixels for $samples traced points"
else
  fail "--show-samples changed '$changed' pixels for $samples traced points"
fi

# ---- probe mode (--mode probe, docs/probe.md) -------------------------------------------------------
# --stats: probes= beside samples_traced= (points shaded in full); --show-samples: shaded points
# white (cyan where they took their local part from their square's corners), probed ones
# magenta, one mark per point. On matte spheres (the demo's mirror floor leaves no probe).
PROBE_AT="--scene scenes/shadows.scene --time 5"
samples=$($B/rt-fixed render $PROBE_AT --threads 1 --size 320x240 --stats -o "$T/probe-ad.ppm" 2>/dev/null |
  sed -n 's/^samples_traced=//p')
stats=$($B/rt-fixed render $PROBE_AT --mode probe --threads 1 --size 320x240 --stats -o "$T/probe.ppm" 2>/dev/null)
shaded=$(sed -n 's/^samples_traced=//p' <<<"$stats")
probes=$(sed -n 's/^probes=//p' <<<"$stats")
$B/rt-fixed render $PROBE_AT --mode probe --size 320x240 --show-samples -o "$T/probe-dots.ppm" 2>/dev/null
marks=$(python3 - "$T/probe-dots.ppm" <<'PY'
import sys
d = open(sys.argv[1], 'rb').read().split(b'\n', 3)[3]
px = [d[i:i + 3] for i in range(0, len(d), 3)]
print(px.count(b'\xff\xff\xff') + px.count(b'\x00\xff\xff'), px.count(b'\xff\x00\xff'))
PY
)
read -r white magenta <<<"$marks"
if grep -q '^mode=probe$' <<<"$stats" && [ -n "$shaded" ] && [ -n "$probes" ] && [ "$probes" -gt 0 ] &&
   [ "$shaded" -lt "$samples" ] && [ "${white:-0}" -le "$shaded" ] && [ $((white * 10)) -ge $((shaded * 9)) ] &&
   [ "${magenta:-0}" -gt 0 ] && [ "$magenta" -le "$probes" ]; then
  pass "--mode probe --stats: $shaded points shaded in full (adaptive $samples), $probes probes; --show-samples: $white white or cyan, $magenta magenta"
else
  fail "--mode probe: shaded '$shaded' (adaptive $samples), probes '$probes', marks white or cyan '$white' magenta '$magenta'"
fi
# The same frames on any number of threads (bands of rows of squares), both builds.
for real in fixed float; do
  sums=""
  for th in 1 2 3; do
    sums="$sums $($B/rt-$real render --frames 0-1200 --step 300 --mode probe --threads $th --checksum 2>/dev/null | md5sum | cut -c1-12)"
  done
  read -r s1 s2 s3 <<<"$sums"
  if [ -n "$s1" ] && [ "$s1" = "$s2" ] && [ "$s1" = "$s3" ]; then
    pass "probe mode: rt-$real intro frames 0-1200 step 300 identical on 1, 2 and 3 threads"
  else
    fail "probe mode: rt-$real frames differ between thread counts:$sums"
  fi
done
# The issue's quality and cost bounds, as ratios on intro frames 0..1200 step 200 at 320x240:
# at least 6x fewer points shaded than --mode full, PSNR against --mode full --min-contrib 0
# mean >= 45 dB and worst >= 40 dB (frame 0 is black: identical, left out of the PSNR).
for real in fixed float; do
  tot=0 psum=0 n=0 worst=99 list=""
  for f in 0 200 400 600 800 1000 1200; do
    $B/rt-$real render --frame $f --mode full --min-contrib 0 -o "$T/pr-ref-$f.ppm" 2>/dev/null
    st=$($B/rt-$real render --frame $f --mode probe --threads 1 --stats -o "$T/pr-$f.ppm" 2>/dev/null)
    tot=$((tot + $(sed -n 's/^samples_traced=//p' <<<"$st")))
    p=$($B/rt-cmp "$T/pr-$f.ppm" "$T/pr-ref-$f.ppm" | sed -n 's/.*psnr_db=\([^ ]*\).*/\1/p')
    [ "$p" = inf ] && continue
    list="$list $f:$p"
    read -r psum n worst < <(awk -v s="$psum" -v n="$n" -v w="$worst" -v p="$p" \
      'BEGIN { print s + p, n + 1, (p < w ? p : w) }')
  done
  # full mode shades 7 x 76800 points
  verdict=$(awk -v t="$tot" -v s="$psum" -v n="$n" -v w="$worst" \
    'BEGIN { r = 7 * 76800 / t; m = s / n; printf "%s %.2f %.2f", (r >= 6 && m >= 45 && w >= 40) ? "ok" : "bad", r, m }')
  read -r v ratio mean <<<"$verdict"
  if [ "$v" = ok ]; then
    pass "probe mode, rt-$real intro 0..1200 step 200: ${ratio}x fewer points shaded than full (>= 6), PSNR mean $mean dB (>= 45), worst $worst dB (>= 40)"
  else
    fail "probe mode, rt-$real: ${ratio}x fewer shaded points (want >= 6), PSNR mean $mean (>= 45), worst $worst (>= 40):$list"
  fi
done

# Local parts on reflection edges (ss_local_ok) must not hide a highlight that lies between a
# split square's corners: on intro frame 1012 a glossy sphere's highlight at pixel (244, 112) is
# (255, 228, 197) in full mode; local parts taken over whole 8x8 squares lost it (193 levels
# off, 106 pixels over 8), adaptive mode without them is 69 off at most (84 over 8). Both modes
# that use local parts, both builds: at most 100 levels off anywhere, at most 100 pixels over 8.
for real in fixed float; do
  $B/rt-$real render --frame 1012 --mode full --min-contrib 0 -o "$T/hl-ref.ppm" 2>/dev/null
  bad=""
  for m in adaptive probe; do
    $B/rt-$real render --frame 1012 --mode $m -o "$T/hl-$m.ppm" 2>/dev/null
    line=$($B/rt-cmp "$T/hl-$m.ppm" "$T/hl-ref.ppm" 2>&1)
    read -r mx o8 < <(sed -n 's/.*max_abs=\([0-9]*\).*over8=\([0-9]*\).*/\1 \2/p' <<<"$line")
    if [ -z "$mx" ] || [ "$mx" -gt 100 ] || [ "$o8" -gt 100 ]; then bad="$bad $m: $line;"; fi
  done
  if [ -z "$bad" ]; then
    pass "rt-$real intro frame 1012, adaptive and probe mode: the glossy sphere's highlight between square corners is kept (against full mode: at most 100 levels off, 100 pixels over 8)"
  else
    fail "rt-$real intro frame 1012 lost the highlight between square corners:$bad"
  fi
done

stats=$($B/rt-float render $DEMO --size 80x60 --depth 0 --stats -o "$T/stats0.png" 2>/dev/null)
if grep -q '^rays_reflect=0$' <<<"$stats" && grep -q '^rays_refract=0$' <<<"$stats" && grep -q '^depth=0$' <<<"$stats"; then
  pass "--depth 0 casts no reflected or refracted ray"
else
  fail "--depth 0 still casts secondary rays"
fi

# --octaves N caps every noise texture's octaves. The textures scene has noise textures of 3 and
# 4 octaves: --octaves 1 and 3 change the picture and sum fewer octaves (noise_octaves=, the
# noise work done), 4 (the scene's most) and 8 change nothing, byte for byte; in both builds.
for real in fixed float; do
  oct() { $B/rt-$real render --scene scenes/textures.scene --time 6 --threads 1 --stats "$@" 2>/dev/null |
          sed -n 's/^noise_octaves=//p'; }
  n0=$(oct -o "$T/oct-$real.ppm")
  bad=""
  for k in 1 3 4 8; do
    nk=$(oct --octaves $k -o "$T/oct-$real-$k.ppm")
    if [ $k -ge 4 ]; then
      cmp -s "$T/oct-$real.ppm" "$T/oct-$real-$k.ppm" && [ "$nk" = "$n0" ] ||
        bad="$bad --octaves $k changed the picture or noise_octaves ($nk, not $n0);"
    else
      d=$($B/rt-cmp "$T/oct-$real.ppm" "$T/oct-$real-$k.ppm" | sed -n 's/.*differing=\([0-9]*\).*/\1/p')
      [ "${d:-0}" -gt 0 ] && [ -n "$nk" ] && [ "$nk" -lt "$n0" ] ||
        bad="$bad --octaves $k: $d pixels differ, noise_octaves=$nk (default $n0);"
    fi
    eval "n$k=\$nk"
  done
  if [ -z "$bad" ] && [ "${n0:-0}" -gt 0 ] && [ "$n1" -lt "$n3" ]; then
    pass "--octaves ($real): noise_octaves $n0 (scene's), 3: $n3, 1: $n1, pictures changed; 4 and 8 byte-identical to the scene's"
  else
    fail "--octaves ($real):$bad (noise_octaves ${n0:-none} by default, 1: ${n1:-}, 3: ${n3:-})"
  fi
done
# --footprint (on by default): noise octaves finer than a pixel's footprint are left out, the
# last one faded. On the textures scene at 160x120 (small pixels' worth of far noise) it sums
# fewer octaves (noise_octaves=) and changes the picture; --footprint off is the old picture.
for real in fixed float; do
  fp() { $B/rt-$real render --scene scenes/textures.scene --time 6 --size 160x120 --stats "$@" 2>/dev/null |
         sed -n 's/^\(footprint\|noise_octaves\)=//p' | tr '\n' ' '; }
  on=$(fp -o "$T/fp-$real-on.ppm")
  off=$(fp --footprint off -o "$T/fp-$real-off.ppm")
  d=$($B/rt-cmp "$T/fp-$real-on.ppm" "$T/fp-$real-off.ppm" | sed -n 's/.*differing=\([0-9]*\).*/\1/p')
  read -r fon non <<<"$on"
  read -r foff noff <<<"$off"
  if [ "$fon" = on ] && [ "$foff" = off ] && [ "${non:-0}" -gt 0 ] && [ "$non" -lt "${noff:-0}" ] && [ "${d:-0}" -gt 0 ]; then
    pass "--footprint ($real): noise_octaves $noff -> $non (footprint=on, the default), $d pixels changed"
  else
    fail "--footprint ($real): on '$on', off '$off', $d pixels differ"
  fi
done
# Against a supersampled reference (rt-float, 4x4 samples per pixel in full mode, every octave,
# box-filtered by rt-cmp --box 4), a frame with footprint octaves scores at least the PSNR of
# the frame with every octave: textures scene at 6 s and the intro at 17 s, 320x240 (and the
# textures scene at 160x120, where the footprint leaves most out), full mode, both builds.
bad=""
figs=""
for c in "scenes/textures.scene 6 320 240" "scenes/intro.scene 17 320 240" "scenes/textures.scene 6 160 120"; do
  read -r sc tm w h <<<"$c"
  tag=$(basename "$sc" .scene)-$tm-$w
  ref="$T/fpref-$tag.png"
  $B/rt-float render --scene "$sc" --time "$tm" --size $((4 * w))x$((4 * h)) --mode full --min-contrib 0 \
    --footprint off -o "$ref" >/dev/null 2>&1 || bad="$bad reference $tag failed;"
  for real in fixed float; do
    for f in on off; do
      $B/rt-$real render --scene "$sc" --time "$tm" --size ${w}x$h --mode full --min-contrib 0 \
        --footprint $f -o "$T/fp-$tag-$real-$f.png" >/dev/null 2>&1
      eval "p_$f=\$($B/rt-cmp \"\$ref\" \"$T/fp-$tag-$real-$f.png\" --box 4 | sed -n 's/^psnr_db=\([0-9.]*\).*/\1/p')"
    done
    figs="$figs $tag $real ${p_on:-?}/${p_off:-?} dB;"
    awk -v a="${p_on:-x}" -v b="${p_off:-y}" 'BEGIN { exit !(a + 0 > 0 && a + 0 >= b + 0) }' ||
      bad="$bad $tag $real: footprint on ${p_on:-none} dB < off ${p_off:-none} dB;"
  done
done
if [ -z "$bad" ]; then
  pass "--footprint vs a 4x4 supersampled reference (on/off):$figs"
else
  fail "--footprint vs a 4x4 supersampled reference:$bad"
fi
stats=$($B/rt-fixed render --scene scenes/diffuse.scene --octaves 2 --stats -o "$T/oct-diffuse.png" 2>/dev/null)
if grep -q '^noise_octaves=0$' <<<"$stats" && grep -q '^octaves=2$' <<<"$stats"; then
  pass "--octaves on a scene without noise: octaves=2, noise_octaves=0"
else
  fail "--octaves on a scene without noise: $(grep octaves <<<"$stats" | tr '\n' ' ')"
fi

# ---- several frames in one process: --frames, --step, -o pattern, --checksum -----------------------
# Each frame of a multi-frame render is byte for byte the frame a single render gives (no state
# carries over from one frame to the next), and --checksum prints the same hash for it.
for real in fixed float; do
  mf=$($B/rt-$real render --frames 0-1200 --step 300 --size 96x72 -o "$T/mf-$real-%04d.ppm" --checksum --stats 2>"$T/mf-$real.err")
  bad=""
  grep -q '^frames=5$' <<<"$mf" || bad="$bad no frames=5 in --stats;"
  for f in 0 300 600 900 1200; do
    one=$($B/rt-$real render --frame $f --size 96x72 -o "$T/sf-$real.ppm" --checksum 2>/dev/null)
    cmp -s "$T/sf-$real.ppm" "$T/mf-$real-$(printf %04d $f).ppm" || bad="$bad frame $f differs from a single render;"
    grep -qx -- "$one" <<<"$mf" || bad="$bad checksum of frame $f ($one) not in the run;"
  done
  if [ -z "$bad" ] && [ "$(ls "$T"/mf-$real-*.ppm | wc -l)" = 5 ]; then
    pass "rt-$real --frames 0-1200 --step 300: 5 files, each identical to a single render of its frame, same checksums"
  else
    fail "rt-$real --frames:$bad $(cat "$T/mf-$real.err")"
  fi
done
# --checksum alone writes no file; the checksum is the 64-bit FNV-1a of the PPM's raster bytes
(cd "$T" && ../rt-fixed render --size 40x30 --checksum >/dev/null 2>&1)
sum=$($B/rt-fixed render --size 40x30 --time 2 --checksum -o "$T/ck.ppm" 2>/dev/null)
# FNV-1a in bash's 64-bit arithmetic (it wraps) over the raster: the bytes after "P6\n40 30\n255\n"
h=$((0xcbf29ce484222325))
for byte in $(tail -c +14 "$T/ck.ppm" | od -An -v -tu1); do h=$(( (h ^ byte) * 0x100000001b3 )); done
want=$(printf '%016x' $h)
if [ ! -e "$T/frame.png" ] && [ "$sum" = "time_ms=2000 fnv64=$want" ]; then
  pass "--checksum: $sum is the FNV-1a of the PPM raster; without -o no file is written"
else
  fail "--checksum printed '$sum' (want fnv64=$want), or wrote frame.png without -o"
fi

# ---- rt-cmp ---------------------------------------------------------------------------------------
line=$($B/rt-cmp "$T/det1-fixed.png" "$T/det1-fixed.ppm")
if [ "$line" = "psnr_db=inf max_abs=0 differing=0 over8=0 pixels=30000" ]; then
  pass "rt-cmp: PNG and PPM of the same frame are identical ($line)"
else
  fail "rt-cmp on identical images printed: $line"
fi
if [ -s "$T/fixed-full-6-diff.png" ]; then pass "rt-cmp --diff writes the difference picture"; else fail "rt-cmp --diff wrote nothing"; fi

# ---- bad input: one line on stderr, exit 2 (or 1 for a failed write), nothing left behind -------
expect_error() { # expected-status message-pattern command...
  local want=$1 pattern=$2
  shift 2
  local err rc
  err=$("$@" 2>&1 >/dev/null)
  rc=$?
  if [ $rc -eq "$want" ] && [ "$(wc -l <<<"$err")" -eq 1 ] && grep -q -- "$pattern" <<<"$err"; then
    pass "error: ${*#$B/} -> exit $rc: $err"
  else
    fail "error: ${*#$B/} -> exit $rc (want $want, one line matching '$pattern'): $err"
  fi
}
R=$B/rt-fixed
# The table of bad command lines: tests/bad_cli.txt (its header says what each case must do).
W=$PWD/$T/cli
mkdir -p "$W/adir.png"
$R render --size 8x8 -o "$W/one.ppm" 2>/dev/null
$R render --size 16x8 -o "$W/two.ppm" 2>/dev/null
printf 'P6\n2 2\n255\nabc' >"$W/short.ppm"
printf 'P6\n4000 4000\n255\n' >"$W/big.ppm"
printf 'P6\n5000 4000\n255\n' >"$W/huge.ppm"
echo "not an image" >"$W/text.png"
echo "sphre a material m center 0 0 0 radius 1" >"$W/bad.scene"
printf '%s\n' "duration 2" "camera eye 0 1 5 at 0 1 0" "material m" \
  "sphere s material m center 0 0 -3 radius 1" "key camera.eye 0 linear 0 1 5" \
  "key camera.eye 1 linear 0 1 0" "key camera.eye 2 linear 0 1 -5" >"$W/eye.scene"
listing() { (cd "$W" && find . -mindepth 1 -printf '%p %s %T@\n' | sort); }
TOP=$PWD
before=$(listing)
ncli=0
while IFS= read -r line; do
  [[ -z $line || $line == \#* ]] && continue
  want=${line#* => }
  eval "args=(${line%% => *})"
  case ${args[0]} in
    RT) progs="rt-fixed rt-float san-fixed/rt san-float/rt" ;;
    PLAYERS) progs="rt-fixed:play rt-float:play san-fixed/rt:play intro-fixed intro-float" ;;
    *) progs=${args[0]} ;;
  esac
  bad="" first=""
  for pc in $progs; do
    p=${pc%%:*} cmd=()
    [[ $pc == *:* ]] && cmd=("${pc#*:}")
    err=$(cd "$W" && "$TOP/$B/$p" "${cmd[@]}" "${args[@]:1}" 2>&1 >/dev/null </dev/null)
    rc=$?
    if [ $rc -ne 2 ] || [ "$(wc -l <<<"$err")" -ne 1 ] || [[ "$err" != "$(basename "$p"): "* ]] ||
       [[ "$err" != *"$want"* ]]; then
      bad="$bad $p: exit $rc: $err;"
    fi
    # PLAYERS: word for word the same message, but for the program's name
    if [ "${args[0]}" = PLAYERS ]; then
      msg=${err#"$(basename "$p"): "} msg=${msg//"$(basename "$p")"/PROG}
      [ -z "$first" ] && first=$msg
      [ "$msg" = "$first" ] || bad="$bad $p says '$msg', not '$first';"
    fi
  done
  now=$(listing)
  [ "$now" = "$before" ] || { bad="$bad files changed: $(diff <(echo "$before") <(echo "$now") | grep '^[<>]' | tr '\n' ' ');"; before=$now; }
  ncli=$((ncli + 1))
  if [ -z "$bad" ]; then
    [ -n "${VERBOSE:-}" ] && echo "       ${line%% => *}: $err"
  else
    fail "bad command line '${line%% => *}' (want exit 2, one line containing '$want'):$bad"
  fi
done <tests/bad_cli.txt
pass "bad command lines: the $ncli cases of tests/bad_cli.txt, each one line and exit 2 (render cases from both builds and both sanitized builds; player cases word for word alike from rt-* play and the intro players), no file left behind"
# --progress without a terminal (a log, CI): plain lines, one every 5 percent, no carriage returns.
$B/rt-fixed render --frames 0-199 --size 8x6 --progress --checksum >/dev/null 2>"$T/progress.err"
lines=$(grep -c 'rt-fixed: frame .*%), .* frames/s' "$T/progress.err")
if ! grep -q $'\r' "$T/progress.err" && [ "$lines" -eq 21 ] && grep -q '(200 of 200, 100%)' "$T/progress.err"; then
  pass "--progress into a file: $lines plain lines for 200 frames (the first, then every 5%), no carriage return"
else
  fail "--progress into a file: $lines progress lines for 200 frames (want 21, no \\r): $(head -c 300 "$T/progress.err" | tr '\r\n' '|/')"
fi
# One grammar: `--opt=value` is `--opt value` (here with a size written WXH), and the players
# accept the same command lines: each option is taken before --help ends the run.
eq=$($B/rt-fixed render --size=40X30 --time=2 --checksum 2>&1)
sp=$($B/rt-fixed render --size 40x30 --time 2 --checksum 2>&1)
if [[ $sp == "time_ms=2000 fnv64="* ]] && [ "$eq" = "$sp" ]; then
  pass "render --size=40X30 --time=2 --checksum = render --size 40x30 --time 2 --checksum: $sp"
else
  fail "render --size=40X30 --time=2 --checksum: '$eq', want '$sp'"
fi
bad=""
for args in "--size=64X48 --threads=2 --frames=3" "--size 64x48 --threads 1 --frames 1 --screenshot $W/ok.png" \
            "--frames=9 --screenshot=$W/ok.ppm --size=4096x1"; do
  for p in "rt-fixed play" "rt-float play" intro-fixed intro-float; do
    # shellcheck disable=SC2086  # words on purpose
    out=$($B/$p $args --help 2>&1 </dev/null) && grep -q "^usage:" <<<"$out" || bad="$bad $p $args: $out;"
  done
done
[ -z "$bad" ] && [ ! -e "$W/ok.png" ] && pass "the players accept the same command lines (rt-fixed/rt-float play, intro-fixed/intro-float, each option taken before --help)" ||
  fail "players' command lines:$bad"
# help and --version: `help`, `--help` and `render --help` print the same usage, generated from
# the option table (every option of render and play in it, no stray line); --version names the
# program, fixray's version and the number system.
h1=$($B/rt-fixed help) h2=$($B/rt-fixed --help) h3=$($B/rt-fixed render --help) h4=$($B/rt-fixed play -h)
v1=$($B/rt-fixed --version) v2=$($B/intro-float --version) v3=$($B/rt-edges --version)
bad=""
[ "$h1" = "$h2" ] && [ "$h2" = "$h3" ] && [ "$h3" = "$h4" ] || bad="$bad the four usages differ;"
for o in --scene -o --size --time --frame --frames --step --checksum --progress --depth --mode --grid \
         --threshold --min-contrib --octaves --effects --show-samples --threads --stats --screenshot; do
  grep -q -- "^  $o \|^  $o, \|, $o \| $o,\| $o as" <<<"$h1" || bad="$bad $o missing;"
done
grep -qx ' *rt-fixed --help' <<<"$h1" && bad="$bad stray 'rt-fixed --help' line;"
[[ $v1 =~ ^rt-fixed\ \(fixray\)\ [0-9.]+,\ fixed$ ]] && [[ $v2 =~ ^intro-float\ \(fixray\)\ [0-9.]+,\ float$ ]] &&
  [[ $v3 =~ ^rt-edges\ \(fixray\) ]] || bad="$bad versions: $v1 / $v2 / $v3;"
[ -z "$bad" ] && pass "help = --help = render --help = play -h ($(wc -l <<<"$h1") lines, every option); $v1; $v2" ||
  fail "help and --version:$bad"
# The tools never open a window: they link the null display (platform/null.c), not SDL2; the
# programs that play do (the positive control).
bad=""
for p in rt-cmp rt-scenec rt-edges; do
  readelf -d "$B/$p" | grep -q 'NEEDED.*libSDL2' && bad="$bad $p links SDL2;"
done
for p in rt-fixed rt-float intro-fixed; do
  readelf -d "$B/$p" | grep -q 'NEEDED.*libSDL2' || bad="$bad $p does not link SDL2;"
done
[ -z "$bad" ] && pass "rt-cmp, rt-scenec, rt-edges link no SDL2 (null display); rt-fixed, rt-float, intro-fixed do" ||
  fail "SDL2 links:$bad"
# A write that fails once rendering is done (here: a file size limit) gets exit status 1 and
# leaves neither the file nor its temporary file behind, in single- and multi-frame renders.
for args in "-o $W/limit.ppm" "--frames 0-2 -o $W/limit-%d.ppm"; do
  err=$( (trap '' XFSZ; ulimit -f 1; $R render --size 64x48 $args) 2>&1 >/dev/null)
  rc=$?
  now=$(listing)
  if [ $rc -eq 1 ] && [ "$(wc -l <<<"$err")" -eq 1 ] && [[ "$err" == "rt-fixed: "*"cannot write: File too large" ]] &&
     [ "$now" = "$before" ]; then
    pass "failed write ($args, 1 KiB file size limit): exit 1, one line, nothing left behind: $err"
  else
    fail "failed write ($args): exit $rc: $err; files: $(diff <(echo "$before") <(echo "$now") | grep '^[<>]' | tr '\n' ' ')"
    before=$now
  fi
done

# ---- example scenes: fixed vs float, derived effects, no rays for unused effects ---------------
# The effects each scene is written to use (docs/scene-format.md); checked at every moment rendered.
declare -A WANT_FX=(
  [intro]=shadow,specular,reflect,refract,texture,noise
  [demo]=shadow,specular,reflect,refract,texture,noise
  [diffuse]=none
  [shadows]=shadow
  [mirrors]=shadow,specular,reflect
  [glass]=shadow,specular,reflect,refract,texture
  [textures]=shadow,texture,noise
)
for scene in scenes/*.scene; do
  name=$(basename "${scene%.scene}")
  dur=$(awk '$1 == "duration" { printf "%d", $2 * 1000 }' "$scene")
  step=$((dur / 4))
  [ "$name" = intro ] && step=4000
  worst="" bad=""
  for ((ms = 0; ms <= dur; ms += step)); do
    t=$((ms / 1000)).$(printf '%03d' $((ms % 1000)))
    sx=$($B/rt-fixed render --scene "$scene" --time "$t" --stats -o "$T/sc-$name-x.png" 2>&1) || { bad="$bad fixed render failed at $t s: $sx;"; continue; }
    sf=$($B/rt-float render --scene "$scene" --time "$t" --stats -o "$T/sc-$name-f.png" 2>&1) || { bad="$bad float render failed at $t s;"; continue; }
    line=$($B/rt-cmp "$T/sc-$name-x.png" "$T/sc-$name-f.png")
    psnr=$(sed -n 's/.*psnr_db=\([^ ]*\).*/\1/p' <<<"$line")
    awk -v p="$psnr" 'BEGIN { exit !(p == "inf" || p >= 38) }' || bad="$bad psnr $psnr dB at $t s;"
    worst=$(awk -v a="$worst" -v p="$psnr" 'BEGIN { if (p == "inf") p = 999; print (a == "" || p < a) ? p : a }')
    for out in "$sx" "$sf"; do
      fx=$(sed -n 's/^effects=//p' <<<"$out")
      [ "$fx" = "${WANT_FX[$name]:-?}" ] || bad="$bad effects=$fx at $t s (want ${WANT_FX[$name]:-a WANT_FX entry});"
      for kind in shadow reflect refract; do
        if [[ ",$fx," != *",$kind,"* ]] && ! grep -q "^rays_$kind=0$" <<<"$out"; then
          bad="$bad $(grep "^rays_$kind=" <<<"$out") without $kind;"
        fi
      done
    done
  done
  if [ -z "$bad" ]; then
    pass "scene $name: fixed vs float >= 38 dB at every moment tested (worst $worst dB), effects=${WANT_FX[$name]}, no ray of an unused kind"
  else
    fail "scene $name:$bad"
  fi
done
# A scene compiled into its own program (rt-scenec, only the scene's effects linked) renders
# exactly what render --scene renders.
if tests/scene_programs.sh --check --arm >"$T/programs.log" 2>&1; then
  pass "every scene compiled into its own program renders the same bytes as render --scene"
else
  fail "compiled scene programs (see below)"
fi
sed 's/^/       /' "$T/programs.log"
# Regression scenes where a derivation once skipped what the scene needed: auto and all agree,
# in both builds, with no numeric event; and each compiled into its own program.
for scene in tests/scenes/fx-*.scene; do
  name=$(basename "${scene%.scene}")
  t=0; grep -q '^duration' "$scene" && t=5
  bad=""
  for real in fixed float; do
    a=$($B/san-$real/rt render --scene "$scene" --time $t --size 64x48 --stats -o "$T/$name-auto.ppm" 2>&1)
    $B/san-$real/rt render --scene "$scene" --time $t --size 64x48 --effects all -o "$T/$name-all.ppm" 2>/dev/null
    cmp -s "$T/$name-auto.ppm" "$T/$name-all.ppm" || bad="$bad $real auto/all differ;"
    grep -q '^fx_overflow=0$' <<<"$a" && grep -q '^fx_domain=0$' <<<"$a" || bad="$bad $real numeric events;"
  done
  tests/scene_programs.sh --check "$scene" >"$T/$name-prog.log" 2>&1 || bad="$bad compiled program differs;"
  if [ -z "$bad" ]; then pass "effects regression $name: auto = all, compiled = file, no numeric event"; else fail "effects regression $name:$bad"; fi
done
# Effects on demand and every effect forced on give the same picture.
for real in fixed float; do
  $B/rt-$real render $DEMO --time 5 --effects all -o "$T/fx-all-$real.ppm" 2>/dev/null
  $B/rt-$real render $DEMO --time 5 -o "$T/fx-auto-$real.ppm" 2>/dev/null
  if [ -s "$T/fx-all-$real.ppm" ] && cmp -s "$T/fx-all-$real.ppm" "$T/fx-auto-$real.ppm"; then
    pass "rt-$real: --effects auto and --effects all render the demo to identical bytes"
  else
    fail "rt-$real: --effects auto and --effects all differ"
  fi
done

# ---- numerically hard scenes (tests/hard/*.scene; docs/numerics.md) ----------------------------
while read -r line; do
  case $line in
    ok*) pass "${line#ok   }" ;;
    *) fail "${line#FAIL }" ;;
  esac
done < <(tests/hard_scenes.sh 2>&1)

# Subsampled modes against full mode on every example and hard scene (tests/quality.sh, docs/quality.md).
if tests/quality.sh --short >"$T/quality.log" 2>&1; then pass "quality --short: $(grep -c "| ok" "$T/quality.log") frames within the targets; $(grep "^| fixed | probe" "$T/quality.log")"; else fail "quality --short: $(grep ^FAIL "$T/quality.log" | tr "\n" " ")"; fi

# ---- each texture its own reach (docs/scene-format.md): a checker plane takes scale 1 and up
# to 1.5625 (points 20480 units out, x 1.5625 = 32000), rendered towards the far edge of the
# scene with no numeric event, fixed against float; noise textures keep their 20000 (bad_scenes).
bad=""
for scale in 1 1.5625; do
  printf '%s\n' "camera eye 0 1 -4000 at 0 0.95 -4096" "light sun pos 0 4000 0 color 1 1 1" \
    "material checks texture checker scale $scale color2 0.2 0.2 0.2" \
    "plane floor material checks normal 0 1 0 offset 0" >"$T/checker-$scale.scene"
  for v in san-fixed san-float; do
    st=$($B/$v/rt render --scene "$T/checker-$scale.scene" --size 64x48 --stats -o "$T/checker-$scale-$v.png" 2>&1) ||
      bad="$bad $v scale $scale: $st;"
    grep -q '^fx_overflow=0$' <<<"$st" && grep -q '^fx_domain=0$' <<<"$st" || bad="$bad $v scale $scale: numeric events;"
  done
  # the release build (unchecked products, r_mul_round_in's one-sum form) gives san-fixed's bytes
  $B/rt-fixed render --scene "$T/checker-$scale.scene" --size 64x48 -o "$T/checker-$scale-rel.png" >/dev/null 2>&1 &&
    cmp -s "$T/checker-$scale-rel.png" "$T/checker-$scale-san-fixed.png" || bad="$bad rt-fixed scale $scale differs from san-fixed;"
  line=$($B/rt-cmp "$T/checker-$scale-san-fixed.png" "$T/checker-$scale-san-float.png" 2>&1)
  awk -v p="$(sed -n 's/.*psnr_db=\([^ ]*\).*/\1/p' <<<"$line")" 'BEGIN { exit !(p == "inf" || p >= 40) }' || bad="$bad scale $scale: $line;"
done
[ -z "$bad" ] && pass "checker plane at scale 1 and 1.5625 out to the scene's edge: no numeric event, fixed vs float $line" ||
  fail "checker plane scales:$bad"

# ---- bad scene files: the table in tests/bad_scenes.txt --------------------------------------
# Each case: exit 2, one line "FILE:LINE:COL: words", and the same message from both builds.
BAD=$T/bad
mkdir -p "$BAD"
awk -v dir="$BAD" '
  /^===/ { n++; f = sprintf("%s/case%02d.scene", dir, n); sub(/^=== /, ""); print > (dir "/case" sprintf("%02d", n) ".want"); printf "" > f; next }
  n > 0 { print >> f }
' tests/bad_scenes.txt
for want in "$BAD"/case*.want; do
  scene=${want%.want}.scene
  expected="$scene:$(cat "$want")"
  errs="" msgs=""
  # both builds, and both again under ASan + UBSan
  for prog in rt-fixed rt-float san-fixed/rt san-float/rt; do
    err=$($B/$prog render --scene "$scene" --size 8x8 -o "$T/bad.ppm" 2>&1 >/dev/null)
    rc=$?
    if [ $rc -ne 2 ] || [ "$(wc -l <<<"$err")" -ne 1 ] || [[ "$err" != *"$expected"* ]]; then
      errs="$errs $prog: exit $rc: $err;"
    fi
    msgs="$msgs${err#*: }"$'\n'
  done
  if [ -z "$errs" ] && [ "$(sort -u <<<"$msgs" | grep -c .)" = 1 ]; then
    pass "bad scene: ${err#*: }"
  else
    fail "bad scene $(basename "$scene"): want '$expected':$errs"
  fi
done
# more than the limits of items
{ echo "camera eye 0 1 5 at 0 0 0"; echo "material m"
  for i in $(seq 1 33); do echo "sphere s$i material m center $i 0 0 radius 0.5"; done; } >"$BAD/objects.scene"
expect_error 2 "objects.scene:35:1: more than 32 objects" $R render --scene "$BAD/objects.scene"
{ for i in $(seq 1 17); do echo "material m$i"; done; } >"$BAD/materials.scene"
expect_error 2 "materials.scene:17:1: more than 16 materials" $R render --scene "$BAD/materials.scene"
: >"$BAD/empty.scene"
expect_error 2 "empty.scene:1:1: the scene has no camera" $R render --scene "$BAD/empty.scene"
head -c 1100000 /dev/zero >"$BAD/huge.scene"
expect_error 2 "larger than 1048576 bytes" $R render --scene "$BAD/huge.scene"
# rt-scenec: the same messages (its other bad command lines are in tests/bad_cli.txt)
expect_error 2 "case08.scene:2:19: undefined material 'glas'" $B/rt-scenec "$BAD/case08.scene" -o "$T/sc.c"
# a write that fails half-way: exit 1, neither output nor a temporary file left behind
mkdir -p "$T/scw"
err=$( (trap '' XFSZ; ulimit -f 1; $B/rt-scenec scenes/intro.scene -o "$T/scw/sc.c" --effects "$T/scw/sc.h") 2>&1 >/dev/null)
rc=$?
if [ $rc -eq 1 ] && [ "$(wc -l <<<"$err")" -eq 1 ] && [ -z "$(ls -A "$T/scw")" ]; then
  pass "rt-scenec: a failed write (1 KiB file size limit) gets exit 1 and leaves nothing behind: $err"
else
  fail "rt-scenec failed write: exit $rc: $err; left: $(ls -A "$T/scw")"
fi

# ---- rt-edges: the bound on adaptive subsampling (tests/bench_subsample.sh prints it) -----------
# A lone plane seen from above (no horizon), no texture, no highlight, one light: no edge at all,
# so only the grid's corners must be traced (41 x 31 at 320x240, grid 8). The demo scene: edges,
# and the bound it prints is pixels / points that must be traced.
printf '%s\n' "camera eye 0 6 1 at 0 0 0" "light l pos 0 5 0 color 1 1 1" "material m specular 0" \
  "plane p material m normal 0 1 0 offset 0" >"$T/flat.scene"
flat=$($B/rt-edges --scene "$T/flat.scene" --size 320x240 --time 0)
demo=$($B/rt-edges --scene=scenes/demo.scene --size=160x120 --time=4)
kv() { sed -n "s/^$1=//p" <<<"$2"; }
if [ "$(kv edge_pixels "$flat")" = 0 ] && [ "$(kv must_trace "$flat")" = 1271 ] &&
   [ "$(kv edge_pixels "$demo")" -gt 1000 ] && [ "$(kv must_trace "$demo")" -ge "$(kv edge_pixels "$demo")" ] &&
   awk -v b="$(kv bound_x_samples "$demo")" -v m="$(kv must_trace "$demo")" 'BEGIN { exit !(b > 1 && (19200 / m - b) ^ 2 < 0.0001) }'; then
  pass "rt-edges: a flat plane has no edge (1271 points: the 8x8 grid's corners); the demo scene at 160x120 has $(kv edge_pixels "$demo") edge pixels, bound x_samples $(kv bound_x_samples "$demo")"
else
  fail "rt-edges: flat: $(tr '\n' ' ' <<<"$flat"); demo: $(tr '\n' ' ' <<<"$demo")"
fi

# ---- the scene fuzzer: a bounded smoke run (make fuzz runs it longer) ----------------------------
# tests/fuzz.sh replays every kept crash of tests/fuzz-regress/ first, then fuzzes each build from
# the seeds; any crash, hang (10 s), leak, sanitizer report or numeric event fails.
while IFS= read -r line; do
  case $line in
    fuzz-*": "*"no crash"*) pass "$line" ;;
    fuzz-*) fail "$line" ;;
    *) echo "       $line" ;;
  esac
done < <(tests/fuzz.sh "${FUZZ_SECONDS:-15}" --smoke 2>&1)
# Each kept crash also goes through the programs themselves (scn_load, the render command) under
# ASan + UBSan, at its start and its end: rendered, or refused with one line and exit 2.
bad=""
for f in tests/fuzz-regress/*.scene; do
  for real in fixed float; do
    for t in 0 "$(awk '$1 == "duration" { d = $2 } END { print d + 0 }' "$f")"; do
      out=$($B/san-$real/rt render --scene "$f" --size 32x24 --time "$t" --stats -o "$T/regress.ppm" 2>"$T/regress.err")
      rc=$?
      if [ $rc -eq 0 ]; then
        grep -q '^fx_overflow=0$' <<<"$out" && grep -q '^fx_domain=0$' <<<"$out" || bad="$bad $real $(basename "$f") $t: numeric events;"
      elif [ $rc -ne 2 ] || [ "$(wc -l <"$T/regress.err")" -ne 1 ]; then
        bad="$bad $real $(basename "$f") $t: exit $rc: $(head -3 "$T/regress.err");"
      fi
    done
  done
done
if [ -z "$bad" ]; then
  pass "the $(ls tests/fuzz-regress/*.scene | wc -l) kept fuzz inputs (tests/fuzz-regress/) render cleanly under ASan + UBSan in both builds, no numeric event"
else
  fail "kept fuzz inputs:$bad"
fi

# ---- soak: every frame of the intro, twice, both builds (tests/soak.sh; SOAK_STEP=N for a subset) -
while IFS= read -r line; do
  case $line in
    *"identical passes, no growth") pass "$line" ;;
    *) fail "$line" ;;
  esac
done < <(tests/soak.sh "${SOAK_STEP:-1}" 320x240 2>&1)

# ---- rt-fixed16: the cheaper fixed-point variant (unit vectors in Q16.16) ---------------------
# Intro frames at t = 4, 14, 24, 34, 44 s (320x240, default settings): the same bytes twice, the
# same bytes from the sanitized build with no numeric event, and each within 40 dB PSNR and 3 per
# mille of pixels off by more than 8 of rt-float's (measured over every 25th frame of the intro:
# worst 42.7 dB and 1.7 per mille, at 24 s; rt-fixed's worst is 52.6 dB).
F16="--frames 100-1100 --step 250"
bad=""
# shellcheck disable=SC2086  # options are words on purpose
for run in 1 2; do
  mkdir -p "$T/f16-$run"
  $B/rt-fixed16 render $F16 -o "$T/f16-$run/%04d.ppm" 2>/dev/null || bad="$bad rt-fixed16 render failed (run $run);"
done
# shellcheck disable=SC2086
$B/rt-float render $F16 -o "$T/f16-float-%04d.ppm" 2>/dev/null || bad="$bad rt-float render failed;"
mkdir -p "$T/f16-san"
# shellcheck disable=SC2086
san=$($B/san-fixed16/rt render $F16 -o "$T/f16-san/%04d.ppm" --stats 2>&1) || bad="$bad san-fixed16 render failed: $(tail -3 <<<"$san");"
grep -q '^real=fixed16$' <<<"$san" || bad="$bad --stats does not say real=fixed16;"
grep -q '^fx_overflow=0$' <<<"$san" && grep -q '^fx_domain=0$' <<<"$san" || bad="$bad numeric events: $(grep '^fx_' <<<"$san" | tr '\n' ' ');"
psnrs=""
for n in 0100 0350 0600 0850 1100; do
  cmp -s "$T/f16-1/$n.ppm" "$T/f16-2/$n.ppm" || bad="$bad frame $n differs between two runs;"
  cmp -s "$T/f16-1/$n.ppm" "$T/f16-san/$n.ppm" || bad="$bad frame $n differs from the sanitized build's;"
  line=$($B/rt-cmp "$T/f16-1/$n.ppm" "$T/f16-float-$n.ppm" 2>&1)
  psnr=$(sed -n 's/.*psnr_db=\([^ ]*\).*/\1/p' <<<"$line")
  over8=$(sed -n 's/.*over8=\([0-9]*\).*/\1/p' <<<"$line")
  psnrs="$psnrs $((10#$n)):${psnr}dB/${over8}"
  awk -v p="$psnr" -v o="$over8" 'BEGIN { exit !((p == "inf" || p >= 40) && o * 1000 <= 76800 * 3) }' ||
    bad="$bad frame $n vs float: $line (want >= 40 dB, over8 <= 3 per mille);"
done
if [ -z "$bad" ]; then
  pass "rt-fixed16: intro frames 100-1100 step 250 the same bytes twice and in the sanitized build (no numeric event); vs rt-float (frame:PSNR/over8 of 76800):$psnrs"
else
  fail "rt-fixed16:$bad"
fi

# ---- valgrind memcheck: intro frames rendered and written by both -O2 builds -------------------
# the float build reads the intro from its scene file, the fixed one uses the compiled-in copy
for real in fixed float; do
  scene=(); [ $real = float ] && scene=(--scene scenes/intro.scene)
  if valgrind -q --error-exitcode=99 --leak-check=full --show-leak-kinds=definite,indirect,possible \
       --errors-for-leak-kinds=definite,indirect,possible $B/rt-$real render "${scene[@]}" \
       --frames 0-1200 --step 400 --size 160x120 -o "$T/vg-$real-%04d.png" --stats >/dev/null 2>"$T/vg-$real.log" &&
     [ "$(ls "$T"/vg-$real-*.png | wc -l)" = 4 ] && ! grep -q '^==' "$T/vg-$real.log"; then
    pass "valgrind memcheck: rt-$real renders and writes 4 intro frames (0-1200 step 400, 160x120) with no error and no leak"
  else
    fail "valgrind memcheck on rt-$real (see $T/vg-$real.log)"
    grep '^==' "$T/vg-$real.log" | head -20 | sed 's/^/       /'
  fi
done

# ---- scripts that print ok/FAIL lines: the player and threads, the ARM926 and M3 images under QEMU ----
run_part() { # script: counts its ok/FAIL lines; a failing exit without a FAIL line fails too
  local log=$T/$(basename "$1" .sh).log st before=$failed line
  "$1" >"$log" 2>&1
  st=$?
  while IFS= read -r line; do
    case "$line" in
      "ok   "*) pass "${line#ok   }" ;;
      "FAIL "*) fail "${line#FAIL }" ;;
      *) echo "       $line" ;;
    esac
  done <"$log"
  [ "$st" -eq 0 ] || [ "$failed" -gt "$before" ] || fail "$1 exited with status $st"
}
run_part tests/play.sh
run_part tests/arm.sh
run_part tests/m3.sh

# ---- make bench's script, QUICK=1: runs end to end and writes a well-formed table ------------
# Content, not timings: every configuration has one row, worst >= mean > 0, the fps follow from
# the times (1000 / ms) and from the instruction counts (200 MHz / instructions), the CPU and
# core count are named, and progress went to standard error.
bench_md=$T/bench-quick.md
nl=$'\n'
if QUICK=1 tests/bench_all.sh -o "$bench_md" >"$T/bench-quick.out" 2>"$T/bench-quick.err"; then
  nth=2; [ "$(nproc)" -gt 1 ] || nth=1
  problems=$(awk -F' *[|] *' -v nth="$nth" -v cores="$(nproc)" '
    function num(s) { sub(/ .*/, "", s); sub(/\*$/, "", s); return s + 0 }
    function near(a, b, r) { return a >= b * 0.99 - r && a <= b * 1.01 + r }   # r: the printed rounding
    # fps f printed to 0.01 from clock / m, m printed to 0.1 M: m was within 0.05 M of its figure
    function per(f, clock, m) { return f >= clock / (m + 0.05) * 0.99 - 0.0051 && (m <= 0.05 || f <= clock / (m - 0.05) * 1.01 + 0.0051) }
    /^- CPU: .*, [0-9]+ cores/ { cpu = 1; if ($0 !~ ", " cores " cores") print "core count is not " cores }
    /^[|] platform [|] build [|] size [|] threads [|] mean frame [|] worst frame [|] mean fps [|] worst-frame fps [|]$/ { head = 1 }
    /^[|] (desktop|ARM926, QEMU) [|]/ {
      key = $2 "/" $3 "/" $4 "/" $5
      if (key in seen) print "duplicate row " key
      seen[key] = 1
      m = num($6); w = num($7); fm = num($8); fw = num($9)
      if (!(m > 0 && w >= m)) print "bad mean/worst: " $0
      if ($2 == "desktop") {
        d++
        if ($6 !~ / ms$/ || !near(fm, 1000 / m, 0.051) || !near(fw, 1000 / w, 0.051)) print "fps do not follow from ms: " $0
      } else {
        a++
        if ($5 != 1 || $6 !~ / M instructions$/ || $8 !~ /[*]$/ || !per(fm, 200, m) || !per(fw, 200, w))
          print "ARM926 fps do not follow from 200 MHz / instructions: " $0
      }
    }
    /^[\\][*] ARM926 fps: [*][*]at a 200 MHz clock, assuming one instruction per cycle/ { label = 1 }
    /^[|] Cortex-M3, QEMU [|]/ {
      m3++; m = num($6); w = num($7); fm = num($8); fw = num($9)
      if ($3 != "fixed" || $4 != "128x64" || $6 !~ / M instructions$/ || $8 !~ /[*][*]$/ || !(m > 0 && w >= m) ||
          !per(fm, 50, m) || !per(fw, 50, w))
        print "Cortex-M3 fps do not follow from 50 MHz / instructions: " $0
    }
    /^[\\][*][\\][*] Cortex-M3 fps: [*][*]at the LM3S6965.s 50 MHz, assuming one instruction per cycle/ { m3label = 1 }
    END {
      if (m3 != 1) print m3 + 0 " Cortex-M3 rows, expected 1"
      if (!m3label) print "no 50 MHz / one instruction per cycle label for the Cortex-M3"
      if (!cpu) print "no CPU line"
      if (!head) print "no table header"
      if (!label) print "no 200 MHz / one instruction per cycle label"
      if (d != 2 * 2 * nth) print d + 0 " desktop rows, expected " 2 * 2 * nth
      if (a != 2) print a + 0 " ARM926 rows, expected 2"
    }' "$bench_md")
  for want in "desktop | float | 320x240 | 1 |" "desktop | fixed | 640x480 | $(nproc) |" \
              "ARM926, QEMU | fixed | 320x240 |" "ARM926, QEMU | soft-float | 320x240 |"; do
    grep -qF "| $want" "$bench_md" || problems+="${problems:+$nl}no row '$want'"
  done
  grep -q 'bench: desktop, round 1/1, frame 3/3' "$T/bench-quick.err" && grep -q 'qemu-bench: float image.*frames in' "$T/bench-quick.err" ||
    problems+="${problems:+$nl}no progress on standard error"
  if [ -z "$problems" ]; then
    pass "make bench's script (QUICK=1): $(grep -c '^| desktop' "$bench_md") desktop, $(grep -c '^| ARM926' "$bench_md") ARM926 and $(grep -c '^| Cortex-M3' "$bench_md") Cortex-M3 rows, fps consistent with the times and instruction counts"
  else
    fail "make bench's script (QUICK=1) wrote a malformed $bench_md:"
    sed 's/^/       /' <<<"$problems"
  fi
else
  fail "make bench's script (QUICK=1 tests/bench_all.sh) failed:"
  tail -5 "$T/bench-quick.err" | sed 's/^/       /'
fi

# ---- make tradeoff's script, QUICK=1: runs end to end and writes a well-formed table ------------
# Form, not timings: one row per configuration (float default, fixed full), ms > 0 with the worst
# frame no faster than the mean, PSNR a number or inf (worst <= mean), over8 a share in 0..100 %,
# and the plot written as a PNG. The ARM926 column: the fixed full row (a non-default setting on
# the board) has a positive whole count of instructions, other than the board's default's.
trade_md=$T/tradeoff-quick.md
if QUICK=1 tests/tradeoff.sh -o "$trade_md" >"$T/tradeoff-quick.out" 2>"$T/tradeoff-quick.err"; then
  problems=$(awk -F' *[|] *' '
    function db(s) { sub(/ dB$/, "", s); return s }
    function isdb(s) { return s ~ /^(inf|-?[0-9]+[.][0-9]+) dB$/ }
    /^[|] build [|] configuration [|] render options [|] mean ms [|] worst-frame ms [|] x float default [|] ARM Minstr\/frame [|] x ARM fixed default [|]/ { head = 1 }
    /^[|] (float|fixed) [|]/ {
      key = $2 "/" $3
      if (key in seen) print "duplicate row " key
      seen[key] = 1; n++
      if (!($5 + 0 > 0 && $6 + 0 >= $5 + 0)) print "bad mean/worst ms: " $0
      if ($8 !~ /^[0-9]+[.][0-9]$/ || $8 + 0 <= 0) print "ARM926 Minstr/frame not a positive number: " $0
      if ($2 == "fixed" && ($9 !~ /^[0-9]+[.][0-9][0-9]$/ || $9 == "1.00")) print "fixed full: ARM926 count not other than the default: " $0
      if (!isdb($10) || !isdb($11)) print "PSNR not a number or inf: " $0
      else if (db($10) != "inf" && (db($11) == "inf" || db($11) + 0 > db($10) + 0)) print "worst PSNR above the mean: " $0
      if ($12 !~ /^[0-9]+[.][0-9]+ %$/ || $12 + 0 > 100 || $13 !~ /^[0-9]+[.][0-9]+ %$/ || $13 + 0 < $12 + 0) print "bad over8: " $0
    }
    END {
      if (!head) print "no table header"
      if (n != 2) print n + 0 " rows, expected 2"
      if (!(("float/default") in seen) || !(("fixed/full") in seen)) print "missing the float default or the fixed full row"
    }' "$trade_md")
  png=${trade_md%.md}.png
  [ "$(head -c 8 "$png" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
    problems+="${problems:+$nl}no PNG plot at $png"
  grep -q 'tradeoff: frame 1/1 (t=14 s), round 1/1' "$T/tradeoff-quick.err" ||
    problems+="${problems:+$nl}no progress on standard error"
  arm_def=$(sed -n 's/^tradeoff: ARM926 fixed (defaults), frame 350: \([0-9]*\) instructions$/\1/p' "$T/tradeoff-quick.err")
  arm_full=$(sed -n 's/^tradeoff: ARM926 fixed --mode full, frame 350: \([0-9]*\) instructions$/\1/p' "$T/tradeoff-quick.err")
  [[ "$arm_full" =~ ^[1-9][0-9]*$ ]] && [[ "$arm_def" =~ ^[1-9][0-9]*$ ]] && [ "$arm_full" != "$arm_def" ] ||
    problems+="${problems:+$nl}ARM926 counts: fixed --mode full '$arm_full', fixed default '$arm_def' (want two different positive whole numbers)"
  if [ -z "$problems" ]; then
    pass "make tradeoff's script (QUICK=1): $(grep -cE '^[|] (float|fixed) [|]' "$trade_md") rows with ms, ARM926 instructions, PSNR and over8, and the plot; board frame 350: $arm_full instructions with --mode full, $arm_def by default"
  else
    fail "make tradeoff's script (QUICK=1) wrote a malformed $trade_md:"
    sed 's/^/       /' <<<"$problems"
  fi
else
  fail "make tradeoff's script (QUICK=1 tests/tradeoff.sh) failed:"
  tail -5 "$T/tradeoff-quick.err" | sed 's/^/       /'
fi

echo
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
