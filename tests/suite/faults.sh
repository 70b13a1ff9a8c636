# faults.sh: interrupted, refused and hostile runs leave nothing broken.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).
# Each check here failed before its fix; FAULTS_RT=program runs the render checks on another
# build of rt (the sanitized ones too).
FR=${FAULTS_RT:-$B/rt-fixed}
FW=$T/faults
FTOP=$PWD
rm -rf "$FW" && mkdir -p "$FW"

# ---- an interrupted render leaves no temporary or half-written file --------------------------
# The render is stopped (SIGSTOP) while a temporary file of its output is in the folder, then
# sent the signal and let go: afterwards the folder holds finished images only. Every fwrite
# sleeps 20 ms first (tests/slow_write.c, preloaded), so the poll finds a file being written on
# any machine (a PPM is one fwrite, over in a millisecond).
gcc -std=c11 -O2 -shared -fPIC -o "$FW/slow_write.so" tests/slow_write.c -ldl
interrupt_run() { # signal extension: prints what is wrong, nothing when all is well
  local sig=$1 ext=$2 d pid tries f tmp=()
  for tries in 1 2 3 4 5 6 7 8; do
    d=$FW/int-$sig-$ext-$tries
    mkdir -p "$d"
    # a background job starts with SIGINT ignored: env gives it the default action back
    env --default-signal=INT LD_PRELOAD="$FW/slow_write.so" "$FR" render --frames all --size 640x480 -o "$d/f-%04d.$ext" 2>"$d.err" &
    pid=$!
    # poll without forking until a temporary file shows, then freeze the writer
    for _ in $(seq 200000); do
      tmp=("$d"/*.tmp-*)
      [ -e "${tmp[0]}" ] && break
      kill -0 $pid 2>/dev/null || break
    done
    kill -STOP $pid 2>/dev/null
    tmp=("$d"/*.tmp-*)
    if [ -e "${tmp[0]}" ]; then
      kill -"$sig" $pid
      kill -CONT $pid
      wait $pid
      local st=$?
      tmp=("$d"/*.tmp-*)
      [ -e "${tmp[0]}" ] && { echo "SIG$sig left ${tmp[*]##*/}"; return; }
      [ $st -eq $((128 + $(kill -l $sig))) ] || { echo "SIG$sig: exit $st, not ended by the signal"; return; }
      for f in "$d"/f-*."$ext"; do
        [ -e "$f" ] || continue # none finished before the signal
        $B/rt-cmp "$f" "$f" >/dev/null 2>&1 || { echo "SIG$sig left an unreadable ${f##*/}"; return; }
      done
      return
    fi
    kill -KILL $pid 2>/dev/null
    kill -CONT $pid 2>/dev/null
    wait $pid 2>/dev/null
  done
  echo "SIG$sig: never caught a $ext being written in 8 tries"
}
bad=""
for ext in png ppm; do
  for sig in TERM INT; do
    r=$(interrupt_run $sig $ext)
    [ -z "$r" ] || bad="$bad $ext: $r;"
  done
done
if [ -z "$bad" ]; then
  pass "faults: render --frames all stopped by SIGTERM or SIGINT in the middle of writing a PNG or a PPM: exit by the signal, no temporary file, every image left readable"
else
  fail "faults: interrupted render:$bad"
fi
# A file-size limit (ulimit -f) makes the write fail with one line and exit 1, no file left.
d=$FW/xfsz && mkdir -p "$d"
err=$(ulimit -f 100 && "$FR" render --size 320x240 -o "$d/x.ppm" 2>&1 >/dev/null)
st=$?
if [ $st -eq 1 ] && [ "$(wc -l <<<"$err")" -eq 1 ] && grep -q 'x.ppm: cannot write: File too large' <<<"$err" &&
   [ -z "$(ls "$d")" ]; then
  pass "faults: a render over the file-size limit fails with exit 1 and one line, no file left: $err"
else
  fail "faults: render over the file-size limit: exit $st, '$err', left: $(ls "$d" | tr '\n' ' ')"
fi

# ---- the boards under QEMU (platform/arm/qemu.sh, platform/m3/qemu.sh) --------------------------
# show's screen file name never reaches QEMU's monitor: a name with newlines runs no extra monitor
# command, and the frame is saved under that very name (one with a space too).
d=$FW/show && mkdir -p "$d"
weird="$d/a.ppm"$'\n'"screendump $d/injected.ppm"$'\n'"#.ppm"
platform/m3/qemu.sh show 425 "$weird" >"$d/weird.log" 2>&1
st1=$?
platform/m3/qemu.sh show 425 "$d/with space.ppm" >"$d/space.log" 2>&1
st2=$?
injected=$(find "$FW" -name injected.ppm)
if [ $st1 -eq 0 ] && [ $st2 -eq 0 ] && [ -z "$injected" ] && [ -s "$weird" ] && cmp -s "$weird" "$d/with space.ppm"; then
  pass "faults: m3 show saves the OLED under a name with newlines and a monitor command in it (no command run, no injected.ppm) and under a name with a space"
else
  fail "faults: m3 show with odd screen names: exit $st1 and $st2, injected: '$injected'; $(tail -q -n 2 "$d/weird.log" "$d/space.log" | tr '\n' ' ')"
fi
# A frame the board refuses fails at once: the guest's one error line on stderr, exit 2.
bad=""
for a in "1201" "abc" "--grid 2 0"; do
  s0=$(date +%s%N)
  # shellcheck disable=SC2086  # words on purpose
  err=$(platform/m3/qemu.sh show $a "$d/refused.ppm" 2>&1 >"$d/refused.out")
  st=$?
  ms=$((($(date +%s%N) - s0) / 1000000))
  if [ $st -ne 2 ] || [ $ms -gt 10000 ] || [ "$(wc -l <<<"$err")" -ne 1 ] || ! grep -q '^intro: error: ' <<<"$err" ||
     grep -q 'error' "$d/refused.out" || [ -e "$d/refused.ppm" ]; then
    bad="$bad show $a: exit $st after $ms ms, stderr '$err';"
  fi
done
if [ -z "$bad" ]; then
  pass "faults: m3 show of a refused frame (1201, abc, --grid 2 0) fails within 10 s with the board's one error line on stderr, exit 2"
else
  fail "faults: m3 show of a refused frame:$bad"
fi
# The boards' error lines go to standard error, their log to standard output; QEMU's notice
# "Timer with period zero, disabling" is not shown.
bad=""
while IFS='|' read -r script args want; do
  # shellcheck disable=SC2086
  "$script" $args >"$d/b.out" 2>"$d/b.err"
  st=$?
  if [ $st -ne 2 ] || [ "$(wc -l <"$d/b.err")" -ne 1 ] || ! grep -q "^intro: error: $want" "$d/b.err" ||
     grep -q error "$d/b.out" || ! grep -q '^ram: ' "$d/b.out"; then
    bad="$bad $script $args: exit $st, stderr '$(cat "$d/b.err")', stdout '$(tr '\n' ' ' <"$d/b.out")';"
  fi
done <<'CASES'
platform/arm/qemu.sh|frames --depth 9 0|--depth: expected
platform/arm/qemu.sh|bench 5 1 1|bench wants
platform/m3/qemu.sh|frames 1201|frame numbers
platform/m3/qemu.sh|bench --grid 16 0 0 1|--grid:
CASES
platform/m3/qemu.sh bench 0 0 1 >"$d/m3.out" 2>"$d/m3.err"
st=$?
if [ -z "$bad" ] && [ $st -eq 0 ] && [ ! -s "$d/m3.err" ] && grep -q '^frames=1 ' "$d/m3.out"; then
  pass "faults: the boards' errors go to stderr (4 cases, ARM926 and M3), their log to stdout; an M3 bench prints nothing on stderr"
else
  fail "faults: board errors:$bad m3 bench 0 0 1: exit $st, stderr '$(head -2 "$d/m3.err" | tr '\n' ' ')'"
fi
# A refused board run keeps the frames an earlier run wrote.
bad=""
for board in arm m3; do
  dir=build/qemu; [ $board = m3 ] && dir=build/qemu-m3
  platform/$board/qemu.sh frames 0 >/dev/null 2>&1 || bad="$bad $board frames 0 failed;"
  cp "$dir/fixed-0000.ppm" "$d/$board-0000.ppm" 2>/dev/null
  platform/$board/qemu.sh frames --depth 9 0 >/dev/null 2>&1 && bad="$bad $board --depth 9 accepted;"
  cmp -s "$dir/fixed-0000.ppm" "$d/$board-0000.ppm" || bad="$bad $board: frames --depth 9 0 removed fixed-0000.ppm;"
  platform/$board/qemu.sh frames 0 1.5 >/dev/null 2>&1 && bad="$bad $board 1.5 accepted;"
  cmp -s "$dir/fixed-0000.ppm" "$d/$board-0000.ppm" || bad="$bad $board: frames 0 1.5 removed fixed-0000.ppm;"
done
if [ -z "$bad" ]; then
  pass "faults: a refused board run (frames --depth 9 0, frames 0 1.5) keeps the frame an earlier run wrote (ARM926 and M3)"
else
  fail "faults: refused board runs:$bad"
fi

# ---- rt-scenec: never one output over another or over the scene; C that compiles -----------------
d=$FW/scenec && mkdir -p "$d"
cp scenes/demo.scene "$d/d.scene"
echo "keep me" >"$d/x.c"
bad=""
# case: expected message | arguments (in $d)
while IFS='|' read -r want args; do
  # shellcheck disable=SC2086  # words on purpose
  err=$(cd "$d" && "$FTOP/$B/rt-scenec" $args 2>&1 >/dev/null)
  st=$?
  if [ $st -ne 2 ] || [ "$(wc -l <<<"$err")" -ne 1 ] || ! grep -qF -- "$want" <<<"$err"; then
    bad="$bad rt-scenec $args: exit $st, '$err';"
  fi
done <<'CASES'
d.scene: the output would replace the scene file d.scene|d.scene -o x.c --effects d.scene
d.scene: the output would replace|d.scene -o d.scene
./d.scene: the output would replace|d.scene -o ./d.scene
--effects: x.c is the same file as -o x.c|d.scene -o x.c --effects x.c
--effects: ./x.c is the same file as -o x.c|d.scene -o x.c --effects ./x.c
--effects: y.h is the same file as -o ./y.h|d.scene -o ./y.h --effects y.h
--name: expected a C identifier that is not a keyword or reserved, got 'int'|d.scene -o y.c --name int
--name: expected a C identifier that is not a keyword or reserved, got 'while'|d.scene -o y.c --name=while
--name: expected a C identifier that is not a keyword or reserved, got '__x'|d.scene -o y.c --name __x
--name: expected a C identifier that is not a keyword or reserved, got 'NULL'|d.scene -o y.c --name NULL
CASES
cmp -s "$d/d.scene" scenes/demo.scene || bad="$bad the scene file was changed;"
[ "$(cat "$d/x.c")" = "keep me" ] || bad="$bad x.c was changed or removed;"
[ -z "$(ls "$d" | grep -v '^d.scene$\|^x.c$')" ] || bad="$bad left: $(ls "$d" | tr '\n' ' ');"
# a scene whose path holds */, or *??/ and a newline (a trigraph, a line splice, then /),
# compiles into C that compiles
odd1="$d/a*/b.scene" odd2="$d/a*??/"$'\n'"/b.scene"
mkdir -p "${odd1%/*}" "${odd2%/*}"
for s in "$odd1" "$odd2"; do
  cp scenes/demo.scene "$s"
  if ! $B/rt-scenec "$s" -o "$d/out.c" --effects "$d/out.h" --name scn_odd 2>"$d/sc.err" ||
     ! printf '#include "%s"\n' "$PWD/$d/out.h" | cat - "$d/out.c" >"$d/both.c" ||
     ! gcc -std=c11 -Wall -Werror -fsyntax-only -Ifixed -Isrc/core -Isrc/scene -DREAL_FIXED=1 -DFX_COUNT_EVENTS=0 \
       -isystem build/deps/libfixmath/libfixmath "$d/both.c" 2>>"$d/sc.err"; then
    bad="$bad $(printf %q "$s"): $(head -3 "$d/sc.err" | tr '\n' ' ');"
  fi
done
if [ -z "$bad" ]; then
  pass "faults: rt-scenec refuses an output that is the scene or the other output (by name or by path) and a keyword or reserved --name, changing nothing; scenes under a*/ and a*??/<newline>/ compile into C that compiles"
else
  fail "faults: rt-scenec:$bad"
fi

# ---- rt-edges refuses a time past the scene's end, as render does ------------------------------
err=$($B/rt-edges --scene scenes/demo.scene --time 3600 2>&1 >/dev/null)
st=$?
end=$($B/rt-edges --scene scenes/demo.scene --time 24 --size 32x24 2>&1 | sed -n 's/^time=//p')
if [ $st -eq 2 ] && [ "$err" = "rt-edges: --time: 3600.000 s is past the end of scenes/demo.scene (24.000 s)" ] &&
   [ "$end" = 24.000 ]; then
  pass "faults: rt-edges --time 3600 on the 24 s demo scene: exit 2, '$err'; --time 24 is measured"
else
  fail "faults: rt-edges past the end: exit $st, '$err'; at 24 s: '$end'"
fi

# ---- rt-cmp --oled: an input at most 1024x1024 pixels, whose picture rt-cmp reads back ----------
d=$FW/oled && mkdir -p "$d"
{ printf 'P6\n1025 1024\n255\n'; head -c $((1025 * 1024 * 3)) /dev/zero; } >"$d/big.ppm"
{ printf 'P6\n1024 1024\n255\n'; head -c $((1024 * 1024 * 3)) /dev/zero; } >"$d/max.ppm"
err=$($B/rt-cmp --oled "$d/big.ppm" "$d/big-oled.ppm" 2>&1 >/dev/null)
st=$?
$B/rt-cmp --oled "$d/max.ppm" "$d/max-oled.ppm" 2>"$d/max.err"
st2=$?
back=$($B/rt-cmp "$d/max-oled.ppm" "$d/max-oled.ppm" 2>&1)
if [ $st -eq 2 ] && [ "$(wc -l <<<"$err")" -eq 1 ] && grep -q 'big.ppm: too large for --oled (1025x1024' <<<"$err" &&
   [ ! -e "$d/big-oled.ppm" ] && [ $st2 -eq 0 ] && grep -q 'pixels=16777216$' <<<"$back"; then
  pass "faults: rt-cmp --oled refuses a 1025x1024 input (exit 2: $err) and turns a 1024x1024 one into a 4096x4096 picture it reads back"
else
  fail "faults: rt-cmp --oled size bound: 1025x1024: exit $st, '$err'; 1024x1024: exit $st2 $(cat "$d/max.err"), read back: $back"
fi
rm -f "$d"/*.ppm

# ---- the in-range bounds (docs/numerics.md) at the scene cube's edges -----------------------------
# Scenes with the camera, lights, spheres and planes at and near +-4096, radii 1/128 and 2048,
# lights of intensity 16 and lights on a sphere's normal (tests/edge_scenes.awk, a fixed seed):
# in the event-counting build every _in operation is the checked one, so a bound that does not
# hold there is an overflow or domain event; and the release build, which forms them unchecked,
# must give the same bytes (full mode: every pixel, every ray; and the default adaptive mode).
d=$FW/edge && mkdir -p "$d"
awk -v n="${FAULTS_EDGE_SCENES:-100}" -v seed=31 -v dir="$d" -f tests/edge_scenes.awk
bad="" nsc=0
for s in "$d"/edge-*.scene; do
  for mode in full adaptive; do
    out=$($B/san-fixed/rt render --scene "$s" --size 32x24 --mode "$mode" --stats -o "$d/san.ppm" 2>&1)
    st=$?
    $B/rt-fixed render --scene "$s" --size 32x24 --mode "$mode" -o "$d/rel.ppm" 2>/dev/null
    if [ $st -ne 0 ] || ! grep -q '^fx_overflow=0$' <<<"$out" || ! grep -q '^fx_domain=0$' <<<"$out"; then
      bad="$bad ${s##*/} $mode: exit $st $(grep -E '^fx_(overflow|domain)=|error' <<<"$out" | head -3 | tr '\n' ' ');"
    elif ! cmp -s "$d/san.ppm" "$d/rel.ppm"; then
      bad="$bad ${s##*/} $mode: the release build's frame differs;"
    fi
  done
  nsc=$((nsc + 1))
done
if [ -z "$bad" ] && [ $nsc -ge 1 ]; then
  pass "faults: $nsc scenes at the scene cube's edges (tests/edge_scenes.awk) render with no overflow or domain event in san-fixed, full and adaptive, and the release build gives the same bytes"
else
  fail "faults: scenes at the cube's edges:$bad"
fi

# ---- the sanitized player's leak check under Xvfb: libdbus' leak suppressed, fixray's not ----------
# (tests/lsan.supp says why SDL stays off OpenGL there)
d=$FW/lsan && mkdir -p "$d"
lsan_env=(env LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp SDL_RENDER_DRIVER=software SDL_FRAMEBUFFER_ACCELERATION=0)
bad=""
for real in fixed float; do
  "${lsan_env[@]}" timeout 120 xvfb-run -a -s "-screen 0 1024x768x24" $B/san-$real/rt play --frames 5 --size 160x120 \
    >"$d/play-$real.log" 2>&1 || bad="$bad san-$real play: exit $?: $(grep -E 'leak of|SUMMARY|ERROR' "$d/play-$real.log" | head -3 | tr '\n' ' ');"
done
# the planted leak, next to SDL's window and renderer as play makes them: reported alone
if gcc -std=c11 -Wall -Wextra -Werror -g -O1 -fsanitize=address,undefined -fno-omit-frame-pointer \
     $(pkg-config --cflags sdl2) tests/lsan_plant.c -o "$d/lsan_plant" $(pkg-config --libs sdl2) 2>"$d/plant.log"; then
  "${lsan_env[@]}" timeout 120 xvfb-run -a -s "-screen 0 1024x768x24" "$d/lsan_plant" >>"$d/plant.log" 2>&1
  st=$?
  if [ $st -eq 0 ] || [ "$(grep -c 'leak of' "$d/plant.log")" -ne 1 ] || ! grep -q 'Direct leak of 4242 byte' "$d/plant.log" ||
     ! grep -q 'in plant_leak tests/lsan_plant.c' "$d/plant.log"; then
    bad="$bad the planted leak: exit $st, $(grep -E 'leak of|SUMMARY' "$d/plant.log" | tr '\n' ' ');"
  fi
else
  bad="$bad tests/lsan_plant.c does not build: $(head -2 "$d/plant.log" | tr '\n' ' ');"
fi
if [ -z "$bad" ]; then
  pass "faults: san-fixed and san-float play under Xvfb pass their leak check with tests/lsan.supp (libdbus' 1,032 bytes suppressed); a leak planted next to SDL's (4,242 bytes, tests/lsan_plant.c) is still reported, alone"
else
  fail "faults: leak check of the sanitized player:$bad"
fi

# ---- the differential oracle (make fuzz runs it on the scene fuzzer's corpora) -----------------------
# The scene fuzzer's seeds, the kept inputs among them (tests/fuzz.sh --smoke, earlier in make
# test, gathers them): release rt-fixed and the event-counting build give the same bytes.
if out=$(tests/fuzz_oracle.sh build/fuzz/seeds 2>&1); then
  pass "$out"
else
  fail "$(tr '\n' ' ' <<<"$out")"
fi
# The new fuzzers' findings, through the programs: a control character in an option makes no
# second line, and "P6" without a blank after it is not an image.
d=$FW/found && mkdir -p "$d"
printf 'P62 1\n255\n\nabcdef' >"$d/p62.ppm"
err1=$($B/rt-fixed render $'--fram\nes' 2>&1 >/dev/null)
st1=$?
err2=$($B/rt-scenec $'--na\tme' 2>&1 >/dev/null)
st2=$?
err3=$($B/rt-cmp "$d/p62.ppm" "$d/p62.ppm" 2>&1 >/dev/null)
st3=$?
if [ $st1 -eq 2 ] && [ "$(wc -l <<<"$err1")" -eq 1 ] && [ "$err1" = "rt-fixed: --fram?es: unknown option (see rt-fixed --help)" ] &&
   [ $st2 -eq 2 ] && [ "$(wc -l <<<"$err2")" -eq 1 ] && grep -q '^rt-scenec: --na?me: unknown option' <<<"$err2" &&
   [ $st3 -eq 2 ] && grep -q 'p62.ppm: not a PNG or binary PPM (P6) image' <<<"$err3"; then
  pass "faults: an option holding a newline or a tab gets one line ($err1); 'P62 1 255' is not a PPM"
else
  fail "faults: fuzzers' findings: exit $st1 '$err1'; exit $st2 '$err2'; exit $st3 '$err3'"
fi
