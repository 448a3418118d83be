#!/usr/bin/env python3
"""Where the whole loop's time goes, per simulated second (docs/dev/profiling.md).

Runs a scene twice under `perf record` (software clock sampling with DWARF call stacks: this VM has
no hardware counters), a short and a long run on one core (`taskset -c CORE`), and prints the CPU
time per simulated second of each part of the system: the difference between the two runs divided
by the difference of their simulated durations, so that start-up (loading libraries, building the
world, DDS discovery) drops out; start-up is shown on its own line.

Each sample goes to the part that owns its stack: walking from the leaf towards the root, past
frames of the C library, libm, libstdc++, the kernel, Ceres, PCL and Embree's internals (they run on
someone's behalf), the first frame in one of ours decides:
  libuampc_<component>.so          the component (its own work and the libraries it calls)
  libfastcdr, libuampc_msgs        serialisation (CDR)
  libfastrtps                      DDS (Fast DDS: its threads, queues, transports)
  libuampc_runtime, the uampc binary   runtime (lockstep steps, dispatch, logging, the launcher)
  ld-linux                         start-up (dynamic loading)
A sample with none of these is "kernel and other" when its leaf is in the kernel (mostly the
scheduler and futex waits of threads that are none of the above), and "not unwound" when its leaf is
in a library (libm, libc, ...) but perf found no caller of ours above it.

The runs are recorded with address-space randomisation off (`setarch -R`, for the profiled run only):
with it on, about one run in three lost the callers of every sample in the C and maths libraries
(sine, cosine, log, memcpy, malloc: 15 % of the loop's samples then land in "not unwound"); with
it off, 0 of 9 runs did (2026-11-28). The program itself runs as it does anywhere else. Where the
randomisation cannot be turned off (a container's seccomp profile may refuse it), it says so and
profiles with it on.

  tools/loop_profile/loop_profile.py [--scene config/scenes/default.yaml] [--short 10] [--long 40]
                                     [--core 0] [--frequency 499] [--set NAME=VALUE ...]
                                     [--functions N]

With --functions N it also prints, for each part above 5 % of the loop, its N costliest functions
(the function each sample was taken in, as `perf report` names it, inlined code counted in the
function it was inlined into), the same way per simulated second.

Needs perf (Debian: linux-perf) and a built build/bin/uampc. Prints a Markdown table.
"""
import argparse
import collections
import os
import platform
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools", "common"))
from launch_output import real_time_factor  # noqa: E402  (the launcher's last line, read once)


def part_of(dso):
    """The part a frame's shared object names, or None to look further up the stack."""
    name = os.path.basename(dso)
    m = re.match(r"libuampc_(.+)\.so", name)
    if m:
        if m.group(1) == "msgs":
            return "serialisation (CDR)"
        if m.group(1) in ("runtime", "run_files"):
            return "runtime (lockstep, dispatch, logging)"
        return "component: " + m.group(1)
    if name.startswith("libfastcdr"):
        return "serialisation (CDR)"
    if name.startswith("libfastrtps"):
        return "DDS (Fast DDS)"
    if name == "uampc":
        return "runtime (lockstep, dispatch, logging)"
    if name.startswith("ld-linux"):
        return "start-up (dynamic loading)"
    return None  # the C library, libm, Ceres, PCL, Embree, the kernel: whoever called them


def without_randomisation():
    """The command prefix that runs a program with the address-space randomisation off, so that perf
    keeps every stack (module docstring); empty, with a warning, where that is not allowed (e.g. a
    container whose seccomp profile refuses the personality call)."""
    prefix = ["setarch", platform.machine(), "-R"]
    try:
        check = subprocess.run(prefix + ["true"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    except OSError as e:
        check = subprocess.CompletedProcess(prefix, 1, stderr=str(e))
    if check.returncode == 0:
        return prefix
    print("loop_profile: cannot turn the address-space randomisation off (%s); profiling with it on: "
          "watch the 'not unwound' row" % check.stderr.strip(), file=sys.stderr)
    return []


def record(scene, duration, core, frequency, overrides, directory, prefix):
    data = os.path.join(directory, "perf_%g.data" % duration)
    command = ["taskset", "-c", str(core)] + prefix + [
        "perf", "record", "-q", "-e", "cpu-clock", "-F", str(frequency), "--call-graph", "dwarf,16384",
        "-o", data, "--", os.path.join(ROOT, "build/bin/uampc"), "launch", scene,
        "--set", "clock.duration=%g" % duration, "--out", os.path.join(directory, "run_%g" % duration)]
    for o in overrides:
        command += ["--set", o]
    run = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        if run.returncode != 0:
            raise ValueError("exit code %d" % run.returncode)
        _, wall_seconds = real_time_factor(run.stdout)
    except ValueError as e:
        sys.exit("loop_profile: the run failed (%s):\n%s" % (e, run.stdout[-3000:]))
    return data, wall_seconds


NOT_UNWOUND = "not unwound (a library's leaf, no caller)"
KERNEL_AND_OTHER = "kernel and other"


def dso_of(frame):
    """The shared object a `perf script` frame line names in its last parentheses."""
    return frame[frame.rfind("(") + 1:frame.rfind(")")]


def owner_of(frames):
    """The part a sample's frames (leaf first) belong to."""
    for frame in frames:
        part = part_of(dso_of(frame))
        if part:
            return part
    return KERNEL_AND_OTHER if dso_of(frames[0]).startswith("[kernel") else NOT_UNWOUND


def leaf_function(frames):
    """The function the sample was taken in, as `perf report` names it: the first frame that is not
    inlined into another, with its shared object's file name."""
    frame = next((f for f in frames if dso_of(f) != "inlined"), frames[0])
    symbol = frame.strip().split(None, 1)[1] if len(frame.split()) > 1 else frame.strip()
    symbol = symbol[:symbol.rfind("(")].strip()
    return "%s (%s)" % (symbol, os.path.basename(dso_of(frame)))


def samples_by_part(script):
    """From `perf script -F comm,tid,ip,sym,dso` output: samples per part, and per part the
    samples per leaf function."""
    counts = collections.Counter()
    functions = collections.defaultdict(collections.Counter)
    for block in script.split("\n\n"):
        frames = [line for line in block.splitlines()[1:] if line.strip()]
        if not frames:
            continue
        part = owner_of(frames)
        counts[part] += 1
        functions[part][leaf_function(frames)] += 1
    return counts, functions


def perf_script(data):
    return subprocess.run(["perf", "script", "-i", data, "-F", "comm,tid,ip,sym,dso"], stdout=subprocess.PIPE,
                          stderr=subprocess.DEVNULL, text=True).stdout


def per_simulated_second(short_counts, long_counts, ms_per_sample, seconds):
    """(key, CPU ms per simulated second) from the samples of a short and a long run, costliest first:
    the difference of the two runs, so that start-up drops out."""
    rows = [(key, (long_counts[key] - short_counts[key]) * ms_per_sample / seconds)
            for key in set(short_counts) | set(long_counts)]
    rows.sort(key=lambda r: (-r[1], r[0]))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default=os.path.join(ROOT, "config/scenes/default.yaml"),
                        help="the scene to run (default: the default scene)")
    parser.add_argument("--short", type=float, default=10.0, help="s of sim time of the short run")
    parser.add_argument("--long", type=float, default=40.0, help="s of sim time of the long run")
    parser.add_argument("--core", type=int, default=0, help="the core both runs are pinned to (taskset)")
    parser.add_argument("--frequency", type=int, default=499, help="samples per CPU second")
    parser.add_argument("--set", action="append", default=[], dest="overrides", metavar="NAME=VALUE",
                        help="an override for both runs, as `uampc launch --set` takes it (repeatable)")
    parser.add_argument("--functions", type=int, default=0, metavar="N",
                        help="also the N costliest functions inside each part above 5 %% of the loop")
    args = parser.parse_args()
    if not args.long > args.short:
        sys.exit("loop_profile: --long must be longer than --short")
    prefix = without_randomisation()
    with tempfile.TemporaryDirectory(prefix="loop_profile.") as directory:
        short_data, short_wall = record(args.scene, args.short, args.core, args.frequency, args.overrides, directory,
                                        prefix)
        long_data, long_wall = record(args.scene, args.long, args.core, args.frequency, args.overrides, directory,
                                      prefix)
        short_counts, short_functions = samples_by_part(perf_script(short_data))
        long_counts, long_functions = samples_by_part(perf_script(long_data))
    seconds = args.long - args.short
    ms_per_sample = 1000.0 / args.frequency
    rows = per_simulated_second(short_counts, long_counts, ms_per_sample, seconds)
    total = sum(r[1] for r in rows)
    startup = (sum(short_counts.values()) * ms_per_sample - total * args.short) / 1000.0
    print("| part | CPU ms per simulated s | share |")
    print("|---|---|---|")
    for part, per_s in rows:
        print("| %s | %.1f | %.0f %% |" % (part, per_s, 100.0 * per_s / total if total else 0.0))
    print("| **all** | **%.1f** (%.1fx real time on one core) | |" % (total, 1000.0 / total if total else 0.0))
    print("\nStart-up (the short run's CPU time less its share of the per-second cost): %.1f s of CPU."
          % startup)
    print("Wall time: %g s of sim time in %.2f s, %g s in %.2f s: %.1fx real time between the two."
          % (args.short, short_wall, args.long, long_wall, seconds / (long_wall - short_wall)))
    if args.functions > 0:
        print("\n| part | function | CPU ms per simulated s | share of the part |")
        print("|---|---|---|---|")
        for part, part_per_s in rows:
            if part_per_s < 0.05 * total:
                continue
            functions = per_simulated_second(short_functions[part], long_functions[part], ms_per_sample, seconds)
            for function, per_s in functions[:args.functions]:
                print("| %s | %s | %.1f | %.0f %% |" % (part, function.replace("|", "\\|"), per_s,
                                                       100.0 * per_s / part_per_s))


if __name__ == "__main__":
    main()
