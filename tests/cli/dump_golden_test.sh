#!/usr/bin/env bash
# dump_golden_test.sh PASSGRAPH - the plan of every shipped pipeline is what tests/corpus/dumps
# holds, byte for byte (tests/corpus/dumps/MANIFEST lists the files and the dump arguments).
# PG_UPDATE_GOLDEN=1 writes the files instead of comparing them.
set -u
. "$(dirname "$0")/check_lib.sh"
PG=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
dir="$root/tests/corpus/dumps"
cd "$root" || exit 1
while IFS= read -r line; do
  case "$line" in ''|'#'*) continue ;; esac
  name=$(printf '%s' "${line%%|*}" | tr -d ' ')
  read -r -a args <<<"${line#*|}"
  if ! "$PG" dump "${args[@]}" --out "$tmp/$name" 2>"$tmp/err"; then
    bad "$name: passgraph dump ${args[*]} failed: $(head -c 400 "$tmp/err")"
    continue
  fi
  if [ "${PG_UPDATE_GOLDEN:-0}" = 1 ]; then
    cp "$tmp/$name" "$dir/$name" && ok
  elif cmp -s "$tmp/$name" "$dir/$name"; then
    ok
  else
    bad "$name: the plan differs from tests/corpus/dumps/$name (passgraph dump ${args[*]}):"
    diff "$dir/$name" "$tmp/$name" | head -20
  fi
done <"$dir/MANIFEST"
check_finish dump_golden_test
