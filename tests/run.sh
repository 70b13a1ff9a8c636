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

# ---- unit tests (cmocka), both builds, under AddressSanitizer + UBSan ------------------------
for v in san-fixed san-float; do
  for t in test_numeric test_shapes test_noise test_subsample test_scene test_stability; do
    if "$B/$v/$t" >"$T/$v-$t.log" 2>&1; then
      pass "$v/$t ($(grep -c '^\[       OK \]' "$T/$v-$t.log") cases)"
      grep -E '^(noise|fbm|sphere|far|numeric|interpolation|object|shadow|reflected|min_contrib|plane|normalise|  )' "$T/$v-$t.log" | sed 's/^/       /'
    else
      fail "$v/$t"
      sed 's/^/       /' "$T/$v-$t.log" | tail -30
    fi
  done
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
stats=$($B/rt-fixed render $DEMO --size 320x240 --time 3 --stats -o "$T/stats-ad.ppm" 2>/dev/null)
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
# --show-samples paints the traced points white: as many changed pixels as points traced, at most
$B/rt-fixed render $DEMO --size 320x240 --time 3 --show-samples -o "$T/dots.ppm" 2>/dev/null
line=$($B/rt-cmp "$T/dots.ppm" "$T/stats-ad.ppm")
changed=$(sed -n 's/.*differing=\([0-9]*\).*/\1/p' <<<"$line")
if [ -n "$changed" ] && [ "$changed" -le "$samples" ] && [ $((changed * 10)) -ge $((samples * 9)) ]; then
  pass "--show-samples marks $changed pixels for $samples traced points"
else
  fail "--show-samples changed '$changed' pixels for $samples traced points"
fi
stats=$($B/rt-float render $DEMO --size 80x60 --depth 0 --stats -o "$T/stats0.png" 2>/dev/null)
if grep -q '^rays_reflect=0$' <<<"$stats" && grep -q '^rays_refract=0$' <<<"$stats" && grep -q '^depth=0$' <<<"$stats"; then
  pass "--depth 0 casts no reflected or refracted ray"
else
  fail "--depth 0 still casts secondary rays"
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
expect_error 2 "unknown option" $R render $DEMO --bogus
expect_error 2 "unknown command" $R draw
expect_error 2 "expected WxH" $R render $DEMO --size 0x10 -o "$T/x.png"
expect_error 2 "expected WxH" $R render $DEMO --size 640 -o "$T/x.png"
expect_error 2 "expected WxH" $R render $DEMO --size 5000x100 -o "$T/x.png"
expect_error 2 "expected WxH" $R render $DEMO --size -3x4 -o "$T/x.png"
expect_error 2 "expected seconds" $R render $DEMO --time -1 -o "$T/x.png"
expect_error 2 "expected seconds" $R render $DEMO --time 1.2345 -o "$T/x.png"
expect_error 2 "expected seconds" $R render $DEMO --time abc -o "$T/x.png"
expect_error 2 "expected a frame number" $R render $DEMO --frame 1e3 -o "$T/x.png"
expect_error 2 "expected a recursion limit" $R render $DEMO --depth 9 -o "$T/x.png"
expect_error 2 "either --time or --frame" $R render $DEMO --time 1 --frame 2 -o "$T/x.png"
expect_error 2 "expected full or adaptive" $R render $DEMO --mode fast -o "$T/x.png"
expect_error 2 "expected a square size" $R render $DEMO --grid 3 -o "$T/x.png"
expect_error 2 "expected a square size" $R render $DEMO --grid 32 -o "$T/x.png"
expect_error 2 "expected a square size" $R render $DEMO --grid 1 -o "$T/x.png"
expect_error 2 "expected a number in 0..1" $R render $DEMO --threshold 1.5 -o "$T/x.png"
expect_error 2 "expected a number in 0..1" $R render $DEMO --threshold -0.1 -o "$T/x.png"
expect_error 2 "expected a number in 0..1" $R render $DEMO --min-contrib 0.00001 -o "$T/x.png"
expect_error 2 "expected a number in 0..1" $R render $DEMO --min-contrib abc -o "$T/x.png"
expect_error 2 "needs a value" $R render $DEMO --grid
expect_error 2 "needs a value" $R render $DEMO -o
expect_error 2 ".png or .ppm" $R render $DEMO -o "$T/x.jpg"
expect_error 1 "cannot write" $R render $DEMO --size 8x8 -o "$T/no/such/dir/x.png"
mkdir -p "$T/adir.png"
expect_error 1 "cannot write" $R render $DEMO --size 8x8 -o "$T/adir.png"
if ls "$T"/adir.png.tmp-* >/dev/null 2>&1; then fail "a temporary file was left behind"; else pass "no temporary file left behind after a failed write"; fi
printf 'P6\n2 2\n255\nabc' >"$T/short.ppm"
expect_error 2 "truncated" $B/rt-cmp "$T/short.ppm" "$T/det1-fixed.ppm"
expect_error 2 "cannot open" $B/rt-cmp "$T/missing.png" "$T/det1-fixed.ppm"
echo "not an image" >"$T/text.png"
expect_error 2 "bad PNG\|not a PNG" $B/rt-cmp "$T/text.png" "$T/det1-fixed.ppm"
expect_error 2 "sizes differ" $B/rt-cmp "$T/stats.png" "$T/det1-fixed.png"

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
expect_error 2 "no/such.scene: cannot open" $R render --scene "$T/no/such.scene"
expect_error 2 "cannot read" $R render --scene "$T"
head -c 1100000 /dev/zero >"$BAD/huge.scene"
expect_error 2 "larger than 1048576 bytes" $R render --scene "$BAD/huge.scene"
expect_error 2 "past the end of scenes/demo.scene" $R render $DEMO --time 30 -o "$T/x.png"
expect_error 2 "past the last frame of scenes/demo.scene (600 at 25 fps)" $R render $DEMO --frame 601 -o "$T/x.png"
expect_error 2 "expected auto or all" $R render --effects some -o "$T/x.png"
# rt-scenec: the same messages; never a half-written output
expect_error 2 "case08.scene:2:19: undefined material 'glas'" $B/rt-scenec "$BAD/case08.scene" -o "$T/sc.c"
expect_error 2 "cannot open" $B/rt-scenec "$T/none.scene" -o "$T/sc.c"
expect_error 2 "no output given" $B/rt-scenec scenes/demo.scene
expect_error 2 "not a C identifier" $B/rt-scenec scenes/demo.scene -o "$T/sc.c" --name 9lives
expect_error 1 "cannot write" $B/rt-scenec scenes/demo.scene -o "$T/no/such/dir/sc.c"
expect_error 1 "sc.h: cannot write" $B/rt-scenec scenes/demo.scene -o "$T/sc.c" --effects "$T/no/such/dir/sc.h"
if ls "$T"/no/such/dir/sc.c* "$T"/sc.c >/dev/null 2>&1; then fail "rt-scenec left an output behind after errors"; else pass "rt-scenec leaves no output behind after errors"; fi

# ---- the ARM926 images under QEMU (tests/arm.sh, tests/arm_check.sh) ------------------------
tests/arm.sh >"$T/arm.log" 2>&1
arm_status=$?
arm_failed=$failed
while IFS= read -r line; do
  case "$line" in
    "ok   "*) pass "${line#ok   }" ;;
    "FAIL "*) fail "${line#FAIL }" ;;
    *) echo "       $line" ;;
  esac
done <"$T/arm.log"
[ "$arm_status" -eq 0 ] || [ "$failed" -gt "$arm_failed" ] || fail "tests/arm.sh exited with status $arm_status"

echo
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
