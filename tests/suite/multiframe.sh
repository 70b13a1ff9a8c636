# multiframe.sh: several frames in one process: --frames, --step, -o patterns, --checksum.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

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
