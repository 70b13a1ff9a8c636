#!/usr/bin/env bash
# run.sh: fixray's test suite (make test): runs the parts of tests/suite/, one area each, and prints the closing 'N passed, N failed' line.
#
# Usage: tests/run.sh [PART...]
#   PART is a file of tests/suite/ without .sh (e.g. `tests/run.sh unit frames`); default: every
#   part, in the order of PARTS. Expects `make all san arm m3 fuzz-progs` (make test builds them).
# Prints a header per part, one line per check (`ok ...`, or `FAIL [file:line] ...` naming the
# part's file and line) and the closing count; exits non-zero when any check fails.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh

T=$B/test
rm -rf "$T" && mkdir -p "$T"
# The frames of the tracer's own tests come from the demo scene.
DEMO="--scene scenes/demo.scene"

PARTS=(layout unit softdiv frames sampling settings multiframe cli scenes numerics scene_errors fuzz memory
       fixed16 platforms tools faults quality)
[ $# -gt 0 ] && PARTS=("$@")
# The parts run in this shell, one after the other: they keep off RUN_*, passed and failed.
for RUN_PART in "${PARTS[@]}"; do
  RUN_FILE=tests/suite/$RUN_PART.sh
  if [ ! -f "$RUN_FILE" ]; then
    fail "no part '$RUN_PART' (tests/suite/: $(cd tests/suite && ls -- *.sh | sed 's/\.sh$//' | tr '\n' ' '))"
    continue
  fi
  echo "---- $RUN_FILE: $(sed -n '1s/^# [^:]*: //p' "$RUN_FILE")"
  RUN_START=$SECONDS
  . "$RUN_FILE"
  echo "     ($RUN_FILE: $((SECONDS - RUN_START)) s)"
done

echo
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
