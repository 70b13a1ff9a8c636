# fixed16.sh: rt-fixed16, the cheaper fixed-point variant: repeatable, clean, close to float.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

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
  psnr=$(field psnr_db "$line")
  over8=$(field over8 "$line")
  psnrs="$psnrs $((10#$n)):${psnr}dB/${over8}"
  awk -v p="$psnr" -v o="$over8" 'BEGIN { exit !((p == "inf" || p >= 40) && o * 1000 <= 76800 * 3) }' ||
    bad="$bad frame $n vs float: $line (want >= 40 dB, over8 <= 3 per mille);"
done
if [ -z "$bad" ]; then
  pass "rt-fixed16: intro frames 100-1100 step 250 the same bytes twice and in the sanitized build (no numeric event); vs rt-float (frame:PSNR/over8 of 76800):$psnrs"
else
  fail "rt-fixed16:$bad"
fi
