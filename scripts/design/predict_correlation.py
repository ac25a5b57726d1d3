#!/usr/bin/env python3
"""How well does `dpd predict` rank schemes? (issue 49; docs/design.md, a measurement, not a
test.) For each scheme and gamma it takes the predicted relative T_C error at one dt from
`dpd predict --json` (the exact stationary statistics of the scheme's linear step on the
harmonic modes of the fluid's pair network, plus the leading anharmonic correction; the
harmonic part is printed apart) and measures it with `dpd run` on the standard box
(N = 500, density 3, a = 25, k_B T = 1), then prints both and Spearman's rank correlation of
the predicted and measured |T_C error|. A run that blows up, or a prediction that is unstable,
counts as the largest error (tied); rho is also given over the schemes where both are finite.
Standard library only; Spearman's rho from rank_correlation.py.

    python3 scripts/design/predict_correlation.py --dpd target/release/dpd [--dt 0.08]
        [--gamma 4.5 --gamma 200] [--time 200] [--runs 4]
"""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rank_correlation import arguments, dpd_json, spearman  # noqa: E402

# The twelve splittings of rank_correlation.py, the named schemes of the registry that have a
# program of letters (F, T and Ob included), McLachlan's BAB with an O step and two first-order
# orderings.
SCHEMES = ["OBAB", "OBABO", "OABA", "OABAO", "ABOBAO", "OBAOAB", "ABOBA", "BAOAB", "BAOOAB",
           "BOAOBO", "AOBOA", "BOAOB", "vv", "dpd-s1", "dpd-s2", "sas", "asa", "m-shardlow-2",
           "prk3-ruth", "prk3-ruth-o", "obabo-y4", "aboba-y4",
           "B(0.1932) A(1/2) B(0.6136) A(1/2) B(0.1932) O", "BAO", "ABO"]


def measured(dpd, scheme, gamma, dt, time, runs):
    """(mean T_C - 1, its standard error) over the stable runs, or None when a run blew up."""
    run = dpd_json(dpd, "run", "--scheme", scheme, "--gamma", str(gamma), "--dt", str(dt),
                   "--time", str(time), "--runs", str(runs))
    if not run["stable"]:
        return None
    tc = [r["configurational_temperature"] for r in run["results"]]
    m = sum(tc) / len(tc)
    se = math.sqrt(sum((x - m) ** 2 for x in tc) / (len(tc) - 1) / len(tc)) if len(tc) > 1 else 0.0
    return m - 1.0, se


def main():
    args = arguments(__doc__)
    for gamma in args.gamma or [4.5, 200.0]:
        pred = dpd_json(args.dpd, "predict", *SCHEMES, "--gamma", str(gamma), "--dt", str(args.dt))
        rows = []
        for s, ps in zip(SCHEMES, pred["schemes"]):
            row = ps["rows"][0]
            predicted = row["configurational_temperature"] if row["stable"] else None
            harmonic = predicted - row["anharmonic_correction"] if row["stable"] else None
            rows.append((s, predicted, measured(args.dpd, s, gamma, args.dt, args.time, args.runs),
                         ps["critical_dt_10"], ps["stability_limit"], harmonic))
        r = pred["response"]
        print(f"\ngamma = {gamma}, dt = {args.dt}, {args.runs} runs of {args.time:g} time units (N = 500); "
              f"spectrum of {pred['modes']} modes and response R = {r['r']:.1f} +- {r['std_error']:.1f} "
              f"in {pred['spectrum_seconds']:.1f} s\n")
        print("| scheme | predicted T_C error | harmonic part | measured T_C error | predicted dt_c 10 % | predicted stability limit |")
        print("|---|---|---|---|---|---|")
        pct = lambda x: "unstable" if x is None else f"{100 * x:+.1f} %"
        for s, pr, me, crit, lim, harm in rows:
            ms = "blows up" if me is None else f"{100 * me[0]:+.1f} +- {100 * me[1]:.1f} %"
            c = "-" if crit.get("dt") is None else f"{crit['dt']:.4f}" + (" (limit)" if crit["status"] == "stability_limit" else "")
            print(f"| {s} | {pct(pr)} | {pct(harm)} | {ms} | {c} | {'-' if lim is None else f'{lim:.4f}'} |")
        big = float("inf")
        b = [big if me is None else abs(me[0]) for _, _, me, _, _, _ in rows]
        for name, k in [("predicted", 1), ("harmonic part", 5)]:
            a = [big if row[k] is None else abs(row[k]) for row in rows]
            finite = [(x, y) for x, y in zip(a, b) if x != big and y != big]
            print(f"\nSpearman rho({name}, measured |T_C error|) = {spearman(a, b)} over {len(rows)} schemes "
                  f"(blow-ups and unstable predictions as the largest); "
                  f"{spearman([x for x, _ in finite], [y for _, y in finite])} over the {len(finite)} with both finite",
                  flush=True)


if __name__ == "__main__":
    main()
