# numerics.sh: numerically hard scenes (tests/hard/) and each texture's reach.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

# ---- numerically hard scenes (tests/hard/*.scene; docs/numerics.md) ----------------------------
while read -r line; do
  case $line in
    ok*) pass "${line#ok   }" ;;
    *) fail "${line#FAIL }" ;;
  esac
done < <(tests/hard_scenes.sh 2>&1)

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
  awk -v p="$(field psnr_db "$line")" 'BEGIN { exit !(p == "inf" || p >= 40) }' || bad="$bad scale $scale: $line;"
done
[ -z "$bad" ] && pass "checker plane at scale 1 and 1.5625 out to the scene's edge: no numeric event, fixed vs float $line" ||
  fail "checker plane scales:$bad"
