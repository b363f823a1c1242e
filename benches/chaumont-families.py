#!/usr/bin/env python3
"""Chaumont et al.'s families of walkers (section 3.6, Figure 2), assigned by a written rule
rather than by eye, from a recording of each champion's walk
(`ontogeny eval CHAMPION --task walker --record DIR`, or with the run's --config).

The rule, applied in this order (the first that fits names the family):

1. two blocks (the body has two parts):
   - rolls over (Figure 2d) when, during the measured walk, some axis of the root part turns
     upside down and back at least twice: its vertical component passes from above +0.5 to
     below -0.5 or back (60 degrees either side of the horizontal, so rocking about a lying
     axis does not count) at least 4 times (a rolling block turns two axes over twice a turn);
   - two blocks, one pushing the other (Figure 2a), otherwise.
2. a chain (every part jointed to at most two others) of three or more parts:
   - caterpillar (Figure 2b) when a part at an end of the chain has at least twice the volume
     of every other part (a body pushed by an appendage of several blocks);
   - crawler (Figure 2c) otherwise (blocks of like size that crawl on their corners).
   Rolling is not tested for chains: the segments of a writhing chain turn over as it crawls
   (the three champions of Chaumont's GA over Hornby & Pollack's genome: the median segment's
   axes turned over 18-40 times in 20 s), so a part's turning does not tell rolling from
   crawling there.
3. a branched body (a part jointed to three or more):
   - upright (Figure 2f) when the root part's centre stays, on average over the walk, higher
     than its own longest side (it stands rather than lies);
   - counterbalanced (Figure 2e) otherwise (an appendage beside the moving ones).

The rule is ours: the paper names its families by their look and motion, not by a rule.

    ontogeny eval runs/chaumont-1/best.json --config examples/chaumont-walker.toml --record rec-1
    python3 benches/chaumont-families.py rec-*/recording.json
"""
import json
import math
import sys

FLIP = 0.5  # vertical component beyond which an axis counts as up or down


def rotate(q, v):
    """v rotated by the unit quaternion q = [i, j, k, w]."""
    x, y, z, w = q
    # t = 2 q_vec x v; v' = v + w t + q_vec x t
    tx = 2 * (y * v[2] - z * v[1])
    ty = 2 * (z * v[0] - x * v[2])
    tz = 2 * (x * v[1] - y * v[0])
    return (
        v[0] + w * tx + (y * tz - z * ty),
        v[1] + w * ty + (z * tx - x * tz),
        v[2] + w * tz + (x * ty - y * tx),
    )


def flips(frames):
    """The most times one axis of the root turned over (above +FLIP to below -FLIP or back)."""
    most = 0
    for axis in ((1, 0, 0), (0, 1, 0), (0, 0, 1)):
        side, count = 0, 0
        for f in frames:
            up = rotate(f["parts"][0][1], axis)[1]
            now = 1 if up > FLIP else -1 if up < -FLIP else side
            if side and now != side:
                count += 1
            side = now
        most = max(most, count)
    return most


def family(record):
    creature = record["creature"]
    parts = creature["parts"]
    frames = [f for f in record["frames"] if f.get("phase", "measuring") == "measuring"]
    if not frames:
        return "none (no measured walk)", {}
    degree = [0] * len(parts)
    for j in creature["joints"]:
        degree[j["parent"]] += 1
        degree[j["child"]] += 1
    volume = [s[0] * s[1] * s[2] for s in (p["size"] for p in parts)]
    turned = flips(frames)
    facts = {"parts": len(parts), "flips": turned}
    if len(parts) == 2:
        return ("rolls over (2d)" if turned >= 4 else "two blocks (2a)"), facts
    if len(parts) >= 3 and max(degree) <= 2:
        ends = [i for i, d in enumerate(degree) if d == 1]
        heavy = any(
            all(volume[e] >= 2 * volume[i] for i in range(len(parts)) if i != e) for e in ends
        )
        return ("caterpillar (2b)" if heavy else "crawler (2c)"), facts
    if len(parts) == 1:
        return "one block", facts
    height = sum(f["parts"][0][0][1] for f in frames) / len(frames)
    longest = max(parts[0]["size"])
    facts["root height"] = round(height, 3)
    facts["root longest side"] = round(longest, 3)
    return ("upright (2f)" if height > longest else "counterbalanced (2e)"), facts


for path in sys.argv[1:]:
    record = json.load(open(path))
    name, facts = family(record)
    shown = ", ".join(f"{k} {v}" for k, v in facts.items())
    print(f"{path}: {name}; fitness {record['fitness']:.4f}; {shown}")
