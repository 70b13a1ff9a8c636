# fuzz.sh: the scene fuzzer's smoke run and its kept inputs through the programs.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

# ---- the scene fuzzer: a bounded smoke run (make fuzz runs it longer) ----------------------------
# tests/fuzz.sh replays every kept crash of tests/fuzz-regress/ first, then fuzzes each build from
# the seeds; any crash, hang (10 s), leak, sanitizer report or numeric event fails.
while IFS= read -r line; do
  case $line in
    fuzz-*": "*"no crash"*) pass "$line" ;;
    fuzz-*) fail "$line" ;;
    *) echo "       $line" ;;
  esac
done < <(tests/fuzz.sh "${FUZZ_SECONDS:-15}" --smoke 2>&1)
# Each kept crash also goes through the programs themselves (scn_load, the render command) under
# ASan + UBSan, at its start and its end: rendered, or refused with one line and exit 2.
bad=""
for f in tests/fuzz-regress/*.scene; do
  for real in fixed float; do
    for t in 0 "$(awk '$1 == "duration" { d = $2 } END { print d + 0 }' "$f")"; do
      out=$($B/san-$real/rt render --scene "$f" --size 32x24 --time "$t" --stats -o "$T/regress.ppm" 2>"$T/regress.err")
      rc=$?
      if [ $rc -eq 0 ]; then
        grep -q '^fx_overflow=0$' <<<"$out" && grep -q '^fx_domain=0$' <<<"$out" || bad="$bad $real $(basename "$f") $t: numeric events;"
      elif [ $rc -ne 2 ] || [ "$(wc -l <"$T/regress.err")" -ne 1 ]; then
        bad="$bad $real $(basename "$f") $t: exit $rc: $(head -3 "$T/regress.err");"
      fi
    done
  done
done
if [ -z "$bad" ]; then
  pass "the $(ls tests/fuzz-regress/*.scene | wc -l) kept fuzz inputs (tests/fuzz-regress/) render cleanly under ASan + UBSan in both builds, no numeric event"
else
  fail "kept fuzz inputs:$bad"
fi
