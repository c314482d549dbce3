#!/usr/bin/env python3
"""ab_table.py FILE - the markdown table of an A/B run: lines "round=R side=before|after render: P WxH
lights=L gpu=X ms [...]" (the summary lines of `passgraph render --frames N`, each already a
median over its frames), alternating sides round by round. Prints, per pipeline and light count,
the median GPU frame time of each side over the rounds and after/before."""
import re
import statistics
import sys

rows = {}
for line in open(sys.argv[1]):
    m = re.match(r'round=(\d+) side=(\w+) render: (\S+) (\d+x\d+) lights=(\d+) gpu=([\d.]+) ms', line)
    if not m:
        continue
    _, side, pipe, size, lights, ms = m.groups()
    rows.setdefault((pipe, size, int(lights)), {}).setdefault(side, []).append(float(ms))

print('| pipeline | size | lights | before ms | after ms | after/before | rounds |')
print('|---|---|---:|---:|---:|---:|---:|')
for (pipe, size, lights), sides in rows.items():
    b, a = statistics.median(sides['before']), statistics.median(sides['after'])
    print(f'| {pipe} | {size} | {lights:,} | {b:.3f} | {a:.3f} | {a / b:.4f} | {len(sides["after"])} |')
