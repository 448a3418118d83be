"""tools/speed_targets reads the benchmarks' own output: the parsers against what today's binaries
print (so that a changed output format fails here, not in a measurement), and their errors.

Run by CTest (speed_targets_test) with UAMPC_BUILD set to the build directory."""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools", "speed_targets"))
import speed_targets  # noqa: E402

BUILD = os.environ.get("UAMPC_BUILD", os.path.join(ROOT, "build"))


def domain_blocks():
    """The tests' one list of DDS domain blocks (tests/e2e/test_domains.hpp): (block names in enum
    order, domains per block). Block 0 (domains below kLockstep's) is left free for a user's runs."""
    with open(os.path.join(ROOT, "tests", "e2e", "test_domains.hpp")) as header:
        text = header.read()
    enum = re.search(r"enum class DomainBlock \{(.*?)\};", text, re.S).group(1)
    return re.findall(r"^\s*(k\w+)", enum, re.M), int(re.search(r"kDomainsPerTest = (\d+)", text).group(1))


def domain_of_this_test():
    """This test's block's first domain, so that no test beside it under ctest -j2 shares it."""
    blocks, per_test = domain_blocks()
    return (blocks.index("kSpeedTargets") + 1) * per_test  # kLockstep = 1


def output_of(*command):
    return subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, check=True).stdout


class Parsers(unittest.TestCase):
    def test_google_benchmark_time_and_counters(self):
        line = ("BM_ControlStep/100000/1/5       7.20 ms         7.20 ms          101 depth_map_ms=2.45446 "
                "occupied_px=52.558k solve_ms=0.89599")
        self.assertEqual(speed_targets.google_benchmark(line, "BM_ControlStep/100000/1/5"), 7.20)
        self.assertAlmostEqual(speed_targets.google_benchmark(line, "BM_ControlStep/100000/1/5", "occupied_px"), 52558)
        self.assertEqual(speed_targets.google_benchmark(line, "BM_ControlStep/100000/1/5", "solve_ms"), 0.89599)
        rays = "BM_Mid360FramePackets   4.55 ms  4.55 ms  156 rays_per_s=4.39411M/s returns_per_frame=7.22088k"
        self.assertAlmostEqual(speed_targets.google_benchmark(rays, "BM_Mid360FramePackets", "rays_per_s"), 4.39411e6)
        self.assertEqual(speed_targets.google_benchmark("BM_Solve   746 us   746 us   1031", "BM_Solve"), 0.746)

    def test_launch_and_transfer_lines_also_in_exponent_form(self):
        line = "uampc: 2 s of sim time in 9.8e-05 s (2.04082e+04x real time), after a start of 0.1 s"
        self.assertEqual(speed_targets.real_time_factor(line), (20408.2, 9.8e-05))
        line = "uampc: 40 s of sim time in 9.58838 s (4.17172x real time), after a start of 0.679576 s"
        self.assertEqual(speed_targets.real_time_factor(line), (4.17172, 9.58838))
        self.assertEqual(speed_targets.one_way_ms("one way, 20000 points: 0.274 ms (median ...)"), 0.274)

    def test_what_is_missing_is_named(self):
        with self.assertRaisesRegex(ValueError, "BM_Nothing"):
            speed_targets.google_benchmark("BM_Solve   746 us   746 us   1031", "BM_Nothing")
        with self.assertRaisesRegex(ValueError, "rays_per_s"):
            speed_targets.google_benchmark("BM_Solve   746 us   746 us   1031", "BM_Solve", "rays_per_s")
        with self.assertRaisesRegex(ValueError, "real time"):
            speed_targets.real_time_factor("uampc: scene failed")
        with self.assertRaisesRegex(ValueError, "one way"):
            speed_targets.one_way_ms("round trip only")
        with self.assertRaisesRegex(ValueError, "tests passed"):
            speed_targets.ctest_summary("FAILED: uampc\nninja: build stopped: subcommand failed.")

    def test_ctest_summary(self):
        output = ("...\n100% tests passed, 0 tests failed out of 70\n\nLabel Time Summary:\ne2e    = 512.33 sec*proc\n\n"
                  "Total Test time (real) = 245.12 sec\n")
        self.assertEqual(speed_targets.ctest_summary(output), (70, 70, 245.12, []))
        failed = ("97% tests passed, 2 tests failed out of 70\n\nTotal Test time (real) = 301.50 sec\n\n"
                  "The following tests FAILED:\n\t 55 - scene_validation_test (Failed)\n"
                  "\t 81 - security_test (Timeout)\nErrors while running CTest\n")
        self.assertEqual(speed_targets.ctest_summary(failed), (68, 70, 301.5, ["scene_validation_test", "security_test"]))
        self.assertEqual(speed_targets.minutes_and_seconds(783.4), "13 min 03 s")


class Defaults(unittest.TestCase):
    def test_the_default_domain_is_in_the_block_the_tests_leave_free(self):
        _, per_test = domain_blocks()
        self.assertLess(speed_targets.DEFAULT_DOMAIN, per_test)
        self.assertNotEqual(speed_targets.DEFAULT_DOMAIN, 0)  # the default scenes' domain


class MarkdownFile(unittest.TestCase):
    """--write-markdown's file: the printed table under a header that says how to regenerate it, merged
    with the rows the file already has."""

    PATH = os.path.join(ROOT, "docs", "results", "performance.md")
    ROWS = [speed_targets.Row("memory", "max RSS of a 900 s default run", "217 MB", "< 300 MB", True, "2026-11-28"),
            speed_targets.Row("lo", "LO frame (`lo_bench /300/1/0/0`)", "20.9 ms", "<= 5 ms", False, "2026-11-28")]

    def row(self, name, value, met, day):
        figure, target = speed_targets.FIGURES[name]
        return speed_targets.Row(name, figure, value, target, met, day)

    def test_header_table_and_command(self):
        text = speed_targets.markdown_document(self.ROWS, self.PATH, 0)
        self.assertTrue(text.startswith("# Performance\n"))
        self.assertIn("`tools/speed_targets/speed_targets.py --write-markdown docs/results/performance.md "
                      "--memory`", text)
        generated_by = text.split("\n\n")[1]
        self.assertNotIn("--build-times`", generated_by)  # no build rows: the build times' command is not named
        self.assertIn("- `lo`: `lo_bench BM_RegisterScan20k/300/1/0/0`", text)
        self.assertIn("\n".join(speed_targets.table_lines(self.ROWS)), text)
        self.assertIn("| 20.9 ms | <= 5 ms | **missed** | 2026-11-28 |", text)
        self.assertTrue(all(len(line) <= 100 for line in text.splitlines() if not line.startswith("|")))

    def test_the_regenerating_commands_cover_every_row(self):
        rows = [self.row("lo", "20.9 ms", False, "2026-11-28"), self.row("build", "9 min", True, "2026-11-29")]
        text = speed_targets.markdown_document(rows, self.PATH, 0)
        self.assertIn("`tools/speed_targets/speed_targets.py --write-markdown docs/results/performance.md` and "
                      "`tools/speed_targets/speed_targets.py --write-markdown docs/results/performance.md "
                      "--build-times`", text.replace("\n", " "))

    def test_a_document_reads_back_as_its_rows(self):
        rows = self.ROWS + [self.row("tests", "4 min 05 s, 70 of 70 passed", True, "2026-11-29")]
        kept, unknown = speed_targets.rows_of_document(speed_targets.markdown_document(rows, self.PATH, 0))
        self.assertEqual(kept, rows)
        self.assertEqual(unknown, [])

    def test_the_older_layout_reads_with_the_documents_day(self):
        text = ("Measured on 2026-11-28 on an x86_64 machine.\n\n| figure (one core) | value | target | |\n"
                "|---|---|---|---|\n| max RSS of a 900 s default run | 217 MB | < 300 MB | met |\n"
                "| a figure since renamed | 1 ms | <= 2 ms | met |\n")
        kept, unknown = speed_targets.rows_of_document(text)
        self.assertEqual(kept, self.ROWS[:1])
        self.assertEqual(unknown, ["a figure since renamed"])

    def test_a_merge_replaces_the_rows_measured_and_keeps_the_others_in_table_order(self):
        build = self.row("build", "9 min 58 s (build + tests 13 min 03 s)", True, "2026-11-29")
        lo = self.row("lo", "19.0 ms", False, "2026-11-29")
        merged = speed_targets.merged_rows(self.ROWS, [build, lo])
        self.assertEqual(merged, [self.ROWS[0], lo, build])  # memory kept, lo replaced, build added

    def test_writing_merges_into_the_file(self):
        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, "performance.md")
            speed_targets.write_markdown(path, self.ROWS, 0)
            tests = self.row("tests", "4 min 05 s, 70 of 70 passed", True, "2026-11-29")
            speed_targets.write_markdown(path, [tests], 0)
            with open(path) as written:
                kept, _ = speed_targets.rows_of_document(written.read())
        self.assertEqual(kept, self.ROWS + [tests])

    def test_every_target_is_described(self):
        self.assertEqual(sorted(speed_targets.DESCRIPTIONS), sorted(speed_targets.NAMES))
        self.assertEqual(sorted(speed_targets.FIGURES), sorted(speed_targets.NAMES))


class Choice(unittest.TestCase):
    """Which rows a run measures: --build-times alone measures only its own."""

    def names(self, *argv):
        parser = argparse.ArgumentParser()
        args = argparse.Namespace(only=None, memory=False, build_times=False)
        for option in argv:
            key, _, value = option.partition("=")
            setattr(args, key, value or True)
        return speed_targets.chosen_names(args, parser)

    def test_choices(self):
        self.assertEqual(self.names(), ["loop", "lo", "mpc", "raycaster", "lockstep", "pointcloud", "split",
                                        "calibration"])
        self.assertEqual(self.names("memory")[0], "memory")
        self.assertEqual(self.names("build_times"), ["build", "tests"])
        self.assertEqual(self.names("build_times", "memory"), ["memory", "build", "tests"])
        self.assertEqual(self.names("only=lo", "build_times"), ["lo", "build", "tests"])


class TodaysOutputs(unittest.TestCase):
    def test_mpc_bench(self):
        bench = os.path.join(BUILD, "bench", "mpc_bench")
        if not os.path.exists(bench):
            self.skipTest("no benchmarks in this build (the sanitizer builds have none)")
        output = output_of(bench, "--benchmark_filter=BM_Solve", "--benchmark_min_time=0.01")
        self.assertGreater(speed_targets.google_benchmark(output, "BM_Solve"), 0.0)

    def test_launch(self):
        output = output_of(os.path.join(BUILD, "bin", "uampc"), "launch",
                           os.path.join(ROOT, "bench", "scenes", "lockstep_minimal.yaml"), "--set", "clock.duration=2",
                           "--set", "domain_id=%d" % domain_of_this_test())
        factor, seconds = speed_targets.real_time_factor(output)
        self.assertGreater(factor, 1.0)
        self.assertAlmostEqual(factor, 2.0 / seconds, delta=0.01 * factor)


if __name__ == "__main__":
    unittest.main()
