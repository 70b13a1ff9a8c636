# lib.sh: what every test script shares: ok/FAIL lines and their counts, key=value reading, expected errors, programs run side by side, relayed scripts.
# Sourced from the top of the tree (B=build) by tests/run.sh and its parts (tests/suite/), and by the
# scripts that also run alone (tests/play.sh, tests/arm.sh, tests/m3.sh). A check prints one line:
# `ok   what was checked`, or `FAIL [file:line] what went wrong`, the file and line of the check.
B=${B:-build}
passed=${passed:-0}
failed=${failed:-0}

# The file and line of the check: the first caller outside the libraries (this file, and those
# that add their name to LIB_FILES, such as tests/board.sh).
LIB_FILES="lib.sh"
lib_where() {
  local i
  for ((i = 1; i < ${#BASH_SOURCE[@]}; i++)); do
    if [[ " $LIB_FILES " != *" $(basename "${BASH_SOURCE[$i]}") "* ]]; then
      echo "${BASH_SOURCE[$i]}:${BASH_LINENO[$((i - 1))]}"
      return
    fi
  done
  echo "$0"
}
pass() { passed=$((passed + 1)); echo "ok   $*"; }
fail() { failed=$((failed + 1)); echo "FAIL [$(lib_where)] $*"; }
# The exit status of a script of checks: 1 when any failed.
lib_status() { [ "$failed" -eq 0 ]; }

# kv KEY TEXT: the value of each line `KEY=value` of TEXT (--stats, rt-edges, qemu.sh print such lines).
kv() { sed -n "s/^$1=//p" <<<"$2"; }
# field KEY LINE: the value of the word `KEY=value` in a line of such words (rt-cmp prints one).
field() { sed -n "s/.*\\b$1=\\([^ ]*\\).*/\\1/p" <<<"$2" | head -1; }

# expect_error STATUS PATTERN COMMAND...: the command exits with STATUS and prints one line on
# standard error, which contains PATTERN.
expect_error() {
  local want=$1 pattern=$2
  shift 2
  local err rc
  err=$("$@" 2>&1 >/dev/null)
  rc=$?
  if [ $rc -eq "$want" ] && [ "$(wc -l <<<"$err")" -eq 1 ] && grep -q -- "$pattern" <<<"$err"; then
    pass "error: ${*#$B/} -> exit $rc: $err"
  else
    fail "error: ${*#$B/} -> exit $rc (want $want, one line matching '$pattern'): $err"
  fi
}

# spawn LOG COMMAND...: runs COMMAND in the background, at most one per processor at a time, with
# its output in LOG and its exit status in LOG.rc; `wait` then waits for all of them.
spawn() {
  while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do wait -n; done
  { "${@:2}" >"$1" 2>&1; echo $? >"$1.rc"; } &
}
# spawned_ok LOG: the command spawned with LOG exited with status 0.
spawned_ok() { [ "$(cat "$1.rc" 2>/dev/null)" = 0 ]; }

# relay SCRIPT: runs a script that prints ok/FAIL lines (its log in $T) and counts them as this
# script's own; its other lines are shown indented. A failing exit without a FAIL line fails too.
relay() {
  local log=$T/$(basename "$1" .sh).log st before=$failed line
  "$1" >"$log" 2>&1
  st=$?
  while IFS= read -r line; do
    case "$line" in
      "ok   "*) passed=$((passed + 1)); echo "$line" ;;
      "FAIL "*) failed=$((failed + 1)); echo "$line" ;;
      *) echo "       $line" ;;
    esac
  done <"$log"
  [ "$st" -eq 0 ] || [ "$failed" -gt "$before" ] || fail "$1 exited with status $st"
}
