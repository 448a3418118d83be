#!/usr/bin/env python3
"""matrix_table.py LABEL=FILE [LABEL=FILE ...]

Turns the outputs of world_matrix.sh (one file per set of LO flags) into the Markdown table of
docs/results/lo-degenerate-geometry.md ("A registration budget"): one row per run, one column per
file, each cell "RMS / worst position (m)" or "lost at T s", then a row of the LO's mean time per
frame and, against the first column, how many runs each column lost (a run that failed counts as
lost) and in how many of the runs both held its worst position was worse or better by more than 5 %.
"""
import re
import sys

SUMMARY = re.compile(
    r"worst position (?P<worst>[\d.]+) m.*lost at (?P<lost>\S+),.*RMS position (?P<rms>[\d.]+) m, LO (?P<ms>[\d.]+) ms")


def read_column(path):
    """{run name: (cell text, worst position or None when lost, ms per frame)}, in file order."""
    column = {}
    with open(path, encoding="utf-8") as lines:
        for number, line in enumerate(lines, 1):
            if not line.strip():
                continue
            name = line.split()[0]
            match = SUMMARY.search(line)
            if not match:
                column[name] = ("failed", None, None)
                print(f"matrix_table: {path}:{number}: no lo_replay summary for {name}", file=sys.stderr)
                continue
            ms = float(match["ms"])
            if match["lost"] != "never":
                column[name] = (f"lost at {float(match['lost']):.1f} s", None, ms)
            else:
                column[name] = (f"{float(match['rms']):.3f} / {float(match['worst']):.2f}", float(match["worst"]), ms)
    return column


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) >= 2 else 2
    labels, columns = [], []
    for argument in argv[1:]:
        label, separator, path = argument.partition("=")
        if not separator:
            print(f"matrix_table: '{argument}' is not LABEL=FILE", file=sys.stderr)
            return 2
        labels.append(label)
        try:
            columns.append(read_column(path))
        except OSError as error:
            print(f"matrix_table: {path}: {error.strerror}", file=sys.stderr)
            return 1
    runs = list(columns[0])
    for column in columns[1:]:
        runs += [name for name in column if name not in runs]
    print("| run | " + " | ".join(labels) + " |")
    print("|---|" + "---|" * len(labels))
    for name in runs:
        print(f"| {name} | " + " | ".join(column.get(name, ("-",))[0] for column in columns) + " |")
    means = []
    for column in columns:
        times = [cell[2] for cell in column.values() if cell[2] is not None]
        means.append(f"{sum(times) / len(times):.1f}" if times else "-")
    print("| LO ms per frame, mean of runs | " + " | ".join(means) + " |")
    base = columns[0]
    summary = []
    for column in columns:
        lost = sum(1 for cell in column.values() if cell[1] is None)
        worse = better = 0
        for name, cell in column.items():
            if name in base and cell[1] is not None and base[name][1] is not None:
                worse += cell[1] > 1.05 * base[name][1]
                better += cell[1] < base[name][1] / 1.05
        summary.append(f"{lost} lost; worst position worse in {worse}, better in {better}")
    print("| against the first column | " + " | ".join(summary) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
