#!/usr/bin/env bash
# alias_table.sh [BEFORE_PASSGRAPH] - transient memory of every shipped pipeline at 1920x1080,
# 256 lights, default scene, as a markdown table:
#   unaliased    sum of the transient resources (passgraph dump, estimated sizes)
#   before       aliased bytes by BEFORE_PASSGRAPH's `dump` (a build of the one-resource-per-block
#                scheme; column left out without the argument)
#   plan         aliased bytes now (passgraph dump: offsets from estimated sizes and alignments)
#   device       the VkDeviceMemory passgraph render allocates for transients with and without
#                sharing (real vkGet*MemoryRequirements; `render --explain` line "device transient
#                memory"), on the first Vulkan device (lavapipe on the CI machine)
# Uses build/passgraph; renders each pipeline once at 1920x1080 (about a minute on lavapipe).
set -euo pipefail
cd "$(dirname "$0")/../.."
BEFORE=${1:-}
PG=build/passgraph
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
num() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['totals'][sys.argv[2]])" "$1" "$2"; }
pct() { python3 -c "import sys; u,a=int(sys.argv[1]),int(sys.argv[2]); print(f'{100*(u-a)/u:.1f}%')" "$1" "$2"; }
mib() { python3 -c "import sys; print(f'{int(sys.argv[1])/1048576:.2f}')" "$1"; }
device=$("$PG" devices 2>/dev/null | sed -n "s/^0: //p" | head -1)
echo "Transient memory at 1920x1080, 256 lights, default scene (\`scripts/tables/alias_table.sh${BEFORE:+ $BEFORE}\`, $(git rev-parse --short HEAD), device: ${device:-first Vulkan device}). MiB; saving vs. unaliased in brackets."
echo
if [ -n "$BEFORE" ]; then
  echo "| pipeline | unaliased | before (one per block) | plan (offsets) | device unaliased | device aliased |"
  echo "|---|---:|---:|---:|---:|---:|"
else
  echo "| pipeline | unaliased | plan (offsets) | device unaliased | device aliased |"
  echo "|---|---:|---:|---:|---:|"
fi
for p in pipelines/*.json; do
  name=$(basename "$p" .json)
  "$PG" dump --pipeline "$p" --size 1920x1080 --lights 256 --format json --out "$OUT/now.json" >/dev/null
  un=$(num "$OUT/now.json" transient_bytes_unaliased)
  al=$(num "$OUT/now.json" transient_bytes_aliased)
  line=$("$PG" render --pipeline "$p" --size 1920x1080 --lights 256 --explain --out "$OUT/$name.png" 2>/dev/null |
         grep '^explain: device transient memory')
  dun=$(echo "$line" | sed -E 's/.*memory ([0-9]+) B unaliased.*/\1/')
  dal=$(echo "$line" | sed -E 's/.* -> ([0-9]+) B aliased.*/\1/')
  row="| $name | $(mib "$un") |"
  if [ -n "$BEFORE" ]; then
    "$BEFORE" dump --pipeline "$p" --size 1920x1080 --lights 256 --format json --out "$OUT/before.json" >/dev/null
    bal=$(num "$OUT/before.json" transient_bytes_aliased)
    row="$row $(mib "$bal") ($(pct "$un" "$bal")) |"
  fi
  echo "$row $(mib "$al") ($(pct "$un" "$al")) | $(mib "$dun") | $(mib "$dal") ($(pct "$dun" "$dal")) |"
done
