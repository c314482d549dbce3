#!/usr/bin/env bash
# cli_test.sh PASSGRAPH_BINARY - the command line as a user meets it: help texts, refusals of bad
# input (non-zero exit, message naming the cause, no crash), and a validated render whose summary
# line has the documented shape.
set -u
PG=$1
pass=0
fail=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

# expect_fail "description" "substring of stderr" args...
expect_fail() {
  local what=$1 needle=$2
  shift 2
  "$PG" "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  if [ $rc -eq 0 ]; then bad "$what: exit 0"; return; fi
  if [ $rc -ge 128 ]; then bad "$what: crashed (rc $rc)"; return; fi
  if ! grep -qF -- "$needle" "$tmp/err"; then bad "$what: stderr lacks '$needle':"; cat "$tmp/err"; return; fi
  ok
}

"$PG" --help >"$tmp/h" && grep -q "render" "$tmp/h" && ok || bad "passgraph --help"
"$PG" render --help >"$tmp/h" || bad "render --help exit"
for o in --pipeline --scene --scenario --lights --size --time --seed --out --set --device --validation \
         --no-aliasing --explain --frames --radius --intensity; do
  grep -qF -- "$o" "$tmp/h" && ok || bad "render --help does not document $o"
done

expect_fail "no command" "usage" 
expect_fail "unknown command" "unknown command" frobnicate
expect_fail "unknown option" "unknown option" render --bogus --out "$tmp/x.png"
expect_fail "missing --out" "--out" render
expect_fail "negative lights" "--lights -1" render --lights -1 --out "$tmp/x.png"
expect_fail "lights > 2^32" "--lights 4294967296" render --lights 4294967296 --out "$tmp/x.png"
expect_fail "size 0x0" "--size width 0" render --size 0x0 --out "$tmp/x.png"
expect_fail "huge size" "--size width 100000" render --size 100000x100000 --out "$tmp/x.png"
expect_fail "size garbage" "expected WxH" render --size big --out "$tmp/x.png"
expect_fail "time NaN" "--time nan" render --time nan --out "$tmp/x.png"
expect_fail "set without =" "KEY=VALUE" render --set foo --out "$tmp/x.png"
expect_fail "missing pipeline" "nope.json" render --pipeline "$tmp/nope.json" --out "$tmp/x.png"
expect_fail "missing scene" "missing.gltf" render --scene "$tmp/missing.gltf" --out "$tmp/x.png"
expect_fail "unknown parameter" "no_such_param" render --set no_such_param=1 --size 32x18 --out "$tmp/x.png"
printf '{"name":"x","resources":[{"name":"o","type":"image","format":"rgba8"}],"passes":[{"name":"p","type":"warp_drive","writes":["o"]}],"output":"o"}' >"$tmp/unknown_type.json"
expect_fail "unknown pass type" "passes[0].type" render --pipeline "$tmp/unknown_type.json" --size 32x18 --out "$tmp/x.png"
expect_fail "unwritable out" "cannot write" render --size 32x18 --lights 4 --out "$tmp/no/such/dir/x.png"

"$PG" render --validation --size 160x90 --lights 32 --time 2 --out "$tmp/r.png" --explain >"$tmp/out" 2>"$tmp/err"
rc=$?
if [ $rc -ne 0 ]; then bad "validated render exit $rc"; cat "$tmp/err"; else ok; fi
grep -Eq '^render: naive 160x90 lights=32 gpu=[0-9.]+ ms \[animate_lights [0-9.]+, shade [0-9.]+, display [0-9.]+\] nonfinite=0 frames=1 -> ' "$tmp/out" \
  && ok || { bad "summary line shape"; cat "$tmp/out"; }
grep -q "explain:" "$tmp/out" && ok || bad "--explain printed nothing"
[ -s "$tmp/r.png" ] && ok || bad "PNG not written"
grep -q "validation" "$tmp/err" && grep -q "validation message" "$tmp/err" && bad "validation messages" || ok

echo "cli_test: $pass passed, $fail failed"
[ $fail -eq 0 ]
