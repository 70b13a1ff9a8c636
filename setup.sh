#!/usr/bin/env bash
# setup.sh: installs the Debian packages fixray needs and fetches libfixmath's source (cached in build/deps).
#
# Usage: ./setup.sh [--check] [--arm] [--test] [--gui]
#   --arm     also the ARM926 cross toolchain and QEMU (make arm, make qemu-frames)
#   --test    everything make test needs: --arm, clang (fuzzing), valgrind, time, Xvfb, gnuplot
#   --gui     also QEMU's display window (make qemu)
#   --check   only report what is missing (exit 1 if anything is), change nothing.
# Safe to run again: it does nothing when everything is already there.
set -euo pipefail

top=$(cd "$(dirname "$0")" && pwd)
deps="$top/build/deps"

# Packages for building and playing on the host (make, make run).
packages=(gcc make pkg-config libc6-dev libpng-dev libcmocka-dev libsdl2-dev xz-utils ca-certificates)
# The ARM926 images and their emulator (--arm). What the test suite needs besides (--test):
# clang and libclang-rt-14-dev build the scene fuzzer (libFuzzer), clang-format checks the C
# files' formatting, valgrind and time serve the memcheck run and the soak, Xvfb an X server for
# the player, gnuplot make tradeoff's plot.
# QEMU's window (--gui).
arm_packages=(gcc-arm-none-eabi libnewlib-arm-none-eabi binutils-arm-none-eabi qemu-system-arm)
test_packages=(clang clang-format libclang-rt-14-dev valgrind time xvfb xauth gnuplot-nox)
gui_packages=(qemu-system-gui)

# libfixmath: the Debian source package version, and the upstream tarball it ships.
fixmath_version="0~20220222-3"
fixmath_tarball="libfixmath_0~20220222.orig.tar.xz"
fixmath_sha256="38a93f38bcf2b6fbc00bfc4e10905f8f012cc72943ec5eed69a459c3bc0349e0"

say() { printf 'setup: %s\n' "$*"; }
die() { printf 'setup: error: %s\n' "$*" >&2; exit 1; }

check_only=0
for arg in "$@"; do
  case "$arg" in
    --check) check_only=1 ;;
    --arm) packages+=("${arm_packages[@]}") ;;
    --test) packages+=("${arm_packages[@]}" "${test_packages[@]}") ;;
    --gui) packages+=("${arm_packages[@]}" "${gui_packages[@]}") ;;
    *) die "unknown option '$arg' (usage: ./setup.sh [--check] [--arm] [--test] [--gui])" ;;
  esac
done

as_root() {
  if [ "$(id -u)" -eq 0 ]; then
    "$@"
  elif command -v sudo >/dev/null 2>&1; then
    sudo "$@"
  else
    die "need root to run '$*' and sudo is not installed; run ./setup.sh as root"
  fi
}

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

tarball_ok() {
  [ -f "$deps/$fixmath_tarball" ] &&
    echo "$fixmath_sha256  $deps/$fixmath_tarball" | sha256sum --check --status
}

if [ "$check_only" -eq 1 ]; then
  status=0
  [ ${#missing[@]} -eq 0 ] || { say "missing packages: ${missing[*]}"; status=1; }
  tarball_ok || { say "libfixmath source not fetched yet ($deps/$fixmath_tarball)"; status=1; }
  exit $status
fi

if [ ${#missing[@]} -gt 0 ]; then
  say "installing missing Debian packages: ${missing[*]}"
  [ "$(id -u)" -eq 0 ] || say "(not root: using sudo)"
  say "running: apt-get update"
  as_root apt-get update -q
  say "running: apt-get install -y --no-install-recommends ${missing[*]}"
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

if tarball_ok; then
  exit 0
fi

# Fetch libfixmath's upstream source through apt with a private configuration: deb-src entries
# derived from this machine's own deb entries, private lists and cache. The system apt set-up is
# not touched and no host is named here.
say "fetching libfixmath source ($fixmath_version) through apt into build/deps"
mkdir -p "$deps"
aptdir=$(mktemp -d "$deps/apt.XXXXXX")
trap 'rm -rf "$aptdir"' EXIT
mkdir -p "$aptdir/sources.list.d" "$aptdir/lists/partial" "$aptdir/cache/archives/partial"

n=0
for f in /etc/apt/sources.list.d/*.sources; do
  [ -f "$f" ] || continue
  n=$((n + 1))
  # deb822 stanzas: keep those of type deb, turned into deb-src.
  awk 'BEGIN { RS = ""; ORS = "\n\n" }
       /(^|\n)Types:[^\n]*(^|[ \t])deb([ \t]|\n|$)/ {
         gsub(/(^|\n)Types:[^\n]*/, "\nTypes: deb-src"); sub(/^\n/, ""); print }' \
    "$f" >"$aptdir/sources.list.d/src$n.sources"
done
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
  [ -f "$f" ] || continue
  n=$((n + 1))
  sed -n 's/^[[:space:]]*deb[[:space:]]/deb-src /p' "$f" >"$aptdir/sources.list.d/src$n.list"
done
[ "$n" -gt 0 ] || die "no apt sources found in /etc/apt to derive deb-src entries from"

aptopts=(-o "Dir::Etc::SourceList=/dev/null" -o "Dir::Etc::SourceParts=$aptdir/sources.list.d"
  -o "Dir::State::Lists=$aptdir/lists" -o "Dir::Cache=$aptdir/cache"
  -o "Debug::NoLocking=1" -o "APT::Sandbox::User=$(id -un)")
say "running: apt-get update (private source lists)"
apt-get "${aptopts[@]}" update -q >"$aptdir/update.log" 2>&1 ||
  { cat "$aptdir/update.log" >&2; die "apt-get update for source lists failed"; }
say "running: apt-get source --download-only --tar-only libfixmath=$fixmath_version"
(cd "$aptdir" && apt-get "${aptopts[@]}" source --download-only --tar-only \
  "libfixmath=$fixmath_version" >"$aptdir/source.log" 2>&1) ||
  { cat "$aptdir/source.log" >&2; die "could not download libfixmath's source through apt"; }
[ -f "$aptdir/$fixmath_tarball" ] || die "apt did not deliver $fixmath_tarball"
echo "$fixmath_sha256  $aptdir/$fixmath_tarball" | sha256sum --check --status ||
  die "$fixmath_tarball: SHA-256 mismatch (expected $fixmath_sha256)"
mv "$aptdir/$fixmath_tarball" "$deps/$fixmath_tarball"
say "libfixmath source cached: build/deps/$fixmath_tarball (SHA-256 checked)"
