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
  calibration calibration_bench: a rig calibrated from 30 s of a still Mid-360, s        < 60 s
  memory      the default scene, 900 s: max RSS (only with --memory: about 4 min)     < 300 MB

and, with --build-times, in a temporary clone of the checkout's HEAD (so that uncommitted files do
not count), `CCACHE_DISABLE=1 cmake --workflow --preset test` on every CPU, about 15 min:

  build       its configure and build steps: wall time                                build + tests < 15 min
  tests       its test step: wall time (CTest's own), tests passed                   every test passes

--build-times measures those two rows alone; with --only or --memory, those targets too.

The machine's speed moves from day to day by more than most changes (docs/dev/profiling.md,
"Measuring on a shared machine"): compare figures from one run of this tool, or alternate builds.

  tools/speed_targets/speed_targets.py [--only NAME[,NAME...]] [--core 0] [--memory] [--build-times]
                                       [--domain 11] [--build build] [--write-markdown PATH]

--write-markdown PATH also writes the table into PATH, under a header that says what each row is,
on which machine (`uname -m`, `nproc`) it was measured, and how to regenerate it, each row with the
day it was measured: docs/results/performance.md is written so. The file is merged, not replaced:
the rows measured now replace theirs, every other row of the file stays as it was, with its day
(rows are told apart by their figure, FIGURES below), so that `--build-times` or `--only lo` alone
updates only its rows.

Exit codes: 0 the table was printed (targets missed are not errors), 1 a benchmark failed, 2 bad
arguments or a benchmark binary not built.
"""
import argparse
import collections
import datetime
import os
import platform
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import textwrap
import time

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


def ctest_summary(output):
    """(tests passed, tests run, CTest's own wall seconds, the names of the tests that failed) from the
    end of a `ctest` run's output: '97% tests passed, 2 tests failed out of 70', 'Total Test time
    (real) = 245.12 sec' and the list under 'The following tests FAILED:'."""
    summary = re.search(r"\d+% tests passed, (\d+) tests? failed out of (\d+)", output)
    total = re.search(r"Total Test time \(real\) = +%s sec" % NUMBER, output)
    if not summary or not total:
        raise ValueError("no 'tests passed' and 'Total Test time' lines in the test step's output")
    failed, run_count = int(summary.group(1)), int(summary.group(2))
    names = []
    if "The following tests FAILED:" in output:
        listing = output.split("The following tests FAILED:", 1)[1]
        names = re.findall(r"^\s*\d+ - (\S+) \(", listing, re.M)
    return run_count - failed, run_count, float(total.group(1)), names


def minutes_and_seconds(seconds):
    return "%d min %02d s" % divmod(int(round(seconds)), 60)


BUILD_BUDGET_S = 15 * 60  # a fresh clone's build and tests (docs/dev/testing.md)


class FreshCloneTimes:
    """`CCACHE_DISABLE=1 cmake --workflow --preset test` in a temporary clone of the checkout's HEAD,
    after `docker/install-deps.sh` there (the documented install step, not timed: with the packages
    installed it only fills the clone's node_modules): the workflow's wall time, the test step's
    part of it (CTest's own figure; the rest is configure and build) and the tests passed."""

    def __init__(self):
        self.build_s = self.tests_s = None
        self.passed = self.run_count = None
        self.failed = []  # the names of the tests that failed

    def measure(self):
        if self.build_s is not None:
            return
        head = subprocess.run(["git", "-C", ROOT, "rev-parse", "HEAD"], stdout=subprocess.PIPE, text=True,
                              check=True).stdout.strip()
        work = tempfile.mkdtemp(prefix="uampc_build_times_")
        # mkdtemp makes it 0700; the Slurm test's jobs run as the slurm user, which must reach the
        # clone's build tree as it reaches a checkout's.
        os.chmod(work, 0o755)
        try:
            clone = os.path.join(work, "uampc")
            run(["git", "clone", "--quiet", "--no-checkout", ROOT, clone], "git clone")
            run(["git", "-C", clone, "checkout", "--quiet", "--detach", head], "git checkout")
            run(["bash", os.path.join(clone, "docker", "install-deps.sh")], "docker/install-deps.sh")
            environment = dict(os.environ, CCACHE_DISABLE="1")
            start = time.monotonic()
            result = subprocess.run(["cmake", "--workflow", "--preset", "test"], cwd=clone, env=environment,
                                    stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            wall_s = time.monotonic() - start
            try:
                self.passed, self.run_count, self.tests_s, self.failed = ctest_summary(result.stdout)
            except ValueError:  # the build failed: no test ran
                tail = "\n".join(result.stdout.splitlines()[-20:])
                raise BenchmarkFailed("cmake --workflow --preset test failed (exit %d) in a clone of %s:\n%s"
                                      % (result.returncode, head[:7], tail))
            self.build_s = wall_s - self.tests_s
            if self.failed:  # the clone goes; what the failed tests said stays
                with tempfile.NamedTemporaryFile("w", prefix="uampc_build_times_", suffix=".log",
                                                 delete=False) as log:
                    log.write(result.stdout)
                print("speed_targets: %s failed in the clone; the workflow's output is in %s"
                      % (", ".join(self.failed), log.name), file=sys.stderr)
        finally:
            shutil.rmtree(work, ignore_errors=True)

    def total_s(self):
        return self.build_s + self.tests_s


class Targets:
    def __init__(self, args):
        self.core = str(args.core)
        self.build = os.path.join(ROOT, args.build)
        self.domain = args.domain
        self.loop = None  # (factor, loop seconds) of the one-process loop, for the split
        self.clone = FreshCloneTimes()

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

    # Each measure returns (value text, met); the figure and target texts are FIGURES'.
    def measure_loop(self):
        output, _, _ = self.launch("config/scenes/default.yaml", 40)
        self.loop = real_time_factor(output)
        return "%.2fx real time" % self.loop[0], self.loop[0] >= 10.0

    def measure_lo(self):
        ms = google_benchmark(self.bench("lo_bench", "BM_RegisterScan20k/300/1/0/0"), "BM_RegisterScan20k/300/1/0/0")
        return "%.2f ms" % ms, ms <= 5.0

    def measure_mpc(self):
        output = self.bench("mpc_bench", "BM_ControlStep/100000/1/5$")
        ms = google_benchmark(output, "BM_ControlStep/100000/1/5")
        parts = ", ".join("%s %.2f" % (label, google_benchmark(output, "BM_ControlStep/100000/1/5", counter))
                          for label, counter in (("depth map", "depth_map_ms"), ("U", "uncertainty_ms"),
                                                 ("solve", "solve_ms")))
        return "%.2f ms (%s)" % (ms, parts), ms <= 2.0

    def measure_raycaster(self):
        output = self.bench("raycaster_core_bench", "BM_Mid360FramePackets")
        rays = google_benchmark(output, "BM_Mid360FramePackets", "rays_per_s")
        ms = google_benchmark(output, "BM_Mid360FramePackets")
        return "%.2f M rays/s (%.2f ms per frame)" % (rays / 1e6, ms), rays >= 8e6

    def measure_lockstep(self):
        _, short_cpu, _ = self.launch("bench/scenes/lockstep_minimal.yaml", LOCKSTEP_SHORT_S)
        _, long_cpu, _ = self.launch("bench/scenes/lockstep_minimal.yaml", LOCKSTEP_LONG_S)
        us = (long_cpu - short_cpu) / ((LOCKSTEP_LONG_S - LOCKSTEP_SHORT_S) / SIMULATED_STEP_S) * 1e6
        return "%.1f us per step" % us, us <= 50.0

    def measure_pointcloud(self):
        command = self.pinned(self.binary("bench/dds_transfer_bench"), "--domain", str(self.domain))
        ms = one_way_ms(run(command, "dds_transfer_bench")[0])
        return "%.3f ms one way" % ms, ms <= 0.5

    def measure_split(self):
        if self.loop is None:
            self.measure_loop()
        output, _, _ = self.launch("bench/scenes/default_two_processes.yaml", 40)
        factor, seconds = real_time_factor(output)
        slower = (seconds / self.loop[1] - 1.0) * 100.0
        return "%.2fx real time, %.0f %% slower than in one" % (factor, slower), slower <= 10.0

    def measure_calibration(self):
        seconds = google_benchmark(self.bench("calibration_bench", "BM_Calibrate30sOfMid360"),
                                   "BM_Calibrate30sOfMid360") / 1e3
        return "%.1f s" % seconds, seconds < 60.0

    def measure_memory(self):
        _, _, max_rss_kb = self.launch("config/scenes/default.yaml", 900)
        mb = max_rss_kb / 1024.0
        return "%.0f MB" % mb, mb < 300.0

    def measure_build(self):
        self.clone.measure()
        return ("%s (build + tests %s)" % (minutes_and_seconds(self.clone.build_s),
                                           minutes_and_seconds(self.clone.total_s())),
                self.clone.total_s() < BUILD_BUDGET_S)

    def measure_tests(self):
        self.clone.measure()
        failed = " (failed: %s)" % ", ".join(self.clone.failed) if self.clone.failed else ""
        return ("%s, %d of %d passed%s" % (minutes_and_seconds(self.clone.tests_s), self.clone.passed,
                                           self.clone.run_count, failed),
                self.clone.passed == self.clone.run_count)


# The speed targets, measured on one core, and the fresh clone's build and tests (--build-times).
# memory first: the max RSS of its run is the children's maximum so far (run()).
SPEED_TARGETS = ["memory", "loop", "lo", "mpc", "raycaster", "lockstep", "pointcloud", "split", "calibration"]
BUILD_TIMES = ["build", "tests"]
NAMES = SPEED_TARGETS + BUILD_TIMES  # the table's order

# Each row's figure and target as the table shows them. The figure also names the row when a file
# is merged (rows_of_document): changing one leaves the old row behind as unknown, said on stderr.
FIGURES = {
    "memory": ("max RSS of a 900 s default run", "< 300 MB"),
    "loop": ("whole default loop, 40 s, one process", ">= 10x"),
    "lo": ("LO frame (`lo_bench /300/1/0/0`)", "<= 5 ms"),
    "mpc": ("UA-MPC control step (`mpc_bench /100000/1/5`)", "<= 2 ms"),
    "raycaster": ("raycaster, Mid-360 frame in packets", ">= 8 M rays/s"),
    "lockstep": ("lockstep runtime, one process (%d s minus %d s, CPU)" % (LOCKSTEP_LONG_S, LOCKSTEP_SHORT_S),
                 "<= 50 us"),
    "pointcloud": ("20k-point PointCloud2 between two processes", "<= 0.5 ms"),
    "split": ("the loop split over two processes", "<= 10 % slower"),
    "calibration": ("a rig calibration from 30 s of a still Mid-360", "< 60 s"),
    "build": ("a fresh clone's configure and build (`cmake --workflow --preset test`, every CPU)",
              "build + tests < 15 min"),
    "tests": ("the same workflow's tests (`-j2`)", "every test passes"),
}

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
    "calibration": "`calibration_bench BM_Calibrate30sOfMid360`: `uampc calibrate`'s estimator on 30 s of a "
                   "still Mid-360 in the campus (150 000 points after its downsampling), the recording cast "
                   "before the clock starts",
    "build": "`CCACHE_DISABLE=1 cmake --workflow --preset test` in a temporary clone of the checkout's "
             "HEAD, after `docker/install-deps.sh` there (not timed): the workflow's wall time less its "
             "test step's, i.e. configure and build, on every CPU (only with `--build-times`)",
    "tests": "that workflow's test step: CTest's wall time (`-j2`, the tests that must run alone one "
             "after the other) and the tests passed (only with `--build-times`)",
}

# One row of the table: which target, its texts, whether it was met and the day it was measured.
Row = collections.namedtuple("Row", "name figure value target met measured")


def cpu_count():
    """What `nproc` prints: the CPUs this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count()


def table_lines(rows):
    """The Markdown table this tool prints, one line per row."""
    lines = ["| figure | value | target | | measured |", "|---|---|---|---|---|"]
    for row in rows:
        lines.append("| %s | %s | %s | %s | %s |" % (row.figure, row.value, row.target,
                                                     "met" if row.met else "**missed**", row.measured))
    return lines


def rows_of_document(text):
    """The rows of a file --write-markdown wrote, in its order, and the figures of rows no target has
    (a figure since renamed). A file of the older layout, without a `measured` column, gives each row
    the day of its 'Measured on DAY'."""
    name_of = {figure: name for name, (figure, _) in FIGURES.items()}
    day = re.search(r"Measured on (\d{4}-\d{2}-\d{2})", text)
    rows, unknown = [], []
    for line in text.splitlines():
        if not line.startswith("| ") or not line.endswith(" |"):
            continue
        cells = line[2:-2].split(" | ")
        if cells[0] in ("figure", "figure (one core)"):
            continue
        if cells[0] not in name_of:
            unknown.append(cells[0])
            continue
        measured = cells[4] if len(cells) > 4 else (day.group(1) if day else "unknown")
        rows.append(Row(name_of[cells[0]], cells[0], cells[1], cells[2], cells[3] == "met", measured))
    return rows, unknown


def merged_rows(kept, measured):
    """The file's rows after a run: each target's row as measured now, else as the file had it; in
    NAMES order."""
    by_name = {row.name: row for row in kept}
    by_name.update({row.name: row for row in measured})
    return [by_name[name] for name in NAMES if name in by_name]


def regenerating_commands(path, names):
    """The command lines that measure every row of the file again, its path relative to the checkout:
    the speed targets (with --memory if the file has that row) and the build times."""
    path = os.path.abspath(path)
    if path.startswith(ROOT + os.sep):
        path = os.path.relpath(path, ROOT)
    command = "tools/speed_targets/speed_targets.py --write-markdown %s" % path
    commands = []
    if any(name in SPEED_TARGETS for name in names):
        commands.append(command + (" --memory" if "memory" in names else ""))
    if any(name in BUILD_TIMES for name in names):
        commands.append(command + " --build-times")
    return commands


def markdown_document(rows, path, core):
    """The file --write-markdown writes: a header (what each row is, where it was measured, how to
    regenerate it), then the table, each row with its day."""
    names = [row.name for row in rows]
    commands = ["`%s`" % command for command in regenerating_commands(path, names)]

    def wrapped(text, indent=""):
        """Lines of at most 100 characters, never broken inside a `code span`."""
        keep = "\0"  # stands for a space inside a code span while the text is wrapped
        text = re.sub(r"`[^`]*`", lambda m: m.group(0).replace(" ", keep), text)
        return [line.replace(keep, " ") for line in
                textwrap.wrap(text, width=100, subsequent_indent=indent, break_long_words=False,
                              break_on_hyphens=False)]

    lines = ["# Performance", ""]
    lines += wrapped("Generated by %s; do not edit by hand." % " and ".join(commands))
    lines += [""] + wrapped(
        "The machine-dependent figures of uampc: its speed targets, each measured on one core "
        "(`taskset -c %s`), one after the other, in a Release build, and the time a fresh clone takes to "
        "build and pass its tests, on every CPU. Measured on an %s machine with %d CPUs (`uname -m`, "
        "`nproc`); each row says on which day. Figures of the same code move from day to day (on a shared "
        "virtual machine by 20-50 %%): compare figures from one run of the script, or alternate builds "
        "(docs/dev/profiling.md)." % (core, platform.machine(), cpu_count()))
    lines += ["", "What each row measures:", ""]
    for name in names:
        lines += wrapped("- `%s`: %s." % (name, DESCRIPTIONS[name]), indent="  ")
    lines += [""] + table_lines(rows) + [""]
    lines += wrapped("To regenerate it: build (`cmake --workflow --preset build`), then run %s from the "
                     "checkout (about 3 minutes, 4 more for `--memory`; about 15 for `--build-times`, which "
                     "needs no build). A run rewrites the rows it measures and keeps the file's others as "
                     "they were, with their day: `--only NAME,...` or `--build-times` alone update only "
                     "their rows." % " and ".join(commands))
    return "\n".join(lines) + "\n"


def chosen_names(args, parser):
    """The targets this run measures: the speed targets (--only's, else all but memory, with it under
    --memory) unless --build-times comes alone, and the build times with --build-times."""
    if args.only:
        names = [n.strip() for n in args.only.split(",")]
        unknown = [n for n in names if n not in SPEED_TARGETS]
        if unknown:
            parser.error("unknown target %s; choose from %s (and --build-times)"
                         % (", ".join(unknown), ", ".join(SPEED_TARGETS)))
        if args.memory and "memory" not in names:
            names.append("memory")
        names = list(dict.fromkeys(names))  # each once
    elif args.build_times and not args.memory:
        names = []
    elif args.build_times:
        names = ["memory"]
    else:
        names = [n for n in SPEED_TARGETS if n != "memory" or args.memory]
    if args.build_times:
        names += BUILD_TIMES
    return sorted(names, key=NAMES.index)


def write_markdown(path, measured, core):
    """Merges the rows measured now into PATH (rows_of_document, merged_rows) and writes it."""
    kept = []
    if os.path.exists(path):
        with open(path) as existing:
            kept, unknown = rows_of_document(existing.read())
        for figure in unknown:
            print("speed_targets: %s: dropped the row '%s': no target has that figure now" % (path, figure),
                  file=sys.stderr)
    with open(path, "w") as out:
        out.write(markdown_document(merged_rows(kept, measured), path, core))
    print("speed_targets: wrote %s" % path, file=sys.stderr)


def main(argv):
    parser = argparse.ArgumentParser(description="uampc's speed targets on one core, in one table.")
    parser.add_argument("--only", help="comma-separated subset of: " + ", ".join(SPEED_TARGETS))
    parser.add_argument("--core", type=int, default=0, help="the core every benchmark runs on (default 0)")
    parser.add_argument("--memory", action="store_true", help="also the 900 s run's max RSS (about 4 min)")
    parser.add_argument("--build-times", action="store_true",
                        help="time `CCACHE_DISABLE=1 cmake --workflow --preset test` in a temporary clone of HEAD "
                             "(about 15 min, every CPU): its build and test parts; alone, only those rows")
    parser.add_argument("--domain", type=int, default=DEFAULT_DOMAIN,
                        help="DDS domain of the runs (default %d)" % DEFAULT_DOMAIN)
    parser.add_argument("--build", default="build", help="build directory, relative to the checkout")
    parser.add_argument("--write-markdown", metavar="PATH",
                        help="also write the table, with what each row is and the machine and day it was "
                             "measured on, into PATH (e.g. docs/results/performance.md), merged with the rows "
                             "PATH has")
    args = parser.parse_args(argv)
    if args.write_markdown and not os.path.isdir(os.path.dirname(os.path.abspath(args.write_markdown))):
        parser.error("--write-markdown %s: its directory does not exist" % args.write_markdown)
    names = chosen_names(args, parser)
    targets = Targets(args)
    today = datetime.date.today().isoformat()
    rows = []
    try:
        for name in names:
            print("measuring %s ..." % name, file=sys.stderr, flush=True)
            value, met = getattr(targets, "measure_" + name)()
            figure, target = FIGURES[name]
            rows.append(Row(name, figure, value, target, met, today))
    except FileNotFoundError as e:
        print("speed_targets: %s" % e, file=sys.stderr)
        return 2
    except (BenchmarkFailed, ValueError) as e:
        print("speed_targets: %s" % e, file=sys.stderr)
        return 1
    print("\n".join(table_lines(rows)))
    if args.write_markdown:
        write_markdown(args.write_markdown, rows, args.core)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
