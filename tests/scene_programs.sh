#!/usr/bin/env bash
# scene_programs.sh: compiles every scene into its own program (rt-scenec + the tracer built with
# only the scene's effects), prints the code size of each, and checks that each renders exactly
# what `rt-fixed render --scene` renders. Usage: tests/scene_programs.sh [--check] [--arm] [SCENE...]
# Expects `make all`. With --check, exits non-zero when a compiled scene's frame differs.
# With --arm (expects `make arm`), also links the fixed ARM926 image (src/app/intro.c) around each
# scene, each file built with make arm's flags, and prints its code + read-only data + initialised
# data, the figure the 64 kB limit applies to: an image over it is a failure (exit status 1).
set -u
cd "$(dirname "$0")/.."
B=build
OUT=$B/scenes
mkdir -p "$OUT"
check=0
arm=0
while [ $# -gt 0 ]; do
  case "$1" in
    --check) check=1 ;;
    --arm) arm=1 ;;
    *) break ;;
  esac
  shift
done
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(scenes/*.scene)

CC=${CC:-gcc}
CFLAGS="-std=c11 -Wall -Wextra -Werror -Wundef -Wstrict-prototypes -Wshadow -ffp-contract=off -fno-strict-aliasing -O2"
CFLAGS="$CFLAGS -ffunction-sections -fdata-sections -DREAL_FIXED=1 -DFX_COUNT_EVENTS=0 -DFIXMATH_NO_CACHE"
[ "$(uname -m)" = x86_64 ] && CFLAGS="$CFLAGS -mgeneral-regs-only"
INC="-Ifixed -Isrc/core -Isrc/scene -Isrc/app -isystem $B/deps/libfixmath/libfixmath"
CORE="fixed/fx.c src/core/trace.c src/core/shapes.c src/core/prepare.c src/core/camera.c src/core/render.c src/core/subsample.c src/core/subsample_split.c src/core/subsample_fill.c src/core/subsample_shortcut.c src/core/subsample_local.c src/core/probe.c src/core/noise.c src/core/texture.c src/scene/scn.c src/scene/knobs.c"
LIB=$B/obj/fixed/libfixmath.a

# Builds program $1 from generated scene source $2 and effects header $3.
build() {
  local objs=() f o
  mkdir -p "$1.obj"
  for f in $CORE; do
    o="$1.obj/$(basename "${f%.c}").o"
    $CC $CFLAGS $INC -include "$3" -c "$f" -o "$o" || return 1
    objs+=("$o")
  done
  $CC -std=c11 -O2 -DREAL_FIXED=1 $INC -c "$2" -o "$1.obj/compiled.o" &&
  $CC -std=c11 -O2 -DREAL_FIXED=1 -DFIXMATH_NO_CACHE $INC -c src/tools/still.c -o "$1.obj/still.o" &&
  $CC -O2 -Wl,--gc-sections -o "$1" "${objs[@]}" "$1.obj/compiled.o" "$1.obj/still.o" "$LIB" -lm
}

# The fixed ARM image $1 around generated scene source $2 (named scn_intro) and effects header
# $3: the core compiled for the ARM926 with the scene's effects, each file with the flags `make
# arm` gives it (-O2, or its own: `make arm-file-flags`, such as Thumb at -Os for the timeline);
# intro.c (the board's command line, which no effect changes), the backend and libfixmath as
# `make arm` built them. The image must fit the 64 KiB limit (ARM_LIMIT).
ARM_CC=arm-none-eabi-gcc
ARM_ARCH="-mcpu=arm926ej-s -marm -mfloat-abi=soft"
ARM_LIMIT=65536
AO=$B/obj/arm-fixed
declare -A ARM_FILE_FLAGS=()
ARM_DEFS=
load_arm_flags() {
  local lines f flags
  lines=$(env -u MAKEFLAGS -u MFLAGS make -s --no-print-directory arm-file-flags) || return 1
  while read -r f flags; do
    case $f in
      defines) ARM_DEFS=$flags ;; # the whole image's (ARM_CFLAGS' -D): the same structures as intro.o's
      ?*) ARM_FILE_FLAGS[$f]=$flags ;;
    esac
  done <<<"$lines"
  [ ${#ARM_FILE_FLAGS[@]} -gt 0 ]
}
build_arm() {
  local objs=() f o
  mkdir -p "$1.obj"
  for f in $CORE "$2"; do
    o="$1.obj/arm-$(basename "${f%.c}").o"
    $ARM_CC ${CFLAGS/-mgeneral-regs-only/} $ARM_ARCH -ffreestanding $ARM_DEFS ${ARM_FILE_FLAGS[$f]:-} $INC -Iplatform -include "$3" \
      -c "$f" -o "$o" || return 1
    objs+=("$o")
  done
  $ARM_CC $ARM_ARCH -nostartfiles -T platform/arm/link.ld -Wl,--gc-sections -Wl,-z,noexecstack \
    -Wl,--no-warn-rwx-segments -o "$1" "${objs[@]}" "$AO/src/app/intro.o" "$AO/platform/board.o" "$AO/platform/arm/arm.o" \
    "$AO/start.o" "$AO/libfixmath.a" -lm -lc -lgcc
}
arm_size() { arm-none-eabi-size -A "$1" | awk '$1 ~ /^\.(text|rodata|data|ARM\.exidx)$/ { n += $2 } END { print n }'; }

# Bytes of code (.text) of the tracer, libfixmath and the scene data in a program.
text_size() { size -A "$1" | awk '$1 == ".text" { t = $2 } $1 == ".rodata" { r = $2 } END { print t, r }'; }

bad=0
if [ $arm = 1 ] && ! load_arm_flags; then
  echo "scene_programs: make arm-file-flags failed: cannot build the ARM images as make arm does"
  exit 1
fi
if [ $arm = 1 ]; then
  printf '%-24s %-44s %10s %10s %12s %10s\n' scene effects text rodata "text vs all" "ARM image"
else
  printf '%-24s %-44s %10s %10s %12s\n' scene effects text rodata "text vs all"
fi
for scene in "${scenes[@]}"; do
  name=$(basename "${scene%.scene}")
  gen=$OUT/$name
  if ! $B/rt-scenec "$scene" -o "$gen.c" --effects "$gen-fx.h" 2>"$gen.log"; then
    cat "$gen.log"; bad=1; continue
  fi
  printf '#define RT_COMPILED_EFFECTS RT_FX_ALL\n' >"$gen-all.h"
  if ! build "$gen-fixed" "$gen.c" "$gen-fx.h" || ! build "$gen-all" "$gen.c" "$gen-all.h"; then
    echo "$name: build failed"; bad=1; continue
  fi
  read -r t r < <(text_size "$gen-fixed")
  read -r ta _ < <(text_size "$gen-all")
  fx=$(sed -n 's|.*RT_COMPILED_EFFECTS [0-9]*u /\*\(.*\) \*/|\1|p' "$gen-fx.h")
  printf '%-24s %-44s %10d %10d %11d%%' "$name" "${fx:- none}" "$t" "$r" $((t * 100 / ta))
  if [ $arm = 1 ]; then
    if $B/rt-scenec "$scene" -o "$gen-intro.c" --name scn_intro 2>>"$gen.log" &&
      build_arm "$gen-arm.elf" "$gen-intro.c" "$gen-fx.h"; then
      asz=$(arm_size "$gen-arm.elf")
      printf ' %10d' "$asz"
      if [ "$asz" -gt $ARM_LIMIT ]; then
        printf ' > %d (the 64 KiB limit)' $ARM_LIMIT
        bad=1
      fi
    else
      printf ' %10s' failed
      bad=1
    fi
  fi
  echo
  if [ $check = 1 ]; then
    # the compiled program's frame equals the file's, byte for byte, at three moments
    dur=$(sed -n 's/^ *\.duration_ms = \([0-9]*\),.*/\1/p' "$gen.c")
    for ms in 0 $((dur / 2)) "$dur"; do
      "$gen-fixed" "$ms" 160 120 >"$gen-$ms.ppm"
      s=$((ms / 1000)).$(printf '%03d' $((ms % 1000)))
      $B/rt-fixed render --scene "$scene" --time "$s" --size 160x120 -o "$gen-$ms-ref.ppm" 2>/dev/null
      if ! cmp -s "$gen-$ms.ppm" "$gen-$ms-ref.ppm"; then
        echo "  $name: compiled program differs from render --scene at $s s"
        bad=1
      fi
    done
  fi
done
echo "(x86-64 host, -O2, unused sections dropped; 'text vs all' compares with the same program built with every effect)"
[ $arm = 0 ] || echo "(ARM image: build/arm/intro-fixed.elf with the scene in place of the intro: code + rodata + data bytes, limit $ARM_LIMIT)"
exit $bad
