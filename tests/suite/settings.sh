# settings.sh: render settings: --depth, --octaves, --footprint (against a supersampled reference).
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

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
