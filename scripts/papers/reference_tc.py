"""ABOBA, DPD-S1 and M-Shardlow-2 written again from the papers' equations, to check the engine.

A second implementation, sharing no code with dpd-core: O(N^2) pair search, pairs swept in
index order (i < j, both ascending, as a serial pair-list code visits them) or with `--order
random` in a new random order each step, NumPy's normal generator. Each step of

- `aboba`: A(h/2), conservative forces, B(h/2), the exact pair OU update of eqs. 2.15-2.17 for
  each pair in turn (e, w at the half-step positions), B(h/2), A(h/2);
- `dpd-s1`: Shardlow's pair update for each pair in turn (explicit half, then implicit half,
  one normal), then velocity Verlet;
- `m-shardlow-2` (paper 000, section 2.3, steps 1-4): velocity Verlet over x1 h, x0 h, x1 h
  (x1 = 1 / (2 - 2^(1/3)), x0 = 1 - 2 x1), then Shardlow's pair update for each pair within
  r_c at the new positions.

The standard box of papers 000 and 003 (N = 500, density 3 or `--density`, a = 25,
k_BT = m = r_c = 1, w_D = w_R^2 = (1 - r)^2, uniform random start, Gaussian momenta);
T_C = <sum |grad U|^2> / <sum lap U> at the end of every step of the last `--average`
fraction; T_C - 1 per run and the mean with its standard error over the runs.

    python scripts/papers/reference_tc.py --scheme aboba --gamma 450 --dt 0.116 --runs 10

Needs numpy and numba (`pip install numpy numba` into any virtual environment); 10 runs of
1000 time units take 2 to 4 minutes per point on one core (ABOBA, DPD-S1; M-Shardlow-2, three
force evaluations per step, about three times that).
"""

import argparse
import math
import sys

import numba
import numpy as np

import protocol
from protocol import A, N

# The schemes by name; `run` takes the index into SCHEMES (numba compiles integers), the
# last one, M-Shardlow-2, being its final branch.
SCHEMES = ("aboba", "dpd-s1", "m-shardlow-2")
ABOBA, DPD_S1 = SCHEMES.index("aboba"), SCHEMES.index("dpd-s1")
# Yoshida's triple jump, the sign of x0 that 000 shows to be right.
X1 = 1.0 / (2.0 - 2.0 ** (1.0 / 3.0))
X0 = 1.0 - 2.0 * X1


@numba.njit(cache=True)
def add_pair(a, i, j, c, x, y, z):
    """a_i += c (x, y, z), a_j -= c (x, y, z): a pair's equal and opposite share."""
    a[i, 0] += c * x
    a[i, 1] += c * y
    a[i, 2] += c * z
    a[j, 0] -= c * x
    a[j, 1] -= c * y
    a[j, 2] -= c * z


@numba.njit(cache=True)
def pairs_and_forces(q, side):
    """Pairs i < j with r < 1 (index order), their unit vectors e_ij = (q_i - q_j)/r and r, the
    conservative forces, and sum |F_i|^2 and sum lap_i U of U = sum (a/2)(1 - r)^2."""
    n = q.shape[0]
    ii = np.empty(n * 40, np.int64)
    jj = np.empty(n * 40, np.int64)
    ee = np.empty((n * 40, 3))
    rr = np.empty(n * 40)
    f = np.zeros((n, 3))
    lap = 0.0
    k = 0
    for i in range(n):
        for j in range(i + 1, n):
            dx = q[i, 0] - q[j, 0]
            dy = q[i, 1] - q[j, 1]
            dz = q[i, 2] - q[j, 2]
            dx -= side * np.round(dx / side)
            dy -= side * np.round(dy / side)
            dz -= side * np.round(dz / side)
            r2 = dx * dx + dy * dy + dz * dz
            if r2 < 1.0 and r2 > 0.0:
                if k == ii.shape[0]:
                    raise ValueError("more pairs than the pair buffer holds")
                r = math.sqrt(r2)
                add_pair(f, i, j, A * (1.0 - r) / r, dx, dy, dz)
                lap += 2.0 * A * (3.0 * r - 2.0) / r
                ii[k], jj[k], rr[k] = i, j, r
                ee[k, 0], ee[k, 1], ee[k, 2] = dx / r, dy / r, dz / r
                k += 1
    return ii[:k], jj[:k], ee[:k], rr[:k], f, (f * f).sum(), lap


@numba.njit(cache=True)
def pair_sweep(p, ii, jj, ee, rr, gamma, h, exact, shuffle):
    """One sweep of the pair updates in list order, or with `shuffle` in a new random order
    (unit masses, k_BT = 1, sigma^2 = 2 gamma)."""
    sigma = math.sqrt(2.0 * gamma)
    mu = 0.5  # reduced mass m_i m_j / (m_i + m_j)
    order = np.random.permutation(ii.shape[0]) if shuffle else np.arange(ii.shape[0])
    for k in order:
        i, j = ii[k], jj[k]
        ex, ey, ez = ee[k, 0], ee[k, 1], ee[k, 2]
        wr = 1.0 - rr[k]
        wd = wr * wr
        vn = (p[i, 0] - p[j, 0]) * ex + (p[i, 1] - p[j, 1]) * ey + (p[i, 2] - p[j, 2]) * ez
        if exact:  # eqs. 2.15-2.17: exact OU of the relative normal velocity
            tau = gamma * wd / mu
            dv = vn * (math.exp(-tau * h) - 1.0) + sigma * wr / mu * math.sqrt(
                (1.0 - math.exp(-2.0 * tau * h)) / (2.0 * tau)) * np.random.normal()
            dp = mu * dv
        else:  # Shardlow: explicit half step, implicit half step, the same normal
            g = 0.5 * gamma * wd * h
            noise = 0.5 * sigma * wr * math.sqrt(h) * np.random.normal()
            dp = noise - g * vn
            vn += 2.0 * dp
            dp += (noise - g * vn) / (1.0 + 2.0 * g)
        add_pair(p, i, j, dp, ex, ey, ez)


@numba.njit(cache=True)
def run(scheme, gamma, h, steps, first_sample, seed, shuffle, side):
    """T_C - 1 over the steps from `first_sample` on of one run of SCHEMES[scheme] from a uniform
    random start in the cube of edge `side`, or NaN if the forces became non-finite (a blow-up)."""
    np.random.seed(seed)
    q = np.random.random((N, 3)) * side
    p = np.random.normal(0.0, 1.0, (N, 3))
    num = 0.0
    den = 0.0
    ii, jj, ee, rr, f, _, _ = pairs_and_forces(q, side)
    for step in range(steps):
        if scheme == ABOBA:
            q += 0.5 * h * p
            ii, jj, ee, rr, f, _, _ = pairs_and_forces(q, side)
            p += 0.5 * h * f
            pair_sweep(p, ii, jj, ee, rr, gamma, h, True, shuffle)
            p += 0.5 * h * f
            q += 0.5 * h * p
            q %= side
            _, _, _, _, _, fsq, lap = pairs_and_forces(q, side)
        elif scheme == DPD_S1:
            pair_sweep(p, ii, jj, ee, rr, gamma, h, False, shuffle)
            p += 0.5 * h * f
            q += h * p
            q %= side
            ii, jj, ee, rr, f, fsq, lap = pairs_and_forces(q, side)
            p += 0.5 * h * f
        else:  # m-shardlow-2
            for x in (X1, X0, X1):
                p += 0.5 * x * h * f
                q += x * h * p
                q %= side
                ii, jj, ee, rr, f, fsq, lap = pairs_and_forces(q, side)
                p += 0.5 * x * h * f
            pair_sweep(p, ii, jj, ee, rr, gamma, h, False, shuffle)
        if not math.isfinite(fsq):
            return math.nan
        if step >= first_sample:
            num += fsq
            den += lap
    return num / den - 1.0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scheme", choices=SCHEMES, required=True)
    protocol.add_arguments(ap)
    ap.add_argument("--order", choices=["index", "random"], default="index",
                    help="pair order of the sweeps: i < j ascending, or a new permutation per step")
    args = ap.parse_args()
    protocol.check(args)
    steps = int(round(args.time / args.dt))
    first = int(round((1.0 - args.average) * steps))
    errors = []
    for seed in range(1, args.runs + 1):
        err = run(SCHEMES.index(args.scheme), args.gamma, args.dt, steps, first, seed,
                  args.order == "random", protocol.side(args))
        print(f"seed {seed}: T_C - 1 = {100 * err:+.3f} %" if math.isfinite(err)
              else f"seed {seed}: blew up", flush=True)
        if math.isfinite(err):
            errors.append(err)
    if len(errors) >= 2:
        print(protocol.summary(f"{args.scheme} ({args.order} order)", args, errors))
    if len(errors) < args.runs:
        sys.exit(1)


if __name__ == "__main__":
    main()
