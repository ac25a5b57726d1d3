"""The papers' standard box and run protocol as command-line options, and the summary line
both scripts print."""

import math
import sys

# The standard box of papers 000 and 003: N particles, repulsion A (k_BT = m = r_c = 1), at the
# density of `--density`: 3 in 003, 4 in 000's tables (L = 5; docs/papers.md).
N = 500
A = 25.0


def side(args):
    """Edge of the cubic box holding N particles at `--density`."""
    return (N / args.density) ** (1.0 / 3.0)


def add_arguments(parser):
    """--gamma, --dt, --time, --runs, --average (the averaged fraction of each run) and
    --density."""
    parser.add_argument("--density", type=float, default=3.0,
                        help="particles per unit volume: 3 (003), 4 (000's tables, L = 5)")
    parser.add_argument("--gamma", type=float, required=True)
    parser.add_argument("--dt", type=float, required=True)
    parser.add_argument("--time", type=float, default=1000.0)
    parser.add_argument("--runs", type=int, default=10)
    parser.add_argument("--average", type=float, default=0.8, help="averaged fraction of each run")


def check(args, extra=()):
    """Exit naming the option, its value and the valid range of the first one out of range;
    `extra` adds (option, ok, valid range) triples."""
    limits = (("--density", args.density > 0, "> 0"), ("--gamma", args.gamma > 0, "> 0"),
              ("--dt", args.dt > 0, "> 0"), ("--time", args.time >= args.dt, ">= dt"),
              ("--runs", args.runs >= 2, ">= 2"), ("--average", 0 < args.average <= 1, "in (0, 1]"))
    limits += tuple(extra)
    for name, ok, valid in limits:
        if not ok:
            sys.exit(f"{name} = {getattr(args, name[2:])} is out of range: it must be {valid}")


def summary(label, args, errors, quantity="T_C"):
    """`label: T_C - 1 = mean +- standard error % over n runs ...` of the runs' relative errors
    of `quantity` (at least two: a standard error needs them)."""
    n = len(errors)
    mean = sum(errors) / n
    se = math.sqrt(sum((e - mean) ** 2 for e in errors) / (n - 1) / n)
    return (f"{label} density {args.density:g} gamma {args.gamma:g} dt {args.dt:g}: "
            f"{quantity} - 1 = {100 * mean:+.3f} +- {100 * se:.3f} % over {n} runs of {args.time:g} "
            f"time units (last {100 * args.average:g} %)")
