# tools.sh: make bench's and make tradeoff's scripts (QUICK=1): they run end to end and write well-formed tables.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

# ---- make bench's script, QUICK=1: runs end to end and writes a well-formed table ------------
# Content, not timings: every configuration has one row, worst >= mean > 0, the fps follow from
# the times (1000 / ms) and on the boards from the estimated cycles (200 MHz / cycles), with the
# one-instruction-a-cycle fps in brackets from the instruction counts, which are fewer than the
# cycles; the CPU and core count are named, and progress went to standard error.
bench_md=$T/bench-quick.md
nl=$'\n'
if QUICK=1 tests/bench_all.sh -o "$bench_md" >"$T/bench-quick.out" 2>"$T/bench-quick.err"; then
  nth=2; [ "$(nproc)" -gt 1 ] || nth=1
  problems=$(awk -F' *[|] *' -v nth="$nth" -v cores="$(nproc)" '
    function num(s) { sub(/ .*/, "", s); sub(/\*$/, "", s); return s + 0 }
    function near(a, b, r) { return a >= b * 0.99 - r && a <= b * 1.01 + r }   # r: the printed rounding
    # fps f printed to 0.01 from clock / m, m printed to 0.1 M: m was within 0.05 M of its figure
    function per(f, clock, m) { return f >= clock / (m + 0.05) * 0.99 - 0.0051 && (m <= 0.05 || f <= clock / (m - 0.05) * 1.01 + 0.0051) }
    # a board cell: "C M cycles (I M instructions)", "F (G)*": the figure in brackets
    function br(s) { sub(/^[^(]*[(]/, "", s); sub(/[)].*/, "", s); return s + 0 }
    function board(c, f, clock) { return c ~ /^[0-9.]+ M cycles [(][0-9.]+ M instructions[)]$/ && br(c) > 0 && num(c) >= br(c) &&
                                         per(num(f), clock, num(c)) && per(br(f), clock, br(c)) }
    /^- CPU: .*, [0-9]+ cores/ { cpu = 1; if ($0 !~ ", " cores " cores") print "core count is not " cores }
    /^[|] platform [|] build [|] size [|] threads [|] mean frame [|] worst frame [|] mean fps [|] worst-frame fps [|]$/ { head = 1 }
    /^[|] (desktop|ARM926, QEMU) [|]/ {
      key = $2 "/" $3 "/" $4 "/" $5
      if (key in seen) print "duplicate row " key
      seen[key] = 1
      m = num($6); w = num($7); fm = num($8); fw = num($9)
      if (!(m > 0 && w >= m)) print "bad mean/worst: " $0
      if ($2 == "desktop") {
        d++
        if ($6 !~ / ms$/ || !near(fm, 1000 / m, 0.051) || !near(fw, 1000 / w, 0.051)) print "fps do not follow from ms: " $0
      } else {
        a++
        if ($5 != 1 || $8 !~ /[*]$/ || !board($6, $8, 200) || !board($7, $9, 200))
          print "ARM926 fps do not follow from 200 MHz / cycles and instructions: " $0
      }
    }
    /^[\\][*] ARM926 fps: [*][*]at a 200 MHz clock/ { label = 1 }
    /^[|] Cortex-M3, QEMU [|]/ {
      m3++; m = num($6); w = num($7); fm = num($8); fw = num($9)
      if ($3 != "fixed" || $4 != "128x64" || $8 !~ /[*][*]$/ || !(m > 0 && w >= m) ||
          !board($6, $8, 50) || !board($7, $9, 50))
        print "Cortex-M3 fps do not follow from 50 MHz / cycles and instructions: " $0
    }
    /^[\\][*][\\][*] Cortex-M3 fps: [*][*]at the LM3S6965.s 50 MHz/ { m3label = 1 }
    END {
      if (m3 != 1) print m3 + 0 " Cortex-M3 rows, expected 1"
      if (!m3label) print "no 50 MHz label for the Cortex-M3"
      if (!cpu) print "no CPU line"
      if (!head) print "no table header"
      if (!label) print "no 200 MHz label"
      if (d != 2 * 2 * nth) print d + 0 " desktop rows, expected " 2 * 2 * nth
      if (a != 2) print a + 0 " ARM926 rows, expected 2"
    }' "$bench_md")
  for want in "desktop | float | 320x240 | 1 |" "desktop | fixed | 640x480 | $(nproc) |" \
              "ARM926, QEMU | fixed | 320x240 |" "ARM926, QEMU | soft-float | 320x240 |"; do
    grep -qF "| $want" "$bench_md" || problems+="${problems:+$nl}no row '$want'"
  done
  grep -q 'bench: desktop, round 1/1, frame 3/3' "$T/bench-quick.err" && grep -q 'qemu-bench: float image.*frames in' "$T/bench-quick.err" ||
    problems+="${problems:+$nl}no progress on standard error"
  if [ -z "$problems" ]; then
    pass "make bench's script (QUICK=1): $(grep -c '^| desktop' "$bench_md") desktop, $(grep -c '^| ARM926' "$bench_md") ARM926 and $(grep -c '^| Cortex-M3' "$bench_md") Cortex-M3 rows, fps consistent with the times, estimated cycles and instruction counts"
  else
    fail "make bench's script (QUICK=1) wrote a malformed $bench_md:"
    sed 's/^/       /' <<<"$problems"
  fi
else
  fail "make bench's script (QUICK=1 tests/bench_all.sh) failed:"
  tail -5 "$T/bench-quick.err" | sed 's/^/       /'
fi

# ---- make tradeoff's script, QUICK=1: runs end to end and writes a well-formed table ------------
# Form, not timings: one row per configuration (float default, fixed full), ms > 0 with the worst
# frame no faster than the mean, PSNR a number or inf (worst <= mean), over8 a share in 0..100 %,
# and the plot written as a PNG. The ARM926 columns: the board's estimated ms, cycles and
# instructions are positive, the ms the cycles at 200 MHz, the CPI the cycles over the
# instructions and above 1; the fixed full row (a non-default setting on the board) costs other
# than the board's default.
trade_md=$T/tradeoff-quick.md
if QUICK=1 tests/tradeoff.sh -o "$trade_md" >"$T/tradeoff-quick.out" 2>"$T/tradeoff-quick.err"; then
  problems=$(awk -F' *[|] *' '
    function db(s) { sub(/ dB$/, "", s); return s }
    function isdb(s) { return s ~ /^(inf|-?[0-9]+[.][0-9]+) dB$/ }
    function near(a, b, tol) { return a - b <= tol && b - a <= tol }
    /^[|] build [|] configuration [|] render options [|] mean ms [|] worst-frame ms [|] x float default [|] ARM est[.] ms at 200 MHz [|] x ARM fixed default [|] ARM Mcycles\/frame [|] ARM Minstr\/frame [|] ARM CPI [|]/ { head = 1 }
    /^[|] (float|fixed) [|]/ {
      key = $2 "/" $3
      if (key in seen) print "duplicate row " key
      seen[key] = 1; n++
      if (!($5 + 0 > 0 && $6 + 0 >= $5 + 0)) print "bad mean/worst ms: " $0
      if ($8 !~ /^[0-9]+$/ || $10 !~ /^[0-9]+[.][0-9]$/ || $11 !~ /^[0-9]+[.][0-9]$/ || $11 + 0 <= 0) print "ARM926 ms, Mcycles, Minstr not positive numbers: " $0
      else if (!near($8, $10 * 5, 1)) print "ARM926 ms not the cycles at 200 MHz: " $0
      if ($12 !~ /^[0-9][.][0-9][0-9]$/ || $12 + 0 <= 1 || !near($12, $10 / $11, 0.02)) print "ARM926 CPI not cycles / instructions above 1: " $0
      if ($2 == "fixed" && ($9 !~ /^[0-9]+[.][0-9][0-9]$/ || $9 == "1.00")) print "fixed full: ARM926 cost not other than the default: " $0
      if (!isdb($13) || !isdb($14)) print "PSNR not a number or inf: " $0
      else if (db($13) != "inf" && (db($14) == "inf" || db($14) + 0 > db($13) + 0)) print "worst PSNR above the mean: " $0
      if ($15 !~ /^[0-9]+[.][0-9]+ %$/ || $15 + 0 > 100 || $16 !~ /^[0-9]+[.][0-9]+ %$/ || $16 + 0 < $15 + 0) print "bad over8: " $0
    }
    END {
      if (!head) print "no table header"
      if (n != 2) print n + 0 " rows, expected 2"
      if (!(("float/default") in seen) || !(("fixed/full") in seen)) print "missing the float default or the fixed full row"
    }' "$trade_md")
  png=${trade_md%.md}.png
  [ "$(head -c 8 "$png" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
    problems+="${problems:+$nl}no PNG plot at $png"
  grep -q 'tradeoff: frame 1/1 (t=14 s), round 1/1' "$T/tradeoff-quick.err" ||
    problems+="${problems:+$nl}no progress on standard error"
  arm_def=$(sed -n 's/^tradeoff: ARM926 fixed (defaults), frame 350: \([0-9]*\) instructions, [0-9]* cycles$/\1/p' "$T/tradeoff-quick.err")
  arm_full=$(sed -n 's/^tradeoff: ARM926 fixed --mode full, frame 350: \([0-9]*\) instructions, [0-9]* cycles$/\1/p' "$T/tradeoff-quick.err")
  [[ "$arm_full" =~ ^[1-9][0-9]*$ ]] && [[ "$arm_def" =~ ^[1-9][0-9]*$ ]] && [ "$arm_full" != "$arm_def" ] ||
    problems+="${problems:+$nl}ARM926 counts: fixed --mode full '$arm_full', fixed default '$arm_def' (want two different positive whole numbers)"
  if [ -z "$problems" ]; then
    pass "make tradeoff's script (QUICK=1): $(grep -cE '^[|] (float|fixed) [|]' "$trade_md") rows with ms, ARM926 estimated ms, cycles and instructions, PSNR and over8, and the plot; board frame 350: $arm_full instructions with --mode full, $arm_def by default"
  else
    fail "make tradeoff's script (QUICK=1) wrote a malformed $trade_md:"
    sed 's/^/       /' <<<"$problems"
  fi
else
  fail "make tradeoff's script (QUICK=1 tests/tradeoff.sh) failed:"
  tail -5 "$T/tradeoff-quick.err" | sed 's/^/       /'
fi
