#!/usr/bin/env bash
# compare_builds.sh OLD_DIR NEW_DIR [ROUNDS] - GPU time of the same renders with two passgraph
# checkouts (each built: DIR/build/passgraph, run from DIR so each uses its own pipelines and
# shaders), alternating old/new ROUNDS times (default 3) so machine noise hits both alike.
# Prints a markdown table of medians: frame, light assignment (assign_lights) and its share.
# Configurations: $PG_CB_CONFIGS, lines of "LABEL|PIPELINE|LIGHTS|extra render args"; default:
# clustered deferred (float) and forward+ on the Sponza (cis565 scenario) at 640x360, 1,000 and
# 4,000 lights, 5 frames each (the render's own median).
set -euo pipefail
OLD=$(cd "$1" && pwd)
NEW=$(cd "$2" && pwd)
ROUNDS=${3:-3}
SPONZA=${PG_SPONZA:-$(cd "$(dirname "$0")/../.." && pwd)/shared/assets/dabrovic-sponza/sponza.gltf}
CONFIGS=${PG_CB_CONFIGS:-"deferred 1000|pipelines/deferred.json|1000|
deferred 4000|pipelines/deferred.json|4000|
forward+ 1000|pipelines/forward_plus.json|1000|
forward+ 4000|pipelines/forward_plus.json|4000|"}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

median() { sort -g | awk '{a[NR] = $1} END {if (NR % 2) print a[(NR + 1) / 2]; else print (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

i=0
while IFS='|' read -r label pipeline lights extra; do
  [ -z "$label" ] && continue
  i=$((i + 1))
  for r in $(seq "$ROUNDS"); do
    for side in old new; do
      dir=$OLD
      [ "$side" = new ] && dir=$NEW
      # shellcheck disable=SC2086
      line=$(cd "$dir" && build/passgraph render --pipeline "$pipeline" --scene "$SPONZA" \
        --scenario assets/scenarios/cis565.json --lights "$lights" --size 640x360 --frames 5 \
        --out "$tmp/o.png" $extra 2>/dev/null | grep '^render:')
      echo "$line" | sed -E 's/.* gpu=([0-9.]+) ms.*/\1/' >>"$tmp/$i.$side.frame"
      echo "$line" | sed -E 's/.*assign_lights ([0-9.]+).*/\1/' >>"$tmp/$i.$side.assign"
    done
  done
  echo "$label" >"$tmp/$i.label"
done <<<"$CONFIGS"

echo "| configuration | old frame ms | old assignment ms (share) | new frame ms | new assignment ms (share) | frame speed-up |"
echo "|---|---|---|---|---|---|"
for k in $(seq "$i"); do
  of=$(median <"$tmp/$k.old.frame"); oa=$(median <"$tmp/$k.old.assign")
  nf=$(median <"$tmp/$k.new.frame"); na=$(median <"$tmp/$k.new.assign")
  awk -v l="$(cat "$tmp/$k.label")" -v of="$of" -v oa="$oa" -v nf="$nf" -v na="$na" 'BEGIN {
    printf "| %s | %.1f | %.1f (%.0f%%) | %.1f | %.1f (%.0f%%) | %.2fx |\n", l, of, oa, 100 * oa / of, nf, na,
           100 * na / nf, of / nf }'
done
echo
echo "old: $(git -C "$OLD" rev-parse --short HEAD), new: $(git -C "$NEW" rev-parse --short HEAD);" \
  "$ROUNDS alternating rounds, medians; device: $(cd "$NEW" && build/passgraph devices 2>/dev/null | head -1)"
