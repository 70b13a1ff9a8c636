#!/usr/bin/env bash
# fuzz_oracle.sh: the differential oracle of the unchecked arithmetic: every scene of the given folders that render accepts, rendered by the release fixed build and by the event-counting one, must give the same bytes.
# Usage: tests/fuzz_oracle.sh FOLDER... (make fuzz passes the scene fuzzer's corpora)
# The release build (build/rt-fixed) forms the in-range operations (_in) without their checks;
# build/san-fixed/rt forms them checked, counting any result out of range and saturating it.
# So a bound of docs/numerics.md that does not hold shows as different bytes (or as a sanitizer
# report). Each scene at 32x24, at its start and at its end (when render refuses a frame, e.g.
# a camera with no view direction there, that moment is left out). Prints one line; exit 1 on
# any difference, with the scenes named (their frames in build/fuzz/oracle/).
set -u
cd "$(dirname "$0")/.."
[ $# -ge 1 ] || { echo "usage: tests/fuzz_oracle.sh FOLDER..." >&2; exit 2; }
O=build/fuzz/oracle
rm -rf "$O" && mkdir -p "$O"
for p in build/rt-fixed build/san-fixed/rt; do
  [ -x "$p" ] || { echo "fuzz-oracle: $p is missing (make all san)"; exit 1; }
done
files=$(find "$@" -maxdepth 1 -type f 2>/dev/null | sort)
# one scene: prints "refused", "same N" (N moments compared) or "DIFF what"
oracle_one() {
  local f=$1 id n=0 t dur
  id=$(basename "$f")
  dur=$(awk '$1 == "duration" { d = $2 } END { print d + 0 }' "$f" 2>/dev/null)
  for t in 0 "$dur"; do
    build/rt-fixed render --scene "$f" --size 32x24 --time "$t" -o "$O/$id-rel.ppm" 2>/dev/null || continue
    if ! build/san-fixed/rt render --scene "$f" --size 32x24 --time "$t" -o "$O/$id-san.ppm" >/dev/null 2>"$O/$id-san.err"; then
      echo "DIFF $f at $t s: the event-counting build failed: $(grep -m1 -E 'ERROR|runtime error|rt:' "$O/$id-san.err")"
      return
    fi
    if ! cmp -s "$O/$id-rel.ppm" "$O/$id-san.ppm"; then
      echo "DIFF $f at $t s: the frames differ ($O/$id-rel.ppm, $O/$id-san.ppm)"
      return
    fi
    rm -f "$O/$id-rel.ppm" "$O/$id-san.ppm" "$O/$id-san.err"
    n=$((n + 1))
  done
  [ $n -gt 0 ] && echo "same $n" || echo refused
}
export -f oracle_one
export O
results=$(printf '%s\n' $files | grep . | nice xargs -P 2 -I{} bash -c 'oracle_one "$1"' _ {})
total=$(printf '%s\n' $files | grep -c .)
same=$(grep -c '^same' <<<"$results")
moments=$(awk '$1 == "same" { n += $2 } END { print n + 0 }' <<<"$results")
diffs=$(grep '^DIFF' <<<"$results")
if [ -z "$diffs" ]; then
  echo "fuzz-oracle: $same of $total corpus inputs are scenes render accepts; at $moments moments (start, end) release rt-fixed and the event-counting build give the same bytes at 32x24"
else
  echo "fuzz-oracle: FAILED: $(grep -c . <<<"$diffs") of $same accepted scenes differ between release rt-fixed and the event-counting build:"
  sed 's/^DIFF /    /' <<<"$diffs" | head -20
  exit 1
fi
