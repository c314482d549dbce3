#!/usr/bin/env bash
# symbols_check.sh LIB.a... - every global symbol a passgraph library defines starts with pg_
# (or pj_, the pipeline loader's internal helpers shared between its files; C++ symbols live in
# namespaces; names starting with __ are the compiler's and sanitizers' own, e.g. ASan's
# __odr_asan.* indicators): static libraries share one global namespace with whatever links them, so an
# unprefixed helper (describe, substitute, ...) could collide with a user's or another library's.
set -euo pipefail
bad=0
for lib in "$@"; do
  while read -r sym; do
    echo "FAIL: $(basename "$lib") defines global '$sym' (prefix it pg_, or make it static)"
    bad=$((bad + 1))
  done < <(nm --defined-only "$lib" | awk '$2 ~ /^[TDBR]$/ {print $3}' | grep -vE '^(pg_|pj_|_Z|__)' || true)
done
echo "symbols_check: $# libraries, $bad unprefixed globals"
[ "$bad" -eq 0 ]
