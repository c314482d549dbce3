#!/usr/bin/env bash
# accuracy_table.sh [BUILD_DIR] - the error-against-naive tables of docs/accuracy.md: every
# pipeline and G-buffer variant against pipelines/naive.json on the default scene and the Sponza
# (cis565 scenario) at 100, 1000 and 5000 lights, 640x360, time 2, median GPU ms of 3 frames.
# The reference is named explicitly (compare's default is pipelines/reference.json); PG_REFERENCE
# picks another. Prints markdown. Needs ../shared/assets/dabrovic-sponza for the Sponza rows.
set -euo pipefail
cd "$(dirname "$0")/.."
PG=${1:-build}/passgraph
SPONZA=../shared/assets/dabrovic-sponza/sponza.gltf
SIZE=${PG_SIZE:-640x360}
LIGHTS=${PG_LIGHTS:-100 1000 5000}
REFERENCE=${PG_REFERENCE:-pipelines/naive.json}
variants=(
  "forward+|pipelines/forward_plus.json|"
  "deferred float|pipelines/deferred.json|"
  "deferred float, rgba16f position|pipelines/deferred.json|--set position_format=rgba16f"
  "deferred oct16|pipelines/deferred_oct16.json|"
  "deferred packed|pipelines/deferred_packed.json|"
)
get() { sed -n "s/.* $1=\([^ ]*\).*/\1/p" <<<"$2"; }
for scene in default sponza; do
  if [ $scene = sponza ]; then
    [ -f $SPONZA ] || { echo "(Sponza not found: skipped)"; continue; }
    sargs=(--scene $SPONZA --scenario assets/scenarios/cis565.json)
  else
    sargs=(--scene default)
  fi
  echo
  echo "### $scene, $SIZE"
  echo
  echo "| lights | pipeline | GPU ms | naive ms | RMSE (linear) | PSNR (dB) | max abs (linear) | max abs (8-bit) | pixels > 1/255 | overflowing clusters |"
  echo "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|"
  for n in $LIGHTS; do
    for v in "${variants[@]}"; do
      IFS='|' read -r label pipe extra <<<"$v"
      # shellcheck disable=SC2086
      line=$($PG compare --pipeline $pipe --reference "$REFERENCE" "${sargs[@]}" --lights $n --size $SIZE --time 2 --frames 3 --quiet $extra | grep '^compare:')
      over=$(get overflow_clusters "$line"); [ -n "$over" ] || over=-
      printf "| %s | %s | %.1f | %.1f | %.3g | %s | %.3g | %s | %.3f%% | %s |\n" "$n" "$label" \
        "$(get gpu_ms "$line")" "$(get reference_gpu_ms "$line")" "$(get rmse_linear "$line")" \
        "$(get psnr_linear "$line")" "$(get max_abs_linear "$line")" "$(get max_abs_display "$line")" \
        "$(awk -v x="$(get over_threshold "$line")" 'BEGIN{print x*100}')" "$over"
    done
  done
done
