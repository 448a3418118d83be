#!/usr/bin/env python3
"""Whether a lockstep run's outputs begin with those of the same scene run for a shorter time
(docs/results/soak.md): for each time series of the shorter run, its rows must be the first rows of
the longer run's, byte for byte (timings.csv: its first three columns, the rest are measured
times; ate.csv: its first two, the aligned error depends on the whole run's alignment; the last row of a file may differ where the shorter run was cut mid-way).

    tools/soak/prefix_check.py LONG_RUN_DIR SHORT_RUN_DIR
"""
import pathlib
import sys

SERIES = ["motor.csv", "uncertainty.csv", "timings.csv", "estimate.tum", "ground_truth.tum", "ate.csv",
          "cmplt_windows.csv", "cmplt_ground_truth_windows.csv"]


def rows(path, name):
    lines = path.read_text().splitlines()
    if name == "timings.csv":
        lines = [",".join(line.split(",")[:3]) for line in lines]
    if name == "ate.csv":  # the aligned error depends on the whole run's alignment
        lines = [",".join(line.split(",")[:2]) for line in lines]
    return lines


def main():
    long_dir, short_dir = map(pathlib.Path, sys.argv[1:3])
    ok = True
    for name in SERIES:
        if not (short_dir / name).exists():
            continue
        short, long_ = rows(short_dir / name, name), rows(long_dir / name, name)
        # The shorter run's last window or row may be cut where it stopped: compare all but it.
        compared = short[:-1]
        same = long_[:len(compared)] == compared
        first_diff = next((i for i, (a, b) in enumerate(zip(compared, long_)) if a != b), None)
        print(f"{name}: {len(compared)} of {len(short)} rows compared, "
              + ("the same" if same else f"first difference at row {first_diff}"))
        ok = ok and same
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
