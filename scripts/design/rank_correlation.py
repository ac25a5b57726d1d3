#!/usr/bin/env python3
"""Does the error norm of `dpd check` predict accuracy? (issue 23; docs/design.md, a measurement,
not a test.) For order-2 splittings of A, B and O with one force evaluation per step, it
compares the predicted `invariant_measure_error_norm` and `deterministic_error_norm` with the
measured relative error of the configurational temperature, (T_C - k_B T) / k_B T, at one
fixed dt on the standard box (N = 500, density 3, a = 25, k_B T = 1), at each gamma, and
prints Spearman's rank correlation between the norm and |error|. Standard library only.

    python3 scripts/design/rank_correlation.py --dpd target/release/dpd [--dt 0.08]
        [--gamma 4.5 --gamma 200] [--time 200] [--runs 4]
"""

import argparse
import json
import math
import subprocess

# Order-2 (deterministic and invariant-measure) one-force splittings from `dpd orderings
# --max-len 6 --rank error`, chosen to span its invariant-measure norms (0.156 to 0.524).
SCHEMES = ["OBAB", "OBABO", "OABA", "OABAO", "ABOBAO", "OBAOAB", "ABOBA", "BAOAB", "BAOOAB",
           "BOAOBO", "AOBOA", "BOAOB"]


def dpd_json(dpd, *args):
    out = subprocess.run([dpd, *args, "--json"], capture_output=True, text=True, timeout=3600)
    if out.returncode != 0:
        raise SystemExit(f"dpd {' '.join(args)} failed: {out.stderr}")
    return json.loads(out.stdout)


def ranks(values):
    """Ranks 1..n, ties given their mean rank."""
    order = sorted(range(len(values)), key=lambda k: values[k])
    r = [0.0] * len(values)
    k = 0
    while k < len(order):
        j = k
        while j + 1 < len(order) and values[order[j + 1]] == values[order[k]]:
            j += 1
        for m in range(k, j + 1):
            r[order[m]] = (k + j) / 2 + 1
        k = j + 1
    return r


def spearman(x, y):
    """Spearman's rho, Pearson's correlation of the ranks (ties averaged), as text; "n/a" when
    one side has a single value (every scheme the same norm)."""
    rx, ry = ranks(x), ranks(y)
    mx, my = sum(rx) / len(rx), sum(ry) / len(ry)
    sxy = sum((a - mx) * (b - my) for a, b in zip(rx, ry))
    sxx = sum((a - mx) ** 2 for a in rx)
    syy = sum((b - my) ** 2 for b in ry)
    return "n/a" if sxx == 0 or syy == 0 else f"{sxy / math.sqrt(sxx * syy):+.2f}"


def arguments(description):
    """The command line of this script and of predict_correlation.py: --dpd, --dt, --gamma
    (repeatable), --time and --runs."""
    p = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--dpd", required=True)
    p.add_argument("--dt", type=float, default=0.08)
    p.add_argument("--gamma", type=float, action="append")
    p.add_argument("--time", type=float, default=200.0)
    p.add_argument("--runs", type=int, default=4)
    return p.parse_args()


def main():
    args = arguments(__doc__)
    norms = {s: dpd_json(args.dpd, "check", s) for s in SCHEMES}
    for gamma in args.gamma or [4.5, 200.0]:
        rows = []
        for s in SCHEMES:
            run = dpd_json(args.dpd, "run", "--scheme", s, "--gamma", str(gamma), "--dt", str(args.dt),
                           "--time", str(args.time), "--runs", str(args.runs))
            tc = [r["configurational_temperature"] for r in run["results"]]
            m = sum(tc) / len(tc)
            se = math.sqrt(sum((x - m) ** 2 for x in tc) / (len(tc) - 1) / len(tc))
            rows.append((s, norms[s]["invariant_measure_error_norm"], norms[s]["deterministic_error_norm"],
                         m - 1.0, se))
        print(f"\ngamma = {gamma}, dt = {args.dt}, {args.runs} runs of {args.time:g} time units (N = 500)\n")
        print("| scheme | invariant-measure norm | deterministic norm | T_C error % | +- % |")
        print("|---|---|---|---|---|")
        for s, inv, det, err, se in sorted(rows, key=lambda r: abs(r[3])):
            print(f"| {s} | {inv:.4f} | {det:.4f} | {100 * err:+.2f} | {100 * se:.2f} |")
        errors = [abs(r[3]) for r in rows]
        print(f"\nSpearman rho(invariant-measure norm, |T_C error|) = {spearman([r[1] for r in rows], errors)}; "
              f"rho(deterministic norm, |T_C error|) = {spearman([r[2] for r in rows], errors)} "
              f"({len(rows)} schemes)", flush=True)


if __name__ == "__main__":
    main()
