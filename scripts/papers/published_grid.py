"""Are a paper's published critical steps points of one geometric grid of steps?

A paper that tests dt = s f^k and reports "the stepsize that approximately corresponds" to a
threshold prints grid points, not interpolated crossings. This reads the distinct published
values of one quantity from the items of a paper (scenes/papers/<paper>/*.toml), finds the
grid starts s in [s_min, s_min f) for which the most values lie on s f^k (within half a unit
of their last printed digit), and estimates how often that many would by chance: the same
count of values, each drawn log-uniformly over one grid step at its magnitude and printed to
the same decimals.

    python3 scripts/papers/published_grid.py [--paper 003] [--quantity critical_dt_10]
        [--factor 1.15] [--s-min 0.01] [--trials 4000]
"""

import argparse
import math
import random
import sys
import tomllib
from pathlib import Path


def published(paper_dir, quantity):
    """{printed value: [item ids]} of `quantity` in the items of `paper_dir`."""
    found = {}
    for path in sorted(Path(paper_dir).glob("*.toml")):
        if path.name == "paper.toml":
            continue
        item = tomllib.loads(path.read_text())
        for row in item.get("published", []):
            if quantity in row:
                found.setdefault(row[quantity], []).append(f"{path.stem}/{row.get('scheme')}")
    return found


def decimals(printed):
    """Digits after the decimal point of `printed`."""
    return len(printed.split(".")[1]) if "." in printed else 0


def interval(printed):
    """(low, high) of the numbers that print as `printed`."""
    half = 0.5 * 10.0 ** -decimals(printed)
    return float(printed) - half, float(printed) + half


def on_grid(lo, hi, s, f):
    """Whether some s f^k lies in [lo, hi)."""
    k = math.ceil(math.log(lo / s, f) - 1e-12)
    return s * f ** k < hi


def best_starts(intervals, f, s_min, points=1000):
    """(most values on one grid, the starts that reach it), trying `points` starts per period."""
    starts = [s_min * f ** (i / points) for i in range(points)]
    counts = [sum(on_grid(lo, hi, s, f) for lo, hi in intervals) for s in starts]
    top = max(counts)
    return top, [s for s, c in zip(starts, counts) if c == top]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--paper", default="003")
    p.add_argument("--quantity", default="critical_dt_10")
    p.add_argument("--factor", type=float, default=1.15)
    p.add_argument("--s-min", type=float, default=0.01)
    p.add_argument("--trials", type=int, default=4000)
    p.add_argument("--items", default="scenes/papers", help="directory of the papers' items")
    args = p.parse_args()
    if not (args.factor > 1 and args.s_min > 0 and args.trials >= 1):
        sys.exit("--factor must be > 1, --s-min > 0 and --trials >= 1")
    values = published(Path(args.items) / args.paper, args.quantity)
    if not values:
        sys.exit(f"no published {args.quantity} in {args.items}/{args.paper}")
    printed = sorted(values, key=float)
    intervals = [interval(v) for v in printed]
    top, starts = best_starts(intervals, args.factor, args.s_min)
    s = starts[len(starts) // 2]
    print(f"{len(printed)} distinct published {args.quantity}: {', '.join(printed)}")
    print(f"most on one grid s x {args.factor}^k: {top}, for s in "
          f"[{min(starts):.5f}, {max(starts):.5f}]")
    for v, (lo, hi) in zip(printed, intervals):
        k = round(math.log(float(v) / s, args.factor))
        mark = "on the grid" if on_grid(lo, hi, s, args.factor) else "off"
        print(f"  {v:>7} ({', '.join(values[v])}): nearest point {s * args.factor ** k:.4f}, {mark}")
    rng = random.Random(1)
    hits = 0
    for _ in range(args.trials):
        drawn = []
        for v in printed:
            x = float(v) * args.factor ** (rng.random() - 0.5)
            drawn.append(interval(f"{x:.{decimals(v)}f}"))
        hits += best_starts(drawn, args.factor, args.s_min)[0] >= top
    print(f"chance of {top} or more on one grid: {hits} of {args.trials} random draws")


if __name__ == "__main__":
    main()
