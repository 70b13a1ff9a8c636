# platforms.sh: the scripts of the platforms: the desktop player (tests/play.sh), the ARM926 (tests/arm.sh), the Cortex-M3 (tests/m3.sh), the Cortex-M0 (tests/m0.sh), the boards' cycle model (tests/cycles.sh).
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

# ---- scripts that print ok/FAIL lines: the player and threads, the ARM926 and M3 images under QEMU ----
relay tests/play.sh
relay tests/arm.sh
relay tests/m3.sh
relay tests/m0.sh
relay tests/cycles.sh

# ---- the intro players within the original's 64 kB (stripped, as the Makefile prints them) ------
for p in intro-fixed intro-float; do
  if strip -o "$T/$p.stripped" "$B/$p" && sz=$(stat -c %s "$T/$p.stripped") && [ "$sz" -le 65536 ]; then
    pass "$p: $sz bytes stripped, within 65,536"
  else
    fail "$p: ${sz:-?} bytes stripped, over the 65,536 of a 64 kB intro"
  fi
done
