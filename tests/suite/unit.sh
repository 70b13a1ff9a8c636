# unit.sh: the unit tests (cmocka) of both builds under ASan + UBSan, and of the fixed-point format in rt-fixed's and rt-fixed16's.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

# The test programs run side by side (spawn), each with its log in $T/<build>-<test>.log, and are
# reported below in this order.
for v in san-fixed san-float; do
  for t in test_numeric test_shapes test_noise test_subsample test_scene test_stability test_optics; do
    spawn "$T/$v-$t.log" "$B/$v/$t"
  done
done
for v in san-fixed san-fixed16; do spawn "$T/$v-test_format.log" "$B/$v/test_format"; done
wait

# ---- unit tests (cmocka), both builds, under AddressSanitizer + UBSan ------------------------
for v in san-fixed san-float; do
  for t in test_numeric test_shapes test_noise test_subsample test_scene test_stability test_optics; do
    if spawned_ok "$T/$v-$t.log"; then
      pass "$v/$t ($(grep -c '^\[       OK \]' "$T/$v-$t.log") cases)"
      grep -E '^(noise|fbm|sphere|far|numeric|interpolation|object|shadow|reflected|min_contrib|plane|normalise|  )' "$T/$v-$t.log" | sed 's/^/       /'
    else
      fail "$v/$t"
      sed 's/^/       /' "$T/$v-$t.log" | tail -30
    fi
  done
done

# The fixed-point format itself: U_ONE and friends follow FX_UNIT_FRAC (30 in rt-fixed, 16 in
# rt-fixed16), and each format's unit-vector operations stay within a few of its own steps.
for vf in san-fixed:30 san-fixed16:16; do
  v=${vf%:*} frac=${vf#*:}
  if spawned_ok "$T/$v-test_format.log" && grep -q "^  unit_frac=$frac U_ONE=$((1 << frac))\$" "$T/$v-test_format.log"; then
    pass "$v/test_format: unit has $frac fraction bits ($(grep -c '^\[       OK \]' "$T/$v-test_format.log") cases)"
    grep '^  ' "$T/$v-test_format.log" | sed 's/^/     /'
  else
    fail "$v/test_format (want unit_frac=$frac)"
    sed 's/^/       /' "$T/$v-test_format.log" | tail -30
  fi
done
