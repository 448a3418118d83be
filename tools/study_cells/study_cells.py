#!/usr/bin/env python3
"""An experiment's paired comparison pooled over cells of scenes, with the figures a pre-registered
rule needs (docs/results/point-map-regime.md, "The study").

  tools/study_cells/study_cells.py OUT_DIR/results.json --cell NAME=REGEX [--cell ...]
                                   [--subject ua_mpc] [--baseline constant_3.6] [--ate unaligned|aligned]

A cell is the scenes whose name matches REGEX (e.g. --cell 'Mid-360, point map=_pm_mid360$'). Per
cell, over the pairs (same scene and seed, both runs finished with an ATE): losses of track of each
controller, the summed ATE ratio (subject / baseline), the median paired ATE ratio with its
distribution-free 95 % interval (order statistics of the paired log ratios, from the binomial
distribution), the exact two-sided Wilcoxon signed-rank p of the log ratios, the median paired CMPLT
ratio, and the baseline's median ATE. The ATE is the unaligned one (our studies') or, with --ate
aligned, the one after a rigid alignment over the whole path (the paper's Table I, as its reference's
plot_ate.py computes it). Prints a Markdown table. Exit codes: 0 printed, 2 bad input.
"""
import argparse
import itertools
import json
import math
import re
import statistics
import sys


def median_interval(values, level=0.95):
    """The order statistics (x_(k), x_(n+1-k)) that cover the median with at least `level`."""
    xs, n = sorted(values), len(values)
    best = None
    for k in range(1, n // 2 + 1):
        # P(x_(k) <= median <= x_(n+1-k)) = 1 - 2 P(B <= k - 1), B ~ Binomial(n, 1/2)
        tail = sum(math.comb(n, i) for i in range(k)) / 2 ** n
        if 1 - 2 * tail >= level:
            best = (xs[k - 1], xs[n - k])
    return best


def wilcoxon_p(values):
    """Exact two-sided p of the signed-rank test (zeros dropped; ties share their mean rank)."""
    d = [v for v in values if v != 0.0]
    n = len(d)
    if n == 0:
        return 1.0
    order = sorted(range(n), key=lambda i: abs(d[i]))
    ranks = [0.0] * n
    i = 0
    while i < n:
        j = i
        while j + 1 < n and abs(d[order[j + 1]]) == abs(d[order[i]]):
            j += 1
        for k in range(i, j + 1):
            ranks[order[k]] = (i + j) / 2 + 1
        i = j + 1
    observed = sum(r for r, v in zip(ranks, d) if v > 0)
    total = sum(ranks)
    extreme = min(observed, total - observed)
    count = 0
    for signs in itertools.product((0, 1), repeat=n):
        w = sum(r for r, s in zip(ranks, signs) if s)
        if min(w, total - w) <= extreme + 1e-9:
            count += 1
    return count / 2 ** n


ATE_KEYS = {"unaligned": "ate_m", "aligned": "ate_aligned_m"}


def cell_figures(runs, pattern, subject, baseline, ate_key="ate_m"):
    by_key = {}
    for r in runs:
        if re.search(pattern, r["scene"]):
            by_key[(r["scene"], r["seed"], r["controller"])] = r
    keys = sorted({(s, seed) for (s, seed, _) in by_key})
    lost = {subject: 0, baseline: 0}
    lost_at = {subject: [], baseline: []}
    finished = {subject: 0, baseline: 0}
    pairs = []
    for scene, seed in keys:
        a, b = by_key.get((scene, seed, subject)), by_key.get((scene, seed, baseline))
        for name, run in ((subject, a), (baseline, b)):
            if run and run.get(ate_key) is not None:
                finished[name] += 1
                if run.get("lost_track_at_s") is not None:
                    lost[name] += 1
                    lost_at[name].append(run["lost_track_at_s"])
        if a and b and a.get(ate_key) and b.get(ate_key):
            pairs.append((a, b))
    if not pairs:
        return None
    logs = [math.log(a[ate_key] / b[ate_key]) for a, b in pairs]
    low, high = median_interval(logs) or (float("nan"), float("nan"))
    cmplt = [a["cmplt"] / b["cmplt"] for a, b in pairs if a.get("cmplt") and b.get("cmplt")]
    return {
        "pairs": len(pairs),
        "lost": lost,
        "median_lost_at": {k: statistics.median(v) if v else None for k, v in lost_at.items()},
        "finished": finished,
        "sum_ratio": sum(a[ate_key] for a, _ in pairs) / sum(b[ate_key] for _, b in pairs),
        "median_ratio": math.exp(statistics.median(logs)),
        "interval": (math.exp(low), math.exp(high)),
        "p": wilcoxon_p(logs),
        "cmplt_ratio": statistics.median(cmplt) if cmplt else float("nan"),
        "baseline_median_ate": statistics.median(b[ate_key] for _, b in pairs),
    }


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("results")
    parser.add_argument("--cell", action="append", required=True, metavar="NAME=REGEX")
    parser.add_argument("--subject", default="ua_mpc")
    parser.add_argument("--baseline", default="constant_3.6")
    parser.add_argument("--ate", choices=sorted(ATE_KEYS), default="unaligned")
    args = parser.parse_args(argv[1:])
    try:
        runs = json.load(open(args.results))["runs"]
    except (OSError, ValueError, KeyError) as e:
        print(f"study_cells: {args.results}: {e}", file=sys.stderr)
        return 2
    s, b = args.subject, args.baseline
    print(f"| cell | pairs | {s} lost (median s) | {b} lost (median s) | ATE ratio, sums | ATE ratio, median of pairs [95 % interval] "
          f"| Wilcoxon p | CMPLT ratio, median | {b} median ATE m |")
    print("|---|---|---|---|---|---|---|---|---|")
    for cell in args.cell:
        name, _, pattern = cell.partition("=")
        f = cell_figures(runs, pattern, s, b, ATE_KEYS[args.ate])
        if f is None:
            print(f"| {name} | 0 | | | | | | | |")
            continue
        def lost(c):
            at = f["median_lost_at"][c]
            return f"{f['lost'][c]} of {f['finished'][c]}" + ("" if at is None else f" ({at:.0f})")
        print(f"| {name} | {f['pairs']} | {lost(s)} | {lost(b)} "
              f"| {f['sum_ratio']:.2f} | {f['median_ratio']:.2f} [{f['interval'][0]:.2f}, {f['interval'][1]:.2f}] "
              f"| {f['p']:.3g} | {f['cmplt_ratio']:.3f} | {f['baseline_median_ate']:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
