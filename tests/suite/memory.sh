# memory.sh: long runs and memory: the soak (every intro frame, twice) and valgrind memcheck.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

# ---- soak: every frame of the intro, twice, both builds (tests/soak.sh; SOAK_STEP=N for a subset) -
while IFS= read -r line; do
  case $line in
    *"identical passes, no growth") pass "$line" ;;
    *) fail "$line" ;;
  esac
done < <(tests/soak.sh "${SOAK_STEP:-1}" 320x240 2>&1)

# ---- valgrind memcheck: intro frames rendered and written by both -O2 builds -------------------
# the float build reads the intro from its scene file, the fixed one uses the compiled-in copy
for real in fixed float; do
  scene=(); [ $real = float ] && scene=(--scene scenes/intro.scene)
  if valgrind -q --error-exitcode=99 --leak-check=full --show-leak-kinds=definite,indirect,possible \
       --errors-for-leak-kinds=definite,indirect,possible $B/rt-$real render "${scene[@]}" \
       --frames 0-1200 --step 400 --size 160x120 -o "$T/vg-$real-%04d.png" --stats >/dev/null 2>"$T/vg-$real.log" &&
     [ "$(ls "$T"/vg-$real-*.png | wc -l)" = 4 ] && ! grep -q '^==' "$T/vg-$real.log"; then
    pass "valgrind memcheck: rt-$real renders and writes 4 intro frames (0-1200 step 400, 160x120) with no error and no leak"
  else
    fail "valgrind memcheck on rt-$real (see $T/vg-$real.log)"
    grep '^==' "$T/vg-$real.log" | head -20 | sed 's/^/       /'
  fi
done
