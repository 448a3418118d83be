#!/usr/bin/env python3
"""How much a run's motor command moves: the chatter of a controller, from its run directories.

  tools/command_activity/command_activity.py [--step 0.1] [--max-speed 7.2] [--after 5] RUN_DIR ...

For each run directory (its motor.csv: time, theta, omega, command, one row per 5 ms), sampled at
the control step: the mean |change| of the command per step (rad/s), the changes per second larger
than a quarter of the speed range, the share of time at the speed bounds (within 0.05 rad/s of 0 or
of --max-speed), and the mean command. --after skips the first seconds (a held start). Prints one
Markdown row per run, then the medians. Exit codes: 0 printed, 2 bad arguments or a run without
a readable motor.csv.
"""
import argparse
import csv
import os
import statistics
import sys


def command_samples(path, step, after):
    """The command at every `step` s from `after` on, as motor.csv holds it (the last row at or before)."""
    samples, next_time = [], after
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            t = float(row["time"])
            while t >= next_time - 1e-9:
                samples.append(float(row["command"]))
                next_time += step
    return samples


def activity(samples, step, max_speed):
    changes = [abs(b - a) for a, b in zip(samples, samples[1:])]
    duration = step * max(1, len(samples) - 1)
    big = sum(1 for c in changes if c > 0.25 * max_speed)
    at_bounds = sum(1 for s in samples if s <= 0.05 or s >= max_speed - 0.05)
    return {
        "mean_change": statistics.fmean(changes) if changes else 0.0,
        "big_changes_per_s": big / duration,
        "share_at_bounds": at_bounds / len(samples) if samples else 0.0,
        "mean_command": statistics.fmean(samples) if samples else 0.0,
    }


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("runs", nargs="+", metavar="RUN_DIR")
    parser.add_argument("--step", type=float, default=0.1, help="control step, s (default 0.1)")
    parser.add_argument("--max-speed", type=float, default=7.2, help="the motor's speed bound, rad/s (default 7.2)")
    parser.add_argument("--after", type=float, default=0.0, help="seconds skipped at the start (default 0)")
    args = parser.parse_args(argv[1:])
    for name, value in (("--step", args.step), ("--max-speed", args.max_speed)):
        if not (value > 0 and value < float("inf")):
            parser.error(f"{name} must be a positive finite number")
    rows = []
    print("| run | mean change per step, rad/s | changes > 1/4 of the range per s | share at the bounds | mean command, rad/s |")
    print("|---|---|---|---|---|")
    for run in args.runs:
        path = os.path.join(run, "motor.csv")
        try:
            a = activity(command_samples(path, args.step, args.after), args.step, args.max_speed)
        except (OSError, KeyError, ValueError) as e:
            print(f"command_activity: {path}: {e}", file=sys.stderr)
            return 2
        rows.append(a)
        print(f"| {run} | {a['mean_change']:.2f} | {a['big_changes_per_s']:.2f} | {a['share_at_bounds']:.2f} | "
              f"{a['mean_command']:.2f} |")
    med = {k: statistics.median(r[k] for r in rows) for k in rows[0]}
    print(f"| median of {len(rows)} | {med['mean_change']:.2f} | {med['big_changes_per_s']:.2f} | "
          f"{med['share_at_bounds']:.2f} | {med['mean_command']:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
