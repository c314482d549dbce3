#!/usr/bin/env bash
# cache_test.sh PASSGRAPH_BINARY - the shader and pipeline caches through the command line
# (PASSGRAPH_CACHE_STATS=1 prints the counters): a cold render compiles and writes, a warm one
# compiles nothing and gives the same image; --no-shader-cache and PASSGRAPH_NO_SHADER_CACHE=1
# compile everything and write nothing; a corrupt .spv is reported, recompiled and the image is
# unchanged; an unwritable cache folder is a note and the render succeeds.
set -u
PG=$1
. "$(dirname "$0")/check_lib.sh"
root=$(cd "$(dirname "$0")/../.." && pwd)
export PASSGRAPH_CACHE_STATS=1
unset PASSGRAPH_NO_SHADER_CACHE
r() { # cache-dir out-name extra... ; stderr -> $tmp/NAME.err
  local dir=$1 name=$2; shift 2
  PASSGRAPH_CACHE_DIR=$dir "$PG" render --validation --size 96x54 --pipeline "$root/pipelines/deferred.json" \
    --out "$tmp/$name.png" "$@" >/dev/null 2>"$tmp/$name.err" || bad "$name: exit code"
}
compiled() { sed -n 's/.*cache: \([0-9]*\) shader variants compiled.*/\1/p' "$tmp/$1.err"; }
from_disk() { sed -n 's/.* \([0-9]*\) from disk.*/\1/p' "$tmp/$1.err"; }

r "$tmp/c" cold
n=$(compiled cold)
[ -n "$n" ] && [ "$n" -gt 0 ] && [ "$(from_disk cold)" = 0 ] && ok || { bad "cold: compiled '$n'"; cat "$tmp/cold.err"; }
nspv=$(ls "$tmp/c/spirv" | grep -c '\.spv$')
[ "$nspv" = "$n" ] && ok || bad "cold: $nspv .spv files for $n variants"
ls "$tmp/c/pipelines/"*.bin >/dev/null 2>&1 && ok || bad "no pipeline cache file"

r "$tmp/c" warm
[ "$(compiled warm)" = 0 ] && [ "$(from_disk warm)" = "$n" ] && ok || { bad "warm compiled"; cat "$tmp/warm.err"; }
grep -q 'pipeline cache [1-9][0-9]* bytes loaded' "$tmp/warm.err" && ok || bad "warm: pipeline cache not loaded"
cmp -s "$tmp/cold.png" "$tmp/warm.png" && ok || bad "warm image differs"

r "$tmp/off" off --no-shader-cache
[ "$(compiled off)" = "$n" ] && [ ! -e "$tmp/off" ] && ok || bad "--no-shader-cache: compiled $(compiled off), folder made"
PASSGRAPH_NO_SHADER_CACHE=1 r "$tmp/off" offenv
[ "$(compiled offenv)" = "$n" ] && [ ! -e "$tmp/off" ] && ok || bad "PASSGRAPH_NO_SHADER_CACHE: compiled $(compiled offenv)"

f=$(ls "$tmp/c/spirv/"*.spv | head -1)
head -c 100 "$f" >"$tmp/cut" && cp "$tmp/cut" "$f"
r "$tmp/c" corrupt
grep -q "note: shader cache file .* is corrupt" "$tmp/corrupt.err" && [ "$(compiled corrupt)" = 1 ] && ok ||
  { bad "corrupt .spv"; cat "$tmp/corrupt.err"; }
cmp -s "$tmp/cold.png" "$tmp/corrupt.png" && ok || bad "image after a corrupt .spv differs"

r /proc/passgraph-no-such-dir unwritable
grep -q "note: shader cache folder" "$tmp/unwritable.err" && [ -s "$tmp/unwritable.png" ] && ok ||
  { bad "unwritable cache folder"; cat "$tmp/unwritable.err"; }
grep -q "validation message" "$tmp"/*.err && bad "validation messages" || ok

check_finish cache_test
