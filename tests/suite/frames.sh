# frames.sh: frames of the demo scene: fixed vs float, determinism, the sanitized tracer, rt-cmp.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

# ---- frames: fixed vs float on the demo scene (scenes/demo.scene) --------------------------------------------------
# Full mode (every pixel traced, every ray cast): PSNR >= 40 dB and at most 0.5% of pixels with a
# channel off by more than 8. Adaptive mode (the default): PSNR >= 38 dB.
cmp_frames() { # label fixed.png float.png min-psnr max-over8-per-mille
  local line psnr over8 pixels
  line=$($B/rt-cmp "$2" "$3" --diff "${2%.png}-diff.png")
  psnr=$(field psnr_db "$line")
  over8=$(field over8 "$line")
  pixels=$(field pixels "$line")
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
  ov=$(kv fx_overflow "$out")
  dm=$(kv fx_domain "$out")
  if [ $rc -eq 0 ] && [ ! -s "$T/san-$real.err" -o "$(grep -c 'runtime error\|Sanitizer' "$T/san-$real.err")" = 0 ] &&
     [ "$ov" = 0 ] && [ "$dm" = 0 ]; then
    pass "sanitized $real render: no ASan/UBSan report, fx_overflow=$ov fx_domain=$dm"
  else
    fail "sanitized $real render: exit $rc, fx_overflow=$ov fx_domain=$dm"
    head -20 "$T/san-$real.err" | sed 's/^/       /'
  fi
done

# ---- rt-cmp ---------------------------------------------------------------------------------------
line=$($B/rt-cmp "$T/det1-fixed.png" "$T/det1-fixed.ppm")
if [ "$line" = "psnr_db=inf max_abs=0 differing=0 over8=0 pixels=30000" ]; then
  pass "rt-cmp: PNG and PPM of the same frame are identical ($line)"
else
  fail "rt-cmp on identical images printed: $line"
fi
if [ -s "$T/fixed-full-6-diff.png" ]; then pass "rt-cmp --diff writes the difference picture"; else fail "rt-cmp --diff wrote nothing"; fi
