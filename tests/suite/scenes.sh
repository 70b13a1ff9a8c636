# scenes.sh: the example scenes: fixed vs float, derived effects, compiled scene programs, effects regressions.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

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
    psnr=$(field psnr_db "$line")
    awk -v p="$psnr" 'BEGIN { exit !(p == "inf" || p >= 38) }' || bad="$bad psnr $psnr dB at $t s;"
    worst=$(awk -v a="$worst" -v p="$psnr" 'BEGIN { if (p == "inf") p = 999; print (a == "" || p < a) ? p : a }')
    for out in "$sx" "$sf"; do
      fx=$(kv effects "$out")
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
