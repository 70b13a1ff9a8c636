#!/usr/bin/env bash
# play.sh: the desktop player under Xvfb and multi-threaded rendering: screenshots equal headless frames, every thread count gives the same bytes, the player's size.
#
# Expects make all. Prints `ok ...` / `FAIL ...` lines (tests/run.sh counts them); exits 1 if any
# check fails.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh

T=$B/test/play
rm -rf "$T" && mkdir -p "$T"
SIZE_LIMIT=65536

# An X server of our own for the window (Xvfb, through xvfb-run).
if ! command -v xvfb-run >/dev/null; then
  fail "play: xvfb-run is missing (./setup.sh --test installs xvfb)"
  exit 1
fi
xrun() { xvfb-run -a -s "-screen 0 1024x768x24" "$@"; }

# No display: one line and exit status 1, not an invisible player.
for real in fixed float; do
  msg=$(env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER "$B/rt-$real" play --frames 2 2>&1)
  st=$?
  if [ $st -eq 1 ] && [ "$(wc -l <<<"$msg")" -eq 1 ] && grep -q "no display to play on" <<<"$msg"; then
    pass "rt-$real play without a display: exit 1, one line: $msg"
  else
    fail "rt-$real play without a display: exit $st: $msg"
  fi
done

# Scripted play: N frames, one frame period each, then the last frame shown as a screenshot;
# it must equal the headless render of that frame (frame N - 1) at the same size.
for real in fixed float; do
  for case in "12 320x240 1" "30 160x120 2" "5 200x150 3"; do
    read -r n size threads <<<"$case"
    shot=$T/play-$real-$n.png
    if xrun "$B/rt-$real" play --frames "$n" --size "$size" --threads "$threads" --screenshot "$shot" \
        >"$T/play-$real-$n.log" 2>&1; then
      "$B/rt-$real" render --frame $((n - 1)) --size "$size" -o "$T/render-$real-$n.png" 2>/dev/null
      line=$("$B/rt-cmp" "$shot" "$T/render-$real-$n.png" 2>&1)
      if grep -q 'differing=0 ' <<<"$line"; then
        pass "rt-$real play --frames $n --size $size --threads $threads under Xvfb: screenshot = render --frame $((n - 1)) ($(grep -o '[0-9.]* fps shown' "$T/play-$real-$n.log"))"
      else
        fail "rt-$real play --frames $n: screenshot differs from render --frame $((n - 1)): $line"
      fi
    else
      fail "rt-$real play --frames $n --size $size under Xvfb: $(tail -2 "$T/play-$real-$n.log" | tr '\n' ' ')"
    fi
  done
done

# Render settings reach the player: frame 425 (day: noise textures) with a cap on noise octaves
# and other settings equals render's with the same settings, and differs from the default frame.
S="--octaves 1 --grid 4 --threshold 0.03 --depth 2"
for real in fixed float; do
  shot=$T/play-set-$real.png
  # shellcheck disable=SC2086  # settings are words on purpose
  if xrun "$B/rt-$real" play --frames 426 --size 160x120 --threads 2 $S --screenshot "$shot" \
      >"$T/play-set-$real.log" 2>&1 &&
     "$B/rt-$real" render --frame 425 --size 160x120 $S -o "$T/render-set-$real.png" 2>/dev/null &&
     "$B/rt-$real" render --frame 425 --size 160x120 -o "$T/render-def-$real.png" 2>/dev/null; then
    same=$("$B/rt-cmp" "$shot" "$T/render-set-$real.png" 2>&1)
    other=$("$B/rt-cmp" "$shot" "$T/render-def-$real.png" 2>&1)
    if grep -q 'differing=0 ' <<<"$same" && ! grep -q 'differing=0 ' <<<"$other"; then
      pass "rt-$real play $S: screenshot = render --frame 425 $S, not the default frame ($other)"
    else
      fail "rt-$real play $S: against render with them: $same; against the default: $other"
    fi
  else
    fail "rt-$real play $S under Xvfb: $(tail -2 "$T/play-set-$real.log" | tr '\n' ' ')"
  fi
done

# The intro player (build/intro-*) shows the same frames.
for real in fixed float; do
  shot=$T/intro-$real.png
  if xrun "$B/intro-$real" --frames 8 --size 320x240 --screenshot "$shot" >"$T/intro-$real.log" 2>&1 &&
      "$B/rt-$real" render --frame 7 -o "$T/render-$real-7.png" 2>/dev/null &&
      grep -q 'differing=0 ' <<<"$("$B/rt-cmp" "$shot" "$T/render-$real-7.png" 2>&1)"; then
    pass "build/intro-$real --frames 8 under Xvfb: screenshot = render --frame 7"
  else
    fail "build/intro-$real --frames 8: $(tail -2 "$T/intro-$real.log" | tr '\n' ' ')"
  fi
done

# The fixed player at 24 s (frame 600: noise textures, the two-tone floor's texture squares, the
# mirror cull): the size-built player still renders what rt-fixed renders.
shot=$T/intro-fixed-600.png
if xrun "$B/intro-fixed" --frames 601 --size 320x240 --screenshot "$shot" >"$T/intro-fixed-600.log" 2>&1 &&
    "$B/rt-fixed" render --frame 600 -o "$T/render-fixed-600.png" 2>/dev/null &&
    grep -q 'differing=0 ' <<<"$("$B/rt-cmp" "$shot" "$T/render-fixed-600.png" 2>&1)"; then
  pass "build/intro-fixed --frames 601 under Xvfb: screenshot = render --frame 600"
else
  fail "build/intro-fixed --frames 601: screenshot differs from render --frame 600: $(tail -2 "$T/intro-fixed-600.log" | tr '\n' ' ')"
fi

# One option table (src/app/cli.c): the intro player and `rt-* play` take the same command line,
# here in the --opt=value form with a size written WXH, and show the same frame.
for real in fixed float; do
  args=(--size=160X120 --threads=2 --frames=3)
  if xrun "$B/intro-$real" "${args[@]}" --screenshot="$T/eq-intro-$real.png" >"$T/eq-intro-$real.log" 2>&1 &&
     xrun "$B/rt-$real" play "${args[@]}" --screenshot="$T/eq-play-$real.png" >"$T/eq-play-$real.log" 2>&1 &&
     cmp -s "$T/eq-intro-$real.png" "$T/eq-play-$real.png"; then
    pass "intro-$real and rt-$real play ${args[*]}: the same command line, the same screenshot"
  else
    fail "intro-$real vs rt-$real play ${args[*]}: $(tail -1 "$T/eq-intro-$real.log") / $(tail -1 "$T/eq-play-$real.log")"
  fi
done

# Threads: 1 thread and several give the same bytes, both builds, both modes, several frames.
for real in fixed float; do
  bad=""
  for t in 3 17 26 36 45; do
    for mode in adaptive full; do
      rm -f "$T/t1.ppm"
      "$B/rt-$real" render --time $t --size 256x192 --mode $mode --threads 1 -o "$T/t1.ppm" 2>/dev/null ||
        bad="$bad t=$t/$mode/1:failed"
      for th in 2 3 7; do
        rm -f "$T/tn.ppm"
        "$B/rt-$real" render --time $t --size 256x192 --mode $mode --threads $th -o "$T/tn.ppm" 2>/dev/null ||
          bad="$bad t=$t/$mode/$th:failed"
        [ -s "$T/t1.ppm" ] && cmp -s "$T/t1.ppm" "$T/tn.ppm" || bad="$bad t=$t/$mode/$th"
      done
    done
  done
  [ -z "$bad" ] && pass "rt-$real render: 2, 3 and 7 threads give the bytes of 1 thread (5 intro times, both modes)" ||
    fail "rt-$real render: threads change the picture:$bad"
done
# and under the sanitizers, with the traced-point map (at 44 s, probe mode: points probed, and
# points on the mirror floor that take their local parts, some on the edges between bands)
for real in fixed float; do
  for set in "--time 36" "--time 44 --mode probe"; do
    rm -f "$T/s1.ppm" "$T/s4.ppm"
    # shellcheck disable=SC2086 # the settings are words
    "$B/san-$real/rt" render $set --size 96x72 --threads 1 --show-samples -o "$T/s1.ppm" 2>"$T/s1.log" &&
      "$B/san-$real/rt" render $set --size 96x72 --threads 4 --show-samples -o "$T/s4.ppm" 2>"$T/s4.log" &&
      cmp -s "$T/s1.ppm" "$T/s4.ppm" &&
      pass "san-$real ($set): 4 threads with --show-samples = 1 thread, no sanitizer report" ||
      fail "san-$real ($set): 4 threads with --show-samples: $(cat "$T/s1.log" "$T/s4.log" | tail -3 | tr '\n' ' ')"
  done
done

# The player program, stripped, within the original intro's 64 kB (SDL2 linked dynamically).
for real in fixed float; do
  strip -o "$T/player-$real" "$B/intro-$real"
  size=$(stat -c %s "$T/player-$real")
  [ "$size" -le $SIZE_LIMIT ] && pass "player build/intro-$real stripped: $size bytes <= $SIZE_LIMIT" ||
    fail "player build/intro-$real stripped: $size bytes > $SIZE_LIMIT"
done
lib_status
