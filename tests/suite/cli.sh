# cli.sh: the command line: bad command lines (tests/bad_cli.txt), --progress, one grammar, help and --version, SDL2 links, failed writes.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

# ---- bad input: one line on stderr, exit 2 (or 1 for a failed write), nothing left behind -------
R=$B/rt-fixed
# The table of bad command lines: tests/bad_cli.txt (its header says what each case must do).
W=$PWD/$T/cli
mkdir -p "$W/adir.png"
$R render --size 8x8 -o "$W/one.ppm" 2>/dev/null
$R render --size 16x8 -o "$W/two.ppm" 2>/dev/null
printf 'P6\n2 2\n255\nabc' >"$W/short.ppm"
printf 'P6\n4000 4000\n255\n' >"$W/big.ppm"
printf 'P6\n5000 4000\n255\n' >"$W/huge.ppm"
echo "not an image" >"$W/text.png"
echo "sphre a material m center 0 0 0 radius 1" >"$W/bad.scene"
printf '%s\n' "duration 2" "camera eye 0 1 5 at 0 1 0" "material m" \
  "sphere s material m center 0 0 -3 radius 1" "key camera.eye 0 linear 0 1 5" \
  "key camera.eye 1 linear 0 1 0" "key camera.eye 2 linear 0 1 -5" >"$W/eye.scene"
listing() { (cd "$W" && find . -mindepth 1 -printf '%p %s %T@\n' | sort); }
TOP=$PWD
before=$(listing)
ncli=0
while IFS= read -r line; do
  [[ -z $line || $line == \#* ]] && continue
  want=${line#* => }
  eval "args=(${line%% => *})"
  case ${args[0]} in
    RT) progs="rt-fixed rt-float san-fixed/rt san-float/rt" ;;
    PLAYERS) progs="rt-fixed:play rt-float:play san-fixed/rt:play intro-fixed intro-float" ;;
    *) progs=${args[0]} ;;
  esac
  bad="" first=""
  for pc in $progs; do
    p=${pc%%:*} cmd=()
    [[ $pc == *:* ]] && cmd=("${pc#*:}")
    err=$(cd "$W" && "$TOP/$B/$p" "${cmd[@]}" "${args[@]:1}" 2>&1 >/dev/null </dev/null)
    rc=$?
    if [ $rc -ne 2 ] || [ "$(wc -l <<<"$err")" -ne 1 ] || [[ "$err" != "$(basename "$p"): "* ]] ||
       [[ "$err" != *"$want"* ]]; then
      bad="$bad $p: exit $rc: $err;"
    fi
    # PLAYERS: word for word the same message, but for the program's name
    if [ "${args[0]}" = PLAYERS ]; then
      msg=${err#"$(basename "$p"): "} msg=${msg//"$(basename "$p")"/PROG}
      [ -z "$first" ] && first=$msg
      [ "$msg" = "$first" ] || bad="$bad $p says '$msg', not '$first';"
    fi
  done
  now=$(listing)
  [ "$now" = "$before" ] || { bad="$bad files changed: $(diff <(echo "$before") <(echo "$now") | grep '^[<>]' | tr '\n' ' ');"; before=$now; }
  ncli=$((ncli + 1))
  if [ -z "$bad" ]; then
    [ -n "${VERBOSE:-}" ] && echo "       ${line%% => *}: $err"
  else
    fail "bad command line '${line%% => *}' (want exit 2, one line containing '$want'):$bad"
  fi
done <tests/bad_cli.txt
pass "bad command lines: the $ncli cases of tests/bad_cli.txt, each one line and exit 2 (render cases from both builds and both sanitized builds; player cases word for word alike from rt-* play and the intro players), no file left behind"
# --progress without a terminal (a log, CI): plain lines, one every 5 percent, no carriage returns.
$B/rt-fixed render --frames 0-199 --size 8x6 --progress --checksum >/dev/null 2>"$T/progress.err"
lines=$(grep -c 'rt-fixed: frame .*%), .* frames/s' "$T/progress.err")
if ! grep -q $'\r' "$T/progress.err" && [ "$lines" -eq 21 ] && grep -q '(200 of 200, 100%)' "$T/progress.err"; then
  pass "--progress into a file: $lines plain lines for 200 frames (the first, then every 5%), no carriage return"
else
  fail "--progress into a file: $lines progress lines for 200 frames (want 21, no \\r): $(head -c 300 "$T/progress.err" | tr '\r\n' '|/')"
fi
# One grammar: `--opt=value` is `--opt value` (here with a size written WXH), and the players
# accept the same command lines: each option is taken before --help ends the run.
eq=$($B/rt-fixed render --size=40X30 --time=2 --checksum 2>&1)
sp=$($B/rt-fixed render --size 40x30 --time 2 --checksum 2>&1)
if [[ $sp == "time_ms=2000 fnv64="* ]] && [ "$eq" = "$sp" ]; then
  pass "render --size=40X30 --time=2 --checksum = render --size 40x30 --time 2 --checksum: $sp"
else
  fail "render --size=40X30 --time=2 --checksum: '$eq', want '$sp'"
fi
bad=""
for args in "--size=64X48 --threads=2 --frames=3" "--size 64x48 --threads 1 --frames 1 --screenshot $W/ok.png" \
            "--frames=9 --screenshot=$W/ok.ppm --size=4096x1"; do
  for p in "rt-fixed play" "rt-float play" intro-fixed intro-float; do
    # shellcheck disable=SC2086  # words on purpose
    out=$($B/$p $args --help 2>&1 </dev/null) && grep -q "^usage:" <<<"$out" || bad="$bad $p $args: $out;"
  done
done
[ -z "$bad" ] && [ ! -e "$W/ok.png" ] && pass "the players accept the same command lines (rt-fixed/rt-float play, intro-fixed/intro-float, each option taken before --help)" ||
  fail "players' command lines:$bad"
# help and --version: `help`, `--help` and `render --help` print the same usage, generated from
# the option table (every option of render and play in it, no stray line); --version names the
# program, fixray's version and the number system.
h1=$($B/rt-fixed help) h2=$($B/rt-fixed --help) h3=$($B/rt-fixed render --help) h4=$($B/rt-fixed play -h)
v1=$($B/rt-fixed --version) v2=$($B/intro-float --version) v3=$($B/rt-edges --version)
bad=""
[ "$h1" = "$h2" ] && [ "$h2" = "$h3" ] && [ "$h3" = "$h4" ] || bad="$bad the four usages differ;"
for o in --scene -o --size --time --frame --frames --step --checksum --progress --depth --mode --grid \
         --threshold --min-contrib --octaves --effects --show-samples --threads --stats --screenshot; do
  grep -q -- "^  $o \|^  $o, \|, $o \| $o,\| $o as" <<<"$h1" || bad="$bad $o missing;"
done
grep -qx ' *rt-fixed --help' <<<"$h1" && bad="$bad stray 'rt-fixed --help' line;"
[[ $v1 =~ ^rt-fixed\ \(fixray\)\ [0-9.]+,\ fixed$ ]] && [[ $v2 =~ ^intro-float\ \(fixray\)\ [0-9.]+,\ float$ ]] &&
  [[ $v3 =~ ^rt-edges\ \(fixray\) ]] || bad="$bad versions: $v1 / $v2 / $v3;"
[ -z "$bad" ] && pass "help = --help = render --help = play -h ($(wc -l <<<"$h1") lines, every option); $v1; $v2" ||
  fail "help and --version:$bad"
# The tools never open a window: they link the null display (platform/null.c), not SDL2; the
# programs that play do (the positive control).
bad=""
for p in rt-cmp rt-scenec rt-edges; do
  readelf -d "$B/$p" | grep -q 'NEEDED.*libSDL2' && bad="$bad $p links SDL2;"
done
for p in rt-fixed rt-float intro-fixed; do
  readelf -d "$B/$p" | grep -q 'NEEDED.*libSDL2' || bad="$bad $p does not link SDL2;"
done
[ -z "$bad" ] && pass "rt-cmp, rt-scenec, rt-edges link no SDL2 (null display); rt-fixed, rt-float, intro-fixed do" ||
  fail "SDL2 links:$bad"
# A write that fails once rendering is done (here: a file size limit) gets exit status 1 and
# leaves neither the file nor its temporary file behind, in single- and multi-frame renders.
for args in "-o $W/limit.ppm" "--frames 0-2 -o $W/limit-%d.ppm"; do
  err=$( (trap '' XFSZ; ulimit -f 1; $R render --size 64x48 $args) 2>&1 >/dev/null)
  rc=$?
  now=$(listing)
  if [ $rc -eq 1 ] && [ "$(wc -l <<<"$err")" -eq 1 ] && [[ "$err" == "rt-fixed: "*"cannot write: File too large" ]] &&
     [ "$now" = "$before" ]; then
    pass "failed write ($args, 1 KiB file size limit): exit 1, one line, nothing left behind: $err"
  else
    fail "failed write ($args): exit $rc: $err; files: $(diff <(echo "$before") <(echo "$now") | grep '^[<>]' | tr '\n' ' ')"
    before=$now
  fi
done
