"""How linear (Couette) or parabolic (Poiseuille) a channel's velocity profile is, and how uniform
its density and temperature: the numbers behind paper 002's Figures 5 and 6.

Reads the points file `dpd reproduce 002-figure-N --out DIR` writes (`DIR/<id>.points.json`:
per run the slab rows of `[profile]`, position along the wall normal, density, mean velocity,
temperature with each sample's slab velocity subtracted) and, for each run, fits a polynomial
of degree 1 or 2 by least squares to the x-velocity of the slabs between the walls, and prints
the fit, its residuals, the fitted velocity at the walls (the parabola's vertex, for degree 2),
and density and temperature in the bulk (slabs more than one unit from a wall) and at the walls.

    python scripts/papers/profile_fit.py DIR/002-figure-5.points.json --degree 1
    python scripts/papers/profile_fit.py DIR/002-figure-6.points.json --degree 2

Needs numpy (`pip install numpy` into any virtual environment).
"""

import argparse
import json

import numpy as np


def slabs(point, lower, upper):
    """The filled slabs strictly between the walls: positions, densities, x-velocities,
    temperatures."""
    rows = [r for r in point["profile"] if r["count"] and lower < r["position"] < upper]
    return (
        np.array([r["position"] for r in rows]),
        np.array([r["density"] for r in rows]),
        np.array([r["velocity"][0] for r in rows]),
        np.array([r["temperature"] for r in rows]),
    )


def spread(label, values):
    return f"{label} {values.mean():.4f} (min {values.min():.4f}, max {values.max():.4f})"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("points", help="a points file of `dpd reproduce` with [profile] rows")
    parser.add_argument("--degree", type=int, choices=(1, 2), required=True,
                        help="1: Couette (a line), 2: Poiseuille (a parabola)")
    args = parser.parse_args()

    data = json.load(open(args.points))
    walls = data["scene"]["walls"]
    lower, upper = walls["lower"], walls["upper"]
    for point in data["points"]:
        print(f"{point['scheme']} dt = {point['dt']} seed {point['seed']}: "
              f"{'stable' if point['stable'] else 'blew up'}, {point['samples']} samples")
        if not point["stable"]:
            continue
        z, density, u, temperature = slabs(point, lower, upper)
        coefficients = np.polyfit(z, u, args.degree)
        residual = u - np.polyval(coefficients, z)
        print(f"  fit (highest power first) {np.array2string(coefficients, precision=5)}, "
              f"residual rms {residual.std():.4f}, largest {np.abs(residual).max():.4f}, "
              f"velocity {u.min():.3f} to {u.max():.3f} in {len(z)} slabs")
        at_walls = np.polyval(coefficients, [lower, upper])
        print(f"  fitted velocity at the walls z = {lower}, {upper}: "
              f"{at_walls[0]:.3f}, {at_walls[1]:.3f}")
        if args.degree == 2:
            vertex = -coefficients[1] / (2 * coefficients[0])
            print(f"  vertex at z = {vertex:.3f}, velocity {np.polyval(coefficients, vertex):.3f}")
        bulk = (z > lower + 1) & (z < upper - 1)
        print(f"  bulk ({bulk.sum()} slabs): {spread('density', density[bulk])}, "
              f"{spread('temperature', temperature[bulk])}")
        print(f"  wall slabs: density {np.array2string(density[~bulk], precision=4)}, "
              f"temperature {np.array2string(temperature[~bulk], precision=4)}")


if __name__ == "__main__":
    main()
