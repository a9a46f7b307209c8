#!/usr/bin/env python3
"""The baseline a user would otherwise write: Shapely 2.x (GEOS) redoes threadcheck's cut.

Reads the insert placements that `threadcheck sweep --export-placements FILE` wrote (one JSON
object per line: the blank rectangle, every placed insert outline, the groove to measure and
threadcheck's own pitch diameter and time for the same work), then for each case:

  1. unions the placements with shapely.union_all and subtracts the union from the blank;
  2. measures the simple pitch diameter: the radius where the groove around z_ref is P/2 wide,
     found by bisection on horizontal clipping lines;
  3. checks that this d2 agrees with threadcheck's to 0.1 um.

It prints one line per case and a summary line with the median times and their ratio.

    pip install "shapely>=2"
    cargo run --release -- sweep --max-d 24 --infeed modified --schedule constant-area \\
        --export-placements /tmp/placements.jsonl
    python3 benches/baseline_shapely.py /tmp/placements.jsonl
"""

import json
import statistics
import sys
import time

import shapely
from shapely.geometry import LineString, Polygon


def groove_width(section, z_ref, r, z0, z1):
    """Width of the gap in the material around z_ref on the horizontal line at radius r."""
    cut = section.intersection(LineString([(z0, r), (z1, r)]))
    pieces = [] if cut.is_empty else getattr(cut, "geoms", [cut])
    left, right = z0, z1
    for g in pieces:
        xs = [c[0] for c in g.coords]
        lo, hi = min(xs), max(xs)
        if hi <= z_ref:
            left = max(left, hi)
        elif lo >= z_ref:
            right = min(right, lo)
        else:
            return 0.0  # material across z_ref: below the root
    return right - left


def pitch_diameter(section, case):
    p, z_ref = case["pitch"], case["z_ref"]
    internal = case["kind"] == "internal"
    zs = [c[0] for c in case["blank"]]
    rs = [c[1] for c in case["blank"]]
    z0, z1 = min(zs), max(zs)
    # Bracket: from the bottom of the groove to the blank surface.
    surface = min(rs) if internal else max(rs)
    far = max(rs) if internal else min(rs)
    lo, hi = far, surface  # radius where width is 0 … where it is widest
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if groove_width(section, z_ref, mid, z0, z1) < 0.5 * p:
            lo = mid
        else:
            hi = mid
    return lo + hi  # the diameter, 2 * (lo + hi) / 2


def main(path):
    rows = []
    worst = 0.0
    for line in open(path, encoding="utf-8"):
        case = json.loads(line)
        start = time.perf_counter()
        blank = Polygon(case["blank"])
        union = shapely.union_all([Polygon(r) for r in case["placements"]])
        section = blank.difference(union)
        d2 = pitch_diameter(section, case)
        seconds = time.perf_counter() - start
        dev_um = abs(d2 - case["pitch_diameter"]) * 1000.0
        worst = max(worst, dev_um)
        ok = dev_um <= 0.1
        rows.append((seconds, case["threadcheck_seconds"], case["verify_seconds"]))
        print(f"{'ok  ' if ok else 'DIFF'} {case['case']}: GEOS d2 {d2:.6f}, threadcheck {case['pitch_diameter']:.6f} "
              f"({dev_um:.4f} um), {1e3 * seconds:.3f} ms vs {1e3 * case['threadcheck_seconds']:.3f} ms")
    geos = statistics.median(r[0] for r in rows)
    ours = statistics.median(r[1] for r in rows)
    whole = statistics.median(r[2] for r in rows)
    # Per case, in one run: GEOS's union + difference + d2 against threadcheck's whole verify.
    per_case = statistics.median(r[0] / r[2] for r in rows)
    print(json.dumps({
        "cases": len(rows),
        "shapely": shapely.__version__,
        "geos": shapely.geos_version_string,
        "median_geos_ms": round(1e3 * geos, 4),
        "median_threadcheck_ms": round(1e3 * ours, 4),
        "ratio": round(geos / ours, 1),
        "median_verify_ms": round(1e3 * whole, 4),
        "ratio_whole_verify": round(geos / whole, 1),
        "median_ratio_whole_verify_per_case": round(per_case, 1),
        "worst_d2_difference_um": round(worst, 5),
    }))
    return 0 if worst <= 0.1 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "placements.jsonl"))
