#!/usr/bin/env bash
# ambient_identical.sh BEFORE AFTER - the ambient push constant renders what the PG_AMBIENT define did:
# for each shipped pipeline and ambient 0 / 0.05: render with BEFORE and AFTER (160x90, 64 lights, rgba32f, --validation) and cmp the PNG and EXR
B=$1; A=$2; t=$(mktemp -d)
for p in naive forward_plus deferred deferred_oct16 deferred_packed reference; do for a in 0 0.05; do
  for s in B A; do bin=${!s}; root=$(cd "$(dirname "$bin")/.." && pwd)
    $bin render --validation --pipeline $root/pipelines/$p.json --size 160x90 --lights 64 --set ambient=$a --set hdr_format=rgba32f --out $t/$s.png --hdr-out $t/$s.exr >/dev/null 2>$t/err || { echo "$p $a $s: failed"; cat $t/err; }
  done
  if cmp -s $t/B.png $t/A.png && cmp -s $t/B.exr $t/A.exr; then echo "$p ambient=$a: display and HDR byte-identical"; else echo "$p ambient=$a: DIFFER"; fi
done; done; rm -rf $t
