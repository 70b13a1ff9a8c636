# softdiv.sh: the ARM926's division-free path (-DFX_SOFT_DIVIDE=1, the san-fixed-sd build) on the host: its unit tests and intro frames.
# A part of tests/run.sh (sourced by it: B, T, DEMO and tests/lib.sh's helpers are set).

# The ARM926's division-free path (FX_SOFT_DIVIDE=1) on the host, under the sanitizers: the unit
# tests, and frames through the whole intro byte for byte those of rt-fixed's hardware division.
for t in test_numeric test_shapes test_subsample; do spawn "$T/san-fixed-sd-$t.log" "$B/san-fixed-sd/$t"; done
bad=""
sd=$("$B/san-fixed-sd/rt" render --frames 0-1200 --step 100 --size 96x72 --checksum 2>"$T/san-fixed-sd.err")
hw=$("$B/rt-fixed" render --frames 0-1200 --step 100 --size 96x72 --checksum 2>/dev/null)
wait
for t in test_numeric test_shapes test_subsample; do
  spawned_ok "$T/san-fixed-sd-$t.log" || bad="$bad $t:$(tail -3 "$T/san-fixed-sd-$t.log" | tr '\n' ' ');"
done
[ "$sd" = "$hw" ] && [ "$(grep -c fnv64= <<<"$sd")" -eq 13 ] || bad="$bad frames differ from rt-fixed: $(tail -1 "$T/san-fixed-sd.err");"
# the division-free quotient is called there, and nowhere in san-fixed
calls=$(objdump -d "$B/san-fixed-sd/rt" | grep -c 'call.*<fx_udiv64>')
[ "$calls" -gt 0 ] && ! objdump -d "$B/san-fixed/rt" | grep -q 'call.*<fx_udiv64>' || bad="$bad fx_udiv64 called $calls times;"
[ -z "$bad" ] && pass "san-fixed-sd (-DFX_SOFT_DIVIDE=1, the ARM926's division path): test_numeric, test_shapes, test_subsample pass; 13 intro frames = rt-fixed's; fx_udiv64 called from $calls places (none in san-fixed)" ||
  fail "san-fixed-sd:$bad"
