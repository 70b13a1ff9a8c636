# scene_errors.sh: bad scene files (tests/bad_scenes.txt), the limits of items, rt-scenec's errors and failed writes.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

# ---- bad scene files: the table in tests/bad_scenes.txt --------------------------------------
R=$B/rt-fixed
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
