# sampling.sh: adaptive and probe subsampling: --stats, --show-samples, probe mode's bounds, highlights between corners, rt-edges' bound.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

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
samples=$(kv samples_traced "$stats")
sq8=$(kv squares_8 "$stats")
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
changed=$(field differing "$line")
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
samples=$(kv samples_traced "$($B/rt-fixed render $PROBE_AT --threads 1 --size 320x240 --stats -o "$T/probe-ad.ppm" 2>/dev/null)")
stats=$($B/rt-fixed render $PROBE_AT --mode probe --threads 1 --size 320x240 --stats -o "$T/probe.ppm" 2>/dev/null)
shaded=$(kv samples_traced "$stats")
probes=$(kv probes "$stats")
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
    tot=$((tot + $(kv samples_traced "$st")))
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

# ---- rt-edges: the bound on adaptive subsampling (tests/bench_subsample.sh prints it) -----------
# A lone plane seen from above (no horizon), no texture, no highlight, one light: no edge at all,
# so only the grid's corners must be traced (41 x 31 at 320x240, grid 8). The demo scene: edges,
# and the bound it prints is pixels / points that must be traced.
printf '%s\n' "camera eye 0 6 1 at 0 0 0" "light l pos 0 5 0 color 1 1 1" "material m specular 0" \
  "plane p material m normal 0 1 0 offset 0" >"$T/flat.scene"
flat=$($B/rt-edges --scene "$T/flat.scene" --size 320x240 --time 0)
demo=$($B/rt-edges --scene=scenes/demo.scene --size=160x120 --time=4)
if [ "$(kv edge_pixels "$flat")" = 0 ] && [ "$(kv must_trace "$flat")" = 1271 ] &&
   [ "$(kv edge_pixels "$demo")" -gt 1000 ] && [ "$(kv must_trace "$demo")" -ge "$(kv edge_pixels "$demo")" ] &&
   awk -v b="$(kv bound_x_samples "$demo")" -v m="$(kv must_trace "$demo")" 'BEGIN { exit !(b > 1 && (19200 / m - b) ^ 2 < 0.0001) }'; then
  pass "rt-edges: a flat plane has no edge (1271 points: the 8x8 grid's corners); the demo scene at 160x120 has $(kv edge_pixels "$demo") edge pixels, bound x_samples $(kv bound_x_samples "$demo")"
else
  fail "rt-edges: flat: $(tr '\n' ' ' <<<"$flat"); demo: $(tr '\n' ' ' <<<"$demo")"
fi
