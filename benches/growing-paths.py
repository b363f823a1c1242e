#!/usr/bin/env python3
"""Where a growing walker's distance comes from: for each recording of a walk that grows
(`ontogeny eval CHAMPION.lsys --config CONFIG --record DIR`), the distance of part 0 in the
ground plane from the start of the measurement (net and along its path), the times at which
parts appear during the measured walk, and how much of the path part 0 covered within 1.5 s
after a part appeared.

    for r in $(seq 1 10); do
      ontogeny eval runs/growing-experiment/during/rep-$r/best.lsys \\
        --config examples/growing-experiment-during.toml --record rec-$r
    done
    python3 benches/growing-paths.py rec-*/recording.json
"""
import json, math, sys

WINDOW = 1.5  # seconds after a part appears

for path in sys.argv[1:]:
    d = json.load(open(path))
    frames = [f for f in d['frames'] if f['phase'] == 'measuring']
    xs = [(f['t'], f['parts'][0][0]) for f in frames]
    grew = [f['t'] for f in frames
            if 'growth' in f and any('appears' in e for e in f['growth'])]
    total = after = 0.0
    for (_, a), (t1, b) in zip(xs, xs[1:]):
        step = math.hypot(b[0] - a[0], b[2] - a[2])
        total += step
        if any(g <= t1 <= g + WINDOW for g in grew):
            after += step
    start, end = xs[0][1], xs[-1][1]
    net = math.hypot(end[0] - start[0], end[2] - start[2])
    share = after / total if total else 0.0
    print(f"{path}: fitness {d['fitness']:.2f}, net {net:.2f} m, path {total:.2f} m, "
          f"parts appear at {[round(g, 2) for g in grew]} s, "
          f"path within {WINDOW} s after: {after:.2f} m ({share:.0%})")
