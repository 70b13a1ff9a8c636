# platforms.sh: the scripts of the platforms: the desktop player (tests/play.sh), the ARM926 (tests/arm.sh), the Cortex-M3 (tests/m3.sh), the Cortex-M0 (tests/m0.sh), the boards' cycle model (tests/cycles.sh).
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

# ---- scripts that print ok/FAIL lines: the player and threads, the ARM926 and M3 images under QEMU ----
relay tests/play.sh
relay tests/arm.sh
relay tests/m3.sh
relay tests/m0.sh
relay tests/cycles.sh
