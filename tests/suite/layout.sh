# layout.sh: the source tree: who may include whom, clang-format, the docs' links and pictures.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

# ---- who may include whom (docs/architecture.md) ------------------------------------------------
# The numeric layer and the tracer core include only each other; the scene language adds the
# core, never the programs or the platform. Each #include "X" must be a file of the allowed
# folders (a positive control checks that the rule sees an include of the programs).
layer_bad() { # allowed-folders files...: prints the includes outside the allowed folders
  local allowed=$1 f inc d ok
  shift
  for f in "$@"; do
    while read -r inc; do
      ok=""
      for d in $allowed; do [ -e "$d/$inc" ] && ok=1; done
      [ -n "$ok" ] || echo -n "$f includes $inc; "
    done < <(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$f")
  done
}
bad="$(layer_bad "fixed src/core" fixed/*.[ch] src/core/*.[ch])$(layer_bad "fixed src/core src/scene" src/scene/*.[ch])"
# and of the system's headers the core takes only these: no I/O, allocation, clock or threads
sys=$(sed -n 's/^#include <\([^>]*\)>.*/\1/p' fixed/*.[ch] src/core/*.[ch] | sort -u | grep -vxE 'stdint.h|stddef.h|string.h|math.h|fix16.h|arm_acle.h')
[ -n "$sys" ] && bad="$bad fixed/ or src/core/ include <$(tr '\n' ' ' <<<"$sys")>;"
printf '#include "rt.h"\n#include "cli.h"\n' >"$T/layer.c"
ctl=$(layer_bad "fixed src/core" "$T/layer.c")
if [ -z "$bad" ] && [[ $ctl == *"includes cli.h"* ]]; then
  pass "layers: fixed/ and src/core/ include only each other and stdint, stddef, string, math, fix16 (and ARM's intrinsics, arm_acle); src/scene/ adds only them ($(ls fixed/*.[ch] src/core/*.[ch] src/scene/*.[ch] | wc -l) files)"
else
  fail "layers: $bad (control: $ctl)"
fi

# ---- formatting and links ------------------------------------------------------------------------
# Every C file is as the checked-in .clang-format has it (setup.sh --test installs clang-format).
cfiles=$(find fixed src platform tests -name '*.[ch]' | sort)
if ! command -v clang-format >/dev/null; then
  fail "format: clang-format is not installed (./setup.sh --test)"
# shellcheck disable=SC2086  # one word per file
elif out=$(clang-format --dry-run --Werror $cfiles 2>&1); then
  pass "format: clang-format --dry-run --Werror passes on the $(wc -w <<<"$cfiles") C files of fixed/ src/ platform/ tests/"
else
  fail "format: files differ from .clang-format (run clang-format -i on them): $(grep -o '^[^:]*\.[ch]' <<<"$out" | sort -u | tr '\n' ' ')"
fi
# Every relative link of README.md and docs/*.md leads to a file, every #anchor to a heading.
if out=$(tests/links.sh 2>&1); then
  pass "$out (each resolves to a file, each #anchor to a heading)"
else
  fail "links: $(tr '\n' ';' <<<"$out")"
fi

# The pictures in docs/images are the current fixed-point build's (make docs-images).
if out=$(src/tools/docs-images.sh --check 2>&1); then
  pass "$out"
else
  fail "$out"
fi
