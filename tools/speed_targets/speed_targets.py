#!/usr/bin/env python3
"""uampc's speed targets, each measured on one core, in one table.

Runs every benchmark the targets name on one core (`taskset -c CORE`), one after the other, and
prints a Markdown table of figure, value, target and whether it is met on this machine today:

  loop        the default scene, 40 s of sim time, in one process: real-time factor   >= 10x
  lo          lo_bench BM_RegisterScan20k/300/1/0/0: ms per 20k-point frame           <= 5 ms
  mpc         mpc_bench BM_ControlStep/100000/1/5: ms per control step               <= 2 ms
  raycaster   raycaster_core_bench BM_Mid360FramePackets: rays per second             >= 8 M/s
  lockstep    bench/scenes/lockstep_minimal.yaml, a 120 s minus a 10 s run: CPU us per step  <= 50 us
  pointcloud  dds_transfer_bench: a 20k-point PointCloud2 one way, ms (median)        <= 0.5 ms
  split       bench/scenes/default_two_processes.yaml against `loop`: slower by       <= 10 %
  memory      the default scene, 900 s: max RSS (only with --memory: about 4 min)     < 300 MB

The machine's speed moves from day to day by more than most changes (docs/dev/profiling.md,
"Measuring on a shared machine"): compare figures from one run of this tool, or alternate builds.

  tools/speed_targets/speed_targets.py [--only NAME[,NAME...]] [--core 0] [--memory]
                                       [--domain 11] [--build build] [--write-markdown PATH]

--write-markdown PATH also writes the table into PATH, under a header that says what each row is,
when and on which machine (`uname -m`, `nproc`) it was measured, and how to regenerate it:
docs/results/performance.md is written so.

Exit codes: 0 the table was printed (targets missed are not errors), 1 a benchmark failed, 2 bad
arguments or a benchmark binary not built.
"""
import argparse
import datetime
import os
import platform
import re
import resource
import subprocess
import sys
import textwrap

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools", "common"))
from launch_output import NUMBER, real_time_factor  # noqa: E402  (the launcher's last line, read once)

SIMULATED_STEP_S = 0.005  # clock.step of the scenes measured here (config/scenes/default.yaml)
LOCKSTEP_SHORT_S, LOCKSTEP_LONG_S = 10, 120  # the lockstep runs: their difference drops the start
# Block 0 of DDS domains (0-11) is the one the tests leave free for a user's runs
# (tests/e2e/test_domains.hpp); 11, so as not to meet a default scene on domain 0 either.
DEFAULT_DOMAIN = 11


class BenchmarkFailed(Exception):
    pass


def run(command, what):
    """Runs a command; returns (stdout + stderr, CPU seconds of it and its children, the largest max
    RSS in KB of any child so far: a `--memory` run comes first)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if result.returncode != 0:
        tail = "\n".join(result.stdout.splitlines()[-10:])
        raise BenchmarkFailed("%s failed (exit %d): %s\n%s" % (what, result.returncode, " ".join(command), tail))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return result.stdout, cpu, after.ru_maxrss


def google_benchmark(output, name, counter=None):
    """Time (ms) of the benchmark line `name`, or the value of its user counter."""
    for line in output.splitlines():
        fields = line.split()
        if not fields or not fields[0].startswith(name):
            continue
        if counter is None:
            value, unit = float(fields[1]), fields[2]
            return value * {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[unit]
        m = re.search(r"\b%s=([0-9.]+)([kMG]?)" % re.escape(counter), line)
        if m:
            return float(m.group(1)) * {"": 1.0, "k": 1e3, "M": 1e6, "G": 1e9}[m.group(2)]
    raise ValueError("no line for %s%s in the benchmark's output" % (name, " with " + counter if counter else ""))


def one_way_ms(output):
    """dds_transfer_bench: 'one way, 20000 points: 0.274 ms (...)'."""
    m = re.search(r"one way, \d+ points: %s ms" % NUMBER, output)
    if not m:
        raise ValueError("no 'one way' line in dds_transfer_bench's output")
    return float(m.group(1))


class Targets:
    def __init__(self, args):
        self.core = str(args.core)
        self.build = os.path.join(ROOT, args.build)
        self.domain = args.domain
        self.loop = None  # (factor, loop seconds) of the one-process loop, for the split

    def binary(self, relative):
        path = os.path.join(self.build, relative)
        if not os.access(path, os.X_OK):
            raise FileNotFoundError("%s is not built (cmake --workflow --preset build)" % path)
        return path

    def pinned(self, *command):
        return ["taskset", "-c", self.core] + list(command)

    def launch(self, scene, duration):
        command = self.pinned(self.binary("bin/uampc"), "launch", os.path.join(ROOT, scene), "--set",
                              "clock.duration=%g" % duration, "--set", "domain_id=%d" % self.domain)
        return run(command, "uampc launch " + scene)

    def bench(self, binary, pattern):
        output, _, _ = run(self.pinned(self.binary("bench/" + binary), "--benchmark_filter=" + pattern), binary)
        return output

    # Each measure returns (figure, value text, target text, met).
    def measure_loop(self):
        output, _, _ = self.launch("config/scenes/default.yaml", 40)
        self.loop = real_time_factor(output)
        return ("whole default loop, 40 s, one process", "%.2fx real time" % self.loop[0], ">= 10x",
                self.loop[0] >= 10.0)

    def measure_lo(self):
        ms = google_benchmark(self.bench("lo_bench", "BM_RegisterScan20k/300/1/0/0"), "BM_RegisterScan20k/300/1/0/0")
        return ("LO frame (`lo_bench /300/1/0/0`)", "%.2f ms" % ms, "<= 5 ms", ms <= 5.0)

    def measure_mpc(self):
        output = self.bench("mpc_bench", "BM_ControlStep/100000/1/5$")
        ms = google_benchmark(output, "BM_ControlStep/100000/1/5")
        parts = ", ".join("%s %.2f" % (label, google_benchmark(output, "BM_ControlStep/100000/1/5", counter))
                          for label, counter in (("depth map", "depth_map_ms"), ("U", "uncertainty_ms"),
                                                 ("solve", "solve_ms")))
        return ("UA-MPC control step (`mpc_bench /100000/1/5`)", "%.2f ms (%s)" % (ms, parts), "<= 2 ms", ms <= 2.0)

    def measure_raycaster(self):
        output = self.bench("raycaster_core_bench", "BM_Mid360FramePackets")
        rays = google_benchmark(output, "BM_Mid360FramePackets", "rays_per_s")
        ms = google_benchmark(output, "BM_Mid360FramePackets")
        return ("raycaster, Mid-360 frame in packets", "%.2f M rays/s (%.2f ms per frame)" % (rays / 1e6, ms),
                ">= 8 M rays/s", rays >= 8e6)

    def measure_lockstep(self):
        _, short_cpu, _ = self.launch("bench/scenes/lockstep_minimal.yaml", LOCKSTEP_SHORT_S)
        _, long_cpu, _ = self.launch("bench/scenes/lockstep_minimal.yaml", LOCKSTEP_LONG_S)
        us = (long_cpu - short_cpu) / ((LOCKSTEP_LONG_S - LOCKSTEP_SHORT_S) / SIMULATED_STEP_S) * 1e6
        return ("lockstep runtime, one process (%d s minus %d s, CPU)" % (LOCKSTEP_LONG_S, LOCKSTEP_SHORT_S),
                "%.1f us per step" % us, "<= 50 us", us <= 50.0)

    def measure_pointcloud(self):
        command = self.pinned(self.binary("bench/dds_transfer_bench"), "--domain", str(self.domain))
        ms = one_way_ms(run(command, "dds_transfer_bench")[0])
        return ("20k-point PointCloud2 between two processes", "%.3f ms one way" % ms, "<= 0.5 ms", ms <= 0.5)

    def measure_split(self):
        if self.loop is None:
            self.measure_loop()
        output, _, _ = self.launch("bench/scenes/default_two_processes.yaml", 40)
        factor, seconds = real_time_factor(output)
        slower = (seconds / self.loop[1] - 1.0) * 100.0
        return ("the loop split over two processes", "%.2fx real time, %.0f %% slower than in one" % (factor, slower),
                "<= 10 % slower", slower <= 10.0)

    def measure_memory(self):
        _, _, max_rss_kb = self.launch("config/scenes/default.yaml", 900)
        mb = max_rss_kb / 1024.0
        return ("max RSS of a 900 s default run", "%.0f MB" % mb, "< 300 MB", mb < 300.0)


NAMES = ["loop", "lo", "mpc", "raycaster", "lockstep", "pointcloud", "split", "memory"]

# What each row measures, for the header of --write-markdown's file.
DESCRIPTIONS = {
    "memory": "the default scene run for 900 s of sim time in one process: the largest max RSS of its "
              "processes (only with `--memory`)",
    "loop": "the default scene (`config/scenes/default.yaml`), 40 s of sim time, in one process: the "
            "launcher's real-time factor of the loop, start-up apart",
    "lo": "`lo_bench BM_RegisterScan20k/300/1/0/0`: one 20k-point Mid-360 frame registered by the LO "
          "(0.3 m scan voxels, each frame's own velocity, no registration budget)",
    "mpc": "`mpc_bench BM_ControlStep/100000/1/5`: one UA-MPC control step on a 100k-point local map "
           "(1-degree panorama, U every 5 degrees), with its depth map, U and solve parts",
    "raycaster": "`raycaster_core_bench BM_Mid360FramePackets`: a Mid-360 frame on the campus, cast in "
                 "Embree packets: rays per second and ms per frame",
    "lockstep": "`bench/scenes/lockstep_minimal.yaml` (a motor bridge and a constant-speed controller), "
                "the CPU time of a %d s run minus a %d s run: the lockstep runtime's own cost per step"
                % (LOCKSTEP_LONG_S, LOCKSTEP_SHORT_S),
    "pointcloud": "`dds_transfer_bench`: a 20k-point PointCloud2 between two processes over Fast DDS, one "
                  "way, median",
    "split": "`bench/scenes/default_two_processes.yaml` (the default loop in a simulator and an estimation "
             "process), 40 s: real-time factor, and how much slower than the `loop` row",
}


def cpu_count():
    """What `nproc` prints: the CPUs this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count()


def table_lines(rows):
    """The Markdown table this tool prints, one line per row."""
    lines = ["| figure (one core) | value | target | |", "|---|---|---|---|"]
    for figure, value, target, met in rows:
        lines.append("| %s | %s | %s | %s |" % (figure, value, target, "met" if met else "**missed**"))
    return lines


def regenerating_command(args):
    """The command line that writes the same file again, its path relative to the checkout."""
    path = os.path.abspath(args.write_markdown)
    if path.startswith(ROOT + os.sep):
        path = os.path.relpath(path, ROOT)
    command = "tools/speed_targets/speed_targets.py --write-markdown %s" % path
    if args.memory:
        command += " --memory"
    if args.only:
        command += " --only %s" % args.only
    return command


def markdown_document(names, rows, args, today=None):
    """The file --write-markdown writes: a header (what each row is, when and where it was measured,
    how to regenerate it), then the table."""
    today = today or datetime.date.today().isoformat()
    command = regenerating_command(args)
    def wrapped(text, indent=""):
        """Lines of at most 100 characters, never broken inside a `code span`."""
        keep = "\0"  # stands for a space inside a code span while the text is wrapped
        text = re.sub(r"`[^`]*`", lambda m: m.group(0).replace(" ", keep), text)
        return [line.replace(keep, " ") for line in
                textwrap.wrap(text, width=100, subsequent_indent=indent, break_long_words=False,
                              break_on_hyphens=False)]

    lines = ["# Performance", ""]
    lines += wrapped("Generated by `%s`; do not edit by hand." % command)
    lines += [""] + wrapped(
        "The machine-dependent figures of uampc: its speed targets, each measured on one core "
        "(`taskset -c %s`), one after the other, in a Release build. Measured on %s on an %s machine with %d "
        "CPUs (`uname -m`, `nproc`). Figures of the same code move from day to day (on a shared virtual "
        "machine by 20-50 %%): compare figures from one run of the script, or alternate builds "
        "(docs/dev/profiling.md)." % (args.core, today, platform.machine(), cpu_count()))
    lines += ["", "What each row measures:", ""]
    for name in names:
        lines += wrapped("- `%s`: %s." % (name, DESCRIPTIONS[name]), indent="  ")
    lines += [""] + table_lines(rows) + [""]
    lines += wrapped("To regenerate it: build (`cmake --workflow --preset build`), then run `%s` from the "
                     "checkout (about 3 minutes, 4 more for `--memory`)." % command)
    return "\n".join(lines) + "\n"


def main(argv):
    parser = argparse.ArgumentParser(description="uampc's speed targets on one core, in one table.")
    parser.add_argument("--only", help="comma-separated subset of: " + ", ".join(NAMES))
    parser.add_argument("--core", type=int, default=0, help="the core every benchmark runs on (default 0)")
    parser.add_argument("--memory", action="store_true", help="also the 900 s run's max RSS (about 4 min)")
    parser.add_argument("--domain", type=int, default=DEFAULT_DOMAIN,
                        help="DDS domain of the runs (default %d)" % DEFAULT_DOMAIN)
    parser.add_argument("--build", default="build", help="build directory, relative to the checkout")
    parser.add_argument("--write-markdown", metavar="PATH",
                        help="also write the table, with what each row is and the date and machine it was "
                             "measured on, into PATH (e.g. docs/results/performance.md)")
    args = parser.parse_args(argv)
    if args.write_markdown and not os.path.isdir(os.path.dirname(os.path.abspath(args.write_markdown))):
        parser.error("--write-markdown %s: its directory does not exist" % args.write_markdown)
    names = [n for n in NAMES if n != "memory" or args.memory]
    if args.only:
        names = [n.strip() for n in args.only.split(",")]
        unknown = [n for n in names if n not in NAMES]
        if unknown:
            parser.error("unknown target %s; choose from %s" % (", ".join(unknown), ", ".join(NAMES)))
    # The max RSS of the memory run is the children's maximum so far: run it first.
    names.sort(key=lambda n: n != "memory")
    targets = Targets(args)
    rows = []
    try:
        for name in names:
            print("measuring %s ..." % name, file=sys.stderr, flush=True)
            rows.append(getattr(targets, "measure_" + name)())
    except FileNotFoundError as e:
        print("speed_targets: %s" % e, file=sys.stderr)
        return 2
    except (BenchmarkFailed, ValueError) as e:
        print("speed_targets: %s" % e, file=sys.stderr)
        return 1
    print("\n".join(table_lines(rows)))
    if args.write_markdown:
        with open(args.write_markdown, "w") as out:
            out.write(markdown_document(names, rows, args))
        print("speed_targets: wrote %s" % args.write_markdown, file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
