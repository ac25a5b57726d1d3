"""Print the table of docs/design.md ("The KL estimator") from the JSON files of kl.sh.

Usage: python3 scripts/design/kl_table.py [OUT_DIR]
"""
import glob
import json
import os
import sys

out = sys.argv[1] if len(sys.argv) > 1 else "results/design-kl"


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def results(prefix):
    """(file name, parsed JSON) of OUT_DIR/<prefix>-*.json, skipping unreadable files."""
    for path in sorted(glob.glob(os.path.join(out, prefix + "-*.json"))):
        d = load(path)
        if d is not None:
            yield os.path.basename(path), d


print("| file | KL | W_F, W_R (k_B T) | equilibrium U/N | Monte Carlo + protocol s |")
print("|---|---|---|---|---|")
for name, d in results("kl"):
    u = d["equilibrium_potential_energy"]
    print(
        f"| {name} | {d['kl_divergence']:.3f} +- {d['kl_error']:.3f} "
        f"| {d['forward_work']['mean']:.1f}, {d['reverse_work']['mean']:.1f} "
        f"| {u['mean']:.5f} +- {u['error']:.5f} "
        f"| {d['sampling_seconds']:.0f} + {d['protocol_seconds']:.0f} |"
    )
print()
print("| file | T_C - 1 | T_K - 1 | U/N | ms per step |")
print("|---|---|---|---|---|")
for name, d in results("tc"):
    print(
        f"| {name} | {100 * d['configurational_temperature_error']:+.2f} % "
        f"+- {100 * d['configurational_temperature_stderr']:.2f} "
        f"| {100 * d['kinetic_temperature_error']:+.2f} % | {d['potential_energy']:.4f} "
        f"| {d['ms_per_step']:.4f} |"
    )
