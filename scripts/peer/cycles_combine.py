#!/usr/bin/env python3
"""Combines independent runs of scripts/peer/cycles_sphere.py (one seed each) into the fixture
tests/fixtures/peer/cycles_sphere.json: per equator bin and channel the mean over the runs and its
standard error from their spread (sd / sqrt(runs)), with how the numbers were made.

  scripts/peer/cycles_combine.py OUT.json RUN1.json RUN2.json ...
"""
import json
import math
import sys


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    runs = [json.load(open(p)) for p in sys.argv[2:]]
    k = len(runs)
    first = runs[0]
    for r in runs:
        if r['pixels'] != first['pixels'] or r['samples'] != first['samples']:
            sys.exit('cycles_combine: the runs differ in pixels or samples')
    if len({r['seed'] for r in runs}) != k:
        sys.exit('cycles_combine: two runs share a seed')
    bins = []
    for b in range(len(first['mean'])):
        mean, se = [], []
        for c in range(3):
            v = [r['mean'][b][c] for r in runs]
            m = sum(v) / k
            var = sum((x - m) ** 2 for x in v) / (k - 1)
            mean.append(m)
            se.append(math.sqrt(var / k))
        bins.append({'theta_deg': [10 * b, 10 * b + 10], 'pixels': first['pixels'][b], 'mean': mean, 'se': se})
    out = {
        'what': 'Equator bins of the Skin1 sphere of bench/skin1-sphere.json rendered by Blender Cycles '
                '(issue 12 section 5): mean linear radiance per bin and channel over %d independent renders '
                'and its standard error from their spread' % k,
        'how': 'nice -n 10 blender -b --factory-startup -P scripts/peer/cycles_sphere.py -- seedS.json %d S 2 '
               'for S in %s, then scripts/peer/cycles_combine.py' % (first['samples'], ' '.join(str(r['seed']) for r in runs)),
        'renderer': 'Blender ' + first['renderer'] + ' (Debian bookworm package 3.4.1+dfsg-2+b1), Cycles on the CPU',
        'samples_per_run': first['samples'],
        'runs': k,
        'seeds': [r['seed'] for r in runs],
        'size': first['size'],
        'band_rows': first['band_rows'],
        'bins': bins,
    }
    head = json.dumps({k: v for k, v in out.items() if k != 'bins'}, indent=1)[:-2]
    rows = ',\n  '.join(json.dumps(b) for b in bins)
    with open(sys.argv[1], 'w') as f:
        f.write(head + ',\n "bins": [\n  ' + rows + '\n ]\n}\n')


main()
