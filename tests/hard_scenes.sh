#!/usr/bin/env bash
# hard_scenes.sh: the numerically hard scenes of tests/hard/, each rendered by both builds, plain and sanitized.
# Usage: tests/hard_scenes.sh [SCENE...] (default: every tests/hard/*.scene). Expects `make all san`.
# Every '# check:' line of a scene is one case:
#   time=T size=WxH    the moment and frame size (full mode: every pixel, every ray)
#   psnr=P over8=N     fixed vs float: PSNR >= P dB and at most N per mille of pixels off by > 8
#   same-all           --effects all (every surface also tests itself for shadow, full depth)
#                      renders the same bytes as the derived effects, in both builds
#   same-all=fixed     the same, in the fixed build only
#   opts=A_B           extra render options, '_' for spaces
#   stat:KEY>=N, stat:KEY=V   assertions on the fixed build's --stats
# and every case also requires, in both sanitized builds: exit 0, no ASan/UBSan report,
# fx_overflow=0, fx_domain=0, fx_nonfinite=0 (no saturation, no domain error, no NaN or
# infinity), and the same bytes as the -O2 build; the same again in probe mode (--mode probe:
# clean, the same bytes as the -O2 build's probe frame). Prints 'ok'/'FAIL' lines; exits 1 on
# a failure.
set -u
cd "$(dirname "$0")/.."
B=build
T=$B/test/hard
mkdir -p "$T"
status=0
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(tests/hard/*.scene)
for scene in "${scenes[@]}"; do
  name=$(basename "${scene%.scene}")
  n=0
  while read -r line; do
    n=$((n + 1))
    time=0 size=96x72 psnr=40 over8=5 sameall=0 opts="" stats=()
    for tok in $line; do
      case $tok in
        time=*) time=${tok#time=} ;;
        size=*) size=${tok#size=} ;;
        psnr=*) psnr=${tok#psnr=} ;;
        over8=*) over8=${tok#over8=} ;;
        same-all) sameall=1 ;;
        same-all=fixed) sameall=fixed ;;
        opts=*) opts=${tok#opts=}; opts=${opts//_/ } ;;
        stat:*) stats+=("${tok#stat:}") ;;
        *) echo "FAIL $name: unknown check '$tok'"; status=1 ;;
      esac
    done
    base="$T/$name-$n"
    bad="" info=""
    for real in fixed float; do
      out=$($B/san-$real/rt render --scene "$scene" --time "$time" --size "$size" --mode full $opts --stats \
            -o "$base-san-$real.ppm" 2>"$base-san-$real.err")
      rc=$?
      [ $rc -eq 0 ] || bad="$bad san-$real exit $rc;"
      grep -q 'runtime error\|Sanitizer' "$base-san-$real.err" && bad="$bad san-$real: $(grep -m1 'runtime error\|Sanitizer' "$base-san-$real.err");"
      for ev in fx_overflow fx_domain fx_nonfinite; do
        v=$(sed -n "s/^$ev=//p" <<<"$out")
        [ "$v" = 0 ] || bad="$bad san-$real $ev=$v;"
      done
      $B/rt-$real render --scene "$scene" --time "$time" --size "$size" --mode full $opts -o "$base-$real.ppm" 2>/dev/null ||
        bad="$bad rt-$real failed;"
      cmp -s "$base-$real.ppm" "$base-san-$real.ppm" || bad="$bad rt-$real and san-$real differ;"
      if [ $sameall = 1 ] || [ $sameall = $real ]; then
        $B/rt-$real render --scene "$scene" --time "$time" --size "$size" --mode full $opts --effects all \
          -o "$base-$real-all.ppm" 2>/dev/null
        cmp -s "$base-$real.ppm" "$base-$real-all.ppm" || bad="$bad $real: --effects all differs ($($B/rt-cmp "$base-$real.ppm" "$base-$real-all.ppm"));"
      fi
      if [ $real = fixed ]; then
        for st in ${stats[@]+"${stats[@]}"}; do
          key=${st%%[>=]*}
          got=$(sed -n "s/^$key=//p" <<<"$out")
          if [[ $st == *">="* ]]; then
            [ -n "$got" ] && [ "$got" -ge "${st#*>=}" ] || bad="$bad $key=$got (want >= ${st#*>=});"
          else
            [ "$got" = "${st#*=}" ] || bad="$bad $key=$got (want ${st#*=});"
          fi
          info="$info $key=$got"
        done
      fi
    done
    # Probe mode on the same case: clean under the sanitizers, the -O2 build's bytes.
    for real in fixed float; do
      out=$($B/san-$real/rt render --scene "$scene" --time "$time" --size "$size" $opts --mode probe --stats \
            -o "$base-san-$real-probe.ppm" 2>"$base-san-$real-probe.err")
      rc=$?
      [ $rc -eq 0 ] || bad="$bad probe: san-$real exit $rc;"
      grep -q 'runtime error\|Sanitizer' "$base-san-$real-probe.err" && bad="$bad probe: san-$real: $(grep -m1 'runtime error\|Sanitizer' "$base-san-$real-probe.err");"
      for ev in fx_overflow fx_domain fx_nonfinite; do
        v=$(sed -n "s/^$ev=//p" <<<"$out")
        [ "$v" = 0 ] || bad="$bad probe: san-$real $ev=$v;"
      done
      $B/rt-$real render --scene "$scene" --time "$time" --size "$size" $opts --mode probe -o "$base-$real-probe.ppm" 2>/dev/null ||
        bad="$bad probe: rt-$real failed;"
      cmp -s "$base-$real-probe.ppm" "$base-san-$real-probe.ppm" || bad="$bad probe: rt-$real and san-$real differ;"
    done
    cmpline=$($B/rt-cmp "$base-fixed.ppm" "$base-float.ppm" --diff "$base-diff.png" 2>&1)
    p=$(sed -n 's/.*psnr_db=\([^ ]*\).*/\1/p' <<<"$cmpline")
    o=$(sed -n 's/.*over8=\([0-9]*\).*/\1/p' <<<"$cmpline")
    px=$(sed -n 's/.*pixels=\([0-9]*\).*/\1/p' <<<"$cmpline")
    if [ -z "$p" ] || ! awk -v p="$p" -v o="$o" -v n="$px" -v min="$psnr" -v pm="$over8" \
         'BEGIN { exit !((p == "inf" || p >= min) && o * 1000 <= n * pm) }'; then
      bad="$bad fixed vs float: $cmpline (want psnr_db >= $psnr, over8 <= $over8 per mille; see $base-diff.png);"
    fi
    what="hard $name t=${time}s $size:"
    if [ -z "$bad" ]; then
      echo "ok   $what no overflow/domain/NaN event in either build (full and probe mode),$([ $sameall != 0 ] && echo " effects all = auto ($([ $sameall = 1 ] && echo both builds || echo $sameall)),")$info fixed vs float $cmpline (bound >= $psnr dB, over8 <= $over8 per mille)"
    else
      echo "FAIL $what$bad"
      status=1
    fi
  done < <(sed -n 's/^# check://p' "$scene")
done
exit $status
