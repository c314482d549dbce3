#!/usr/bin/env bash
# accuracy_table.sh [--write] [--part all|compare|tests] [BUILD_DIR] - the generated tables of
# docs/accuracy.md, each headed by the command, commit and device that produced it:
#   compare: every pipeline and G-buffer variant against pipelines/naive.json with
#            `passgraph compare` on the default scene and the Sponza (cis565 scenario) at 100,
#            1000 and 5000 lights, 640x360, time 2, median GPU ms of 3 frames; plus the opt-in
#            per-cluster cap (--set max_lights=N for N in $PG_CAPS) at 5000 lights;
#   tests:   runs BUILD_DIR/tests/test_gpu_clustered and turns its "bound:", "accuracy:", "far:",
#            "overflow:", "capped:" and "lights:" lines into the tables of what the test enforces
#            (its bounds are the #defines at the top of tests/test_gpu_clustered.c).
# Prints markdown; --write replaces the sections between the markers
#   <!-- accuracy_table.sh PART begin --> ... <!-- accuracy_table.sh PART end -->
# in docs/accuracy.md instead. Needs ../shared/assets/dabrovic-sponza for the Sponza rows.
# Environment: PG_SIZE (640x360), PG_LIGHTS ("100 1000 5000"), PG_CAPS ("512 2048").
set -euo pipefail
cd "$(dirname "$0")/../.."
WRITE=0
PART=all
BUILD=build
while [ $# -gt 0 ]; do
  case $1 in
    --write) WRITE=1 ;;
    --part) PART=$2; shift ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    *) BUILD=$1 ;;
  esac
  shift
done
case $PART in all|compare|tests) ;; *) echo "accuracy_table.sh: --part all|compare|tests" >&2; exit 2 ;; esac
PG=$BUILD/passgraph
# the reference is named explicitly (compare's default is pipelines/reference.json, bit-identical
# to naive); PG_REFERENCE picks another
REFERENCE=${PG_REFERENCE:-pipelines/naive.json}
TEST=$BUILD/tests/test_gpu_clustered
SPONZA=../shared/assets/dabrovic-sponza/sponza.gltf
SIZE=${PG_SIZE:-640x360}
LIGHTS=${PG_LIGHTS:-100 1000 5000}
CAPS=${PG_CAPS:-512 2048}
DOC=docs/accuracy.md

commit=$(git rev-parse --short=12 HEAD)
# what the run measured differs from the commit when tracked files (other than the doc it
# writes) are modified
if [ -n "$(git status --porcelain --untracked-files=no -- . ":(exclude)$DOC")" ]; then
  commit="$commit + uncommitted changes"
fi
mesa=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || echo unknown)
today=$(date -u +%Y-%m-%d)
# lavapipe's GPU ms are CPU time: they depend on what else the machine runs
load() { cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown; }

get() { sed -n "s/.* $1=\([^ ]*\).*/\1/p" <<<"$2" | head -1; }
label_of() { # the test's variant names -> the tables' names
  case $1 in
    forward_plus) echo "forward+" ;;
    forward_plus_prepass_equal) echo "forward+, prepass_test=equal" ;;
    deferred_float) echo "deferred float (rgba32f position)" ;;
    deferred_float_rgba16f_position) echo "deferred float, rgba16f position" ;;
    deferred_oct16) echo "deferred oct16" ;;
    deferred_packed) echo "deferred packed" ;;
    *) echo "$1" ;;
  esac
}

variants=(
  "forward+|pipelines/forward_plus.json|"
  "deferred float|pipelines/deferred.json|"
  "deferred float, rgba16f position|pipelines/deferred.json|--set position_format=rgba16f"
  "deferred oct16|pipelines/deferred_oct16.json|"
  "deferred packed|pipelines/deferred_packed.json|"
)

compare_row() { # n label pipe extra... -> appends one table row to body (needs sargs)
  local n=$1 label=$2 pipe=$3
  shift 3
  local out line over
  out=$($PG compare --pipeline "$pipe" --reference "$REFERENCE" "${sargs[@]}" --lights "$n" --size "$SIZE" --time 2 --frames 3 "$@" 2>&1)
  line=$(grep '^compare:' <<<"$out") || { echo "accuracy_table.sh: compare failed: $out" >&2; exit 1; }
  [ -n "$device" ] || device=$(sed -n 's/^passgraph: device //p' <<<"$out" | head -1)
  over=$(get overflow_clusters "$line"); [ -n "$over" ] || over=-
  body+=$(printf "| %s | %s | %.1f | %.1f | %.3g | %s | %.3g | %s | %.3f%% | %s |" "$n" "$label" \
    "$(get gpu_ms "$line")" "$(get reference_gpu_ms "$line")" "$(get rmse_linear "$line")" \
    "$(get psnr_linear "$line")" "$(get max_abs_linear "$line")" "$(get max_abs_display "$line")" \
    "$(awk -v x="$(get over_threshold "$line")" 'BEGIN{print x*100}')" "$over")$'\n'
}

part_compare() {
  device=""
  body=""
  local load0
  load0=$(load)
  local scene
  local header="| lights | pipeline | GPU ms | naive ms | RMSE (linear) | PSNR (dB) | max abs (linear) | max abs (8-bit) | pixels > 1/255 | overflowing clusters |
|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|"
  for scene in default sponza; do
    if [ $scene = sponza ]; then
      [ -f $SPONZA ] || { body+=$'\n(Sponza not found: skipped)\n'; continue; }
      sargs=(--scene $SPONZA --scenario assets/scenarios/cis565.json)
    else
      sargs=(--scene default)
    fi
    body+=$'\n'"### $scene, $SIZE, shipped defaults"$'\n\n'"$header"$'\n'
    for n in $LIGHTS; do
      for v in "${variants[@]}"; do
        IFS='|' read -r label pipe extra <<<"$v"
        # shellcheck disable=SC2086
        compare_row "$n" "$label" "$pipe" $extra
      done
    done
  done
  local n_over
  n_over=$(awk -F'|' 'NF > 10 && $11 ~ /[1-9]/' <<<"$body" | wc -l)
  if [ "$n_over" -gt 0 ]; then
    body+=$'\n'"*In this run $n_over row(s) above had overflowing clusters with the shipped defaults: those"
    body+=$'\n'"pipelines capped the lights per cluster, and the dropped lights dominate their error.*"$'\n'
  fi
  body+=$'\n'"### The opt-in per-cluster cap: \`--set max_lights=N\`, 5000 lights, $SIZE"$'\n\n'"$header"$'\n'
  for scene in default sponza; do
    if [ $scene = sponza ]; then
      [ -f $SPONZA ] || continue
      sargs=(--scene $SPONZA --scenario assets/scenarios/cis565.json)
    else
      sargs=(--scene default)
    fi
    for cap in $CAPS; do
      for v in "forward+|pipelines/forward_plus.json" "deferred float|pipelines/deferred.json" \
               "deferred packed|pipelines/deferred_packed.json"; do
        IFS='|' read -r label pipe <<<"$v"
        compare_row 5000 "$scene: $label, max_lights=$cap" "$pipe" --set max_lights="$cap"
      done
    done
  done
  printf '%s\n' "*Generated by \`scripts/tables/accuracy_table.sh --part compare\` (each row: \`passgraph compare --pipeline P --reference $REFERENCE --scene S [--scenario assets/scenarios/cis565.json] --lights N --size $SIZE --time 2 --frames 3\`) at commit $commit on $device (Mesa $mesa), $today; load average at the start $load0 on $(nproc) CPUs.*"
  printf '%s' "$body"
}

part_tests() {
  local out rc=0 load0
  load0=$(load)
  out=$("$TEST" 2>&1) || rc=$?
  local dev summary
  dev=$(sed -n 's/^device: //p' <<<"$out" | head -1)
  summary=$(grep -E '^test_gpu_clustered: [0-9]+ passed' <<<"$out" || echo "test_gpu_clustered: no summary (exit $rc)")
  printf '%s\n' "*Generated by \`scripts/tables/accuracy_table.sh --part tests\` from one run of \`$TEST\` at commit $commit on $dev (Mesa $mesa), $today (load average at the start $load0 on $(nproc) CPUs): $summary.*"
  local dropped
  dropped=$(grep 'NO-OVERFLOW-BY-DEFAULT' <<<"$out" |
    sed -n 's/.*CHECK failed: !dropped: \(.*\) \([a-z_0-9]*\): NO-OVERFLOW-BY-DEFAULT: \([0-9]*\) clusters overflowed, \([0-9]*\) light refs.*/\1|\2|\3|\4/p' |
    awk -F'|' '{ k = $1 ": " $3 " clusters overflowed, " $4 " light refs dropped"; if (!(k in seen)) { seen[k] = $2; order[n++] = k } else seen[k] = seen[k] ", " $2 }
               END { for (i = 0; i < n; i++) print "- " order[i] " (" seen[order[i]] ")" }')
  if [ -n "$dropped" ]; then
    echo
    echo "**In this run these frames dropped lights with the shipped defaults (the check"
    echo "NO-OVERFLOW-BY-DEFAULT failed); their bounds were not asserted and they are left out of the"
    echo "worst cases below:**"
    echo
    echo "$dropped"
  fi
  echo
  echo "### Per variant: bound and worst case"
  echo
  echo "| variant | bound asserted (every frame, every pixel and channel) | worst measured | frames asserted |"
  echo "|---|---|---|---:|"
  local line v
  while IFS= read -r line; do
    v=$(get variant "$line")
    local frames ne
    frames=$(get frames "$line"); ne=$(get not_evaluated "$line")
    local fr="$frames"; [ "$ne" = 0 ] || fr="$frames (+$ne not asserted)"
    case $v in
      forward_plus)
        printf "| forward+ | HDR output byte-identical to naive (memcmp, same hdr_format) | identical in %s of %s | %s |\n" \
          "$(get identical "$line")" "$frames" "$fr" ;;
      *)
        local label bound worst
        label=$(label_of "$v")
        bound="\|d\| ≤ $(get px_a "$line") \|ref\| + $(get px_b "$line") peak"
        worst="$(get worst_px_usage "$line") of the bound [$(sed -n 's/.*worst_px_usage=[^ ]* \[\([^]]*\)\].*/\1/p' <<<"$line")]; max \|d\| = $(get worst_max_rel_peak "$line") peak"
        if [ "$(get disp_max_bound "$line")" != - ]; then
          bound+="; display ≤ $(get disp_max_bound "$line") steps; ≤ $(get disp_share_bound "$line") of the pixels > 1 step"
          worst+="; $(get worst_disp_max "$line") steps [$(sed -n 's/.*worst_disp_max=[^ ]* \[\([^]]*\)\].*/\1/p' <<<"$line")]; $(get worst_disp_share "$line") > 1 step [$(sed -n 's/.*worst_disp_share=[^ ]* \[\([^]]*\)\].*/\1/p' <<<"$line")]"
        fi
        printf "| %s | %s | %s | %s |\n" "$label" "$bound" "$worst" "$fr" ;;
    esac
  done < <(grep '^bound:' <<<"$out")
  echo
  echo "### Every frame"
  echo
  local sw
  sw=$(grep '^sweep:' <<<"$out" | head -1)
  echo "$(get size "$sw"), time $(get time "$sw"), seed $(get seed "$sw"); the shipped pipeline defaults (no \`max_lights\` set)."
  echo "\"use\" = the worst pixel's error as a share of its per-pixel bound (1 = at the bound); display ="
  echo "the largest 8-bit step / the share of pixels more than one step off."
  echo
  echo "| scene | lights | shading, HDR | lights dropped (clusters / refs) | forward+ | deferred float: max \|d\|/peak, use | oct16: max \|d\|/peak, use, display | packed: max \|d\|/peak, use, display |"
  echo "|---|---:|---|---:|---|---|---|---|"
  local key prev="" row=""
  while IFS= read -r line; do
    key="$(get scene "$line") $(get lights "$line") $(get shading "$line") $(get hdr "$line")"
    if [ "$key" != "$prev" ]; then
      [ -z "$row" ] || echo "$row |"
      prev=$key
      read -r sc n shd hdr <<<"$key"
      row="| $sc | $n | $shd, $hdr | $(get overflow_clusters "$line") / $(get overflow_dropped "$line")"
    fi
    local cell asserted=""
    grep -q 'bounds not asserted' <<<"$line" && asserted=" (not asserted)"
    case $(get variant "$line") in
      forward_plus)
        if [ "$(get identical "$line")" = 1 ]; then cell="identical"; else cell="differs: max \|d\| $(get max_rel_peak "$line") peak"; fi ;;
      deferred_float) cell="$(get max_rel_peak "$line"), $(get px_usage "$line")" ;;
      *) cell="$(get max_rel_peak "$line"), $(get px_usage "$line"), $(get disp_max "$line") / $(get disp_share "$line")" ;;
    esac
    row+=" | $cell$asserted"
  done < <(grep '^accuracy:' <<<"$out")
  [ -z "$row" ] || echo "$row |"
  echo
  echo "### Far from the origin"
  echo
  echo "The atrium moved by (1e5, 0, 1e5), camera and lights with it, 256 lights, $(sed -n 's/^far: .* size=\([^ ]*\).*/\1/p' <<<"$out" | head -1):"
  echo
  echo "| variant | byte-identical | max abs / peak | RMSE | max abs (8-bit) | pixels > 1/255 |"
  echo "|---|---|---:|---:|---:|---:|"
  while IFS= read -r line; do
    printf "| %s | %s | %s | %s | %s | %s |\n" "$(label_of "$(get variant "$line")")" \
      "$( [ "$(get identical "$line")" = 1 ] && echo yes || echo no)" "$(get max_rel_peak "$line")" \
      "$(get rmse "$line")" "$(get disp_max "$line")" "$(get disp_share "$line")"
  done < <(grep '^far:' <<<"$out")
  echo
  echo "### Explicit caps, light counts"
  echo
  while IFS= read -r line; do
    printf -- "- %s with \`max_lights=%s\` (explicit cap), %s lights: %s clusters overflow, %s light refs dropped\n" \
      "$(get scene "$line")" "$(get max_lights "$line")" "$(get lights "$line")" \
      "$(get overflow_clusters "$line")" "$(get overflow_dropped "$line")"
  done < <(grep '^capped:' <<<"$out")
  while IFS= read -r line; do
    printf -- "- all 64 lights in a 2 cm box, \`max_lights=8\`, %s: %s clusters overflow, %s light refs dropped; two runs byte-identical: %s\n" \
      "$(get pipeline "$line")" "$(get overflow_clusters "$line")" "$(get overflow_dropped "$line")" \
      "$( [ "$(get deterministic "$line")" = 1 ] && echo yes || echo no)"
  done < <(grep '^overflow:' <<<"$out")
  grep '^lights: ' <<<"$out" | sed 's/^lights: /- /'
}

emit() { # part -> stdout
  case $1 in compare) part_compare ;; tests) part_tests ;; esac
}

parts=(compare tests)
[ "$PART" = all ] || parts=("$PART")
for p in "${parts[@]}"; do
  text=$(emit "$p")
  if [ $WRITE = 1 ]; then
    begin="<!-- accuracy_table.sh $p begin -->"
    end="<!-- accuracy_table.sh $p end -->"
    grep -qF "$begin" $DOC && grep -qF "$end" $DOC || { echo "accuracy_table.sh: $DOC lacks the $p markers" >&2; exit 1; }
    tmp=$(mktemp)
    printf '%s\n' "$text" >"$tmp.part"
    awk -v b="$begin" -v e="$end" -v f="$tmp.part" '
      $0 == b { print; while ((getline l < f) > 0) print l; skip = 1; next }
      $0 == e { skip = 0 }
      !skip { print }' $DOC >"$tmp"
    mv "$tmp" $DOC
    rm -f "$tmp.part"
    echo "accuracy_table.sh: wrote the $p section of $DOC"
  else
    printf '%s\n\n' "$text"
  fi
done
