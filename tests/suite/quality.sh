# quality.sh: adaptive and probe mode against full mode on every example and hard scene (tests/quality.sh --short).
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set). The scenes
# of tests/quality-known.txt are reported as known misses, every other frame must meet the targets.
if tests/quality.sh --short >"$T/quality.log" 2>&1; then
  pass "quality --short: $(grep -c '| ok' "$T/quality.log") frames within the targets, $(grep -c '^KNOWN' "$T/quality.log") known misses (tests/quality-known.txt); $(grep '^| fixed | probe' "$T/quality.log")"
else
  fail "quality --short: $(grep ^FAIL "$T/quality.log" | tr '\n' ' ')"
fi
grep -E '^(KNOWN|NOTE)' "$T/quality.log" | sed 's/^/     /'
