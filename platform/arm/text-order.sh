#!/usr/bin/env bash
# text-order.sh: writes platform/arm/text-order.ld, the order of the ARM926 image's functions that run inside frames, densest first, so that the hot code shares fewer I-cache sets (make arm-text-order).
#
# Usage: platform/arm/text-order.sh [FIRST LAST STEP]   (default 0 1200 100: the benchmark's frames)
# Runs `platform/arm/qemu.sh bench fixed FIRST LAST STEP` with the cycle plugin's per-address
# counts kept (QEMU_CYCLES_OUT), sums the instructions executed inside the frames per function
# (arm-none-eabi-nm -S), and lists the functions by instructions per byte of code, most first, as
# `*(.text.NAME)` lines that platform/arm/link.ld includes at the start of .text. Code order
# changes no instruction and no picture, only addresses: the cycle model's I-cache misses
# (docs/arm.md, Cycle model). Functions that no longer exist match nothing; new ones go after the
# listed ones, in the default order.
set -euo pipefail
cd "$(dirname "$0")/../.."

die() { printf 'text-order.sh: error: %s\n' "$*" >&2; exit 2; }
[ $# -eq 0 ] || [ $# -eq 3 ] || die "usage: platform/arm/text-order.sh [FIRST LAST STEP]"
elf=build/arm/intro-fixed.elf
[ -f "$elf" ] || die "$elf is missing: run make arm first"
out=platform/arm/text-order.ld
counts=$(mktemp)
trap 'rm -f "$counts"' EXIT
if [ $# -eq 3 ]; then range=("$@"); else range=(0 1200 100); fi
QEMU_CYCLES_OUT=$counts platform/arm/qemu.sh bench fixed "${range[@]}" >/dev/null || die "the bench run failed"
{
  echo "/* text-order.ld: written by platform/arm/text-order.sh (make arm-text-order): the functions run inside frames, most instructions per byte first (link.ld includes it at the start of .text). */"
  arm-none-eabi-nm -n -S "$elf" | awk -v counts="$counts" '
    ($3 == "t" || $3 == "T") && NF == 4 { n++; start[n] = strtonum_hex($1); size[n] = strtonum_hex($2); name[n] = $4 }
    function strtonum_hex(h,   i, v, c) {
      v = 0; h = tolower(h)
      for (i = 1; i <= length(h); i++) { c = index("0123456789abcdef", substr(h, i, 1)) - 1; v = v * 16 + c }
      return v
    }
    END {
      while ((getline line < counts) > 0) {
        split(line, f, " ")
        if (f[1] != "a") continue
        a = strtonum_hex(f[2]); lo = 1; hi = n
        while (lo < hi) { mid = int((lo + hi + 1) / 2); if (start[mid] <= a) lo = mid; else hi = mid - 1 }
        if (start[lo] <= a && a < start[lo] + size[lo]) heat[name[lo]] += f[3]
      }
      for (k in heat) for (i = 1; i <= n; i++) if (name[i] == k) { d[k] = heat[k] / (size[i] ? size[i] : 1); break }
      m = 0
      for (k in d) keys[++m] = k
      for (i = 1; i <= m; i++)
        for (j = i + 1; j <= m; j++)
          if (d[keys[j]] > d[keys[i]] || (d[keys[j]] == d[keys[i]] && keys[j] < keys[i])) { t = keys[i]; keys[i] = keys[j]; keys[j] = t }
      for (i = 1; i <= m; i++) printf "*(.text.%s)\n", keys[i]
    }'
} >"$out.tmp"
[ "$(wc -l <"$out.tmp")" -gt 1 ] || { rm -f "$out.tmp"; die "no function ran inside the frames"; }
mv "$out.tmp" "$out"
echo "text-order: wrote $out ($(($(wc -l <"$out") - 1)) functions); make arm relinks the images with it"
