"""tools/loop_profile charges each perf sample to a part of the system: the rules against stacks in the
form `perf script -F comm,tid,ip,sym,dso` prints them (taken from a recording of the default loop),
without perf or a run.

Run by CTest (loop_profile_test)."""
import collections
import contextlib
import io
import os
import sys
import unittest
from unittest import mock

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools", "loop_profile"))
import loop_profile  # noqa: E402

RAYCASTER = "/work/main/build/lib/uampc/components/libuampc_raycaster.so"
LO = "/work/main/build/lib/uampc/components/libuampc_lo.so"


def frame(symbol, dso):
    return "\t           70c95 %s (%s)" % (symbol, dso)


def sample(*frames):
    return "exe 29052 \n" + "\n".join(frames) + "\n"


COSINE_IN_THE_RAYCASTER = [frame("do_sin", "inlined"), frame("__cos_fma", "/usr/lib/x86_64-linux-gnu/libm.so.6"),
                           frame("uampc::raycaster::RayCaster::castFrame", RAYCASTER)]
COSINE_NOT_UNWOUND = COSINE_IN_THE_RAYCASTER[:2]
SCHEDULER = [frame("finish_task_switch.isra.0", "[kernel.kallsyms]"), frame("schedule", "[kernel.kallsyms]")]
DDS_WRITE_FROM_THE_LO = [frame("eprosima::fastdds::dds::DataWriterImpl::write", "/lib/x86_64-linux-gnu/libfastrtps.so.2.9.1"),
                         frame("uampc::LoComponent::process", LO)]


class Owner(unittest.TestCase):
    def test_a_library_leaf_counts_for_the_first_of_ours_above_it(self):
        self.assertEqual(loop_profile.owner_of(COSINE_IN_THE_RAYCASTER), "component: raycaster")

    def test_the_first_of_ours_from_the_leaf_decides(self):
        self.assertEqual(loop_profile.owner_of(DDS_WRITE_FROM_THE_LO), "DDS (Fast DDS)")

    def test_a_library_leaf_without_a_caller_of_ours_is_not_unwound(self):
        self.assertEqual(loop_profile.owner_of(COSINE_NOT_UNWOUND), loop_profile.NOT_UNWOUND)

    def test_a_kernel_leaf_without_a_caller_of_ours_is_the_kernel(self):
        self.assertEqual(loop_profile.owner_of(SCHEDULER), loop_profile.KERNEL_AND_OTHER)

    def test_our_other_libraries(self):
        for dso, part in [("/work/main/build/lib/libuampc_msgs.so", "serialisation (CDR)"),
                          ("/lib/x86_64-linux-gnu/libfastcdr.so.1", "serialisation (CDR)"),
                          ("/work/main/build/lib/libuampc_runtime.so", "runtime (lockstep, dispatch, logging)"),
                          ("/work/main/build/bin/uampc", "runtime (lockstep, dispatch, logging)"),
                          ("/usr/lib/x86_64-linux-gnu/ld-linux-x86-64.so.2", "start-up (dynamic loading)")]:
            self.assertEqual(loop_profile.owner_of([frame("f", dso)]), part, dso)


class LeafFunction(unittest.TestCase):
    def test_inlined_code_counts_in_the_function_it_was_inlined_into(self):
        self.assertEqual(loop_profile.leaf_function(COSINE_IN_THE_RAYCASTER), "__cos_fma (libm.so.6)")

    def test_our_own_leaf(self):
        self.assertEqual(loop_profile.leaf_function(DDS_WRITE_FROM_THE_LO[1:]),
                         "uampc::LoComponent::process (libuampc_lo.so)")


class Counting(unittest.TestCase):
    def test_samples_by_part_and_function(self):
        script = "\n".join([sample(*COSINE_IN_THE_RAYCASTER), sample(*COSINE_IN_THE_RAYCASTER),
                            sample(*COSINE_NOT_UNWOUND), sample(*SCHEDULER), "exe 29052 \n"])
        counts, functions = loop_profile.samples_by_part(script)
        self.assertEqual(counts, collections.Counter({"component: raycaster": 2, loop_profile.NOT_UNWOUND: 1,
                                                      loop_profile.KERNEL_AND_OTHER: 1}))
        self.assertEqual(functions["component: raycaster"], collections.Counter({"__cos_fma (libm.so.6)": 2}))

    def test_per_simulated_second_is_the_difference_of_the_runs_costliest_first(self):
        short = collections.Counter({"lo": 100, "mpc": 50, "start-up": 40})
        long = collections.Counter({"lo": 400, "mpc": 350, "start-up": 40, "kernel": 3})
        rows = loop_profile.per_simulated_second(short, long, ms_per_sample=2.0, seconds=30.0)
        self.assertEqual(rows, [("lo", 20.0), ("mpc", 20.0), ("kernel", 0.2), ("start-up", 0.0)])


class Randomisation(unittest.TestCase):
    def test_where_it_cannot_be_turned_off_the_profile_runs_with_it_and_says_so(self):
        warning = io.StringIO()
        with mock.patch.object(loop_profile.platform, "machine", return_value="no-such-architecture"), \
                contextlib.redirect_stderr(warning):
            self.assertEqual(loop_profile.without_randomisation(), [])
        self.assertIn("cannot turn the address-space randomisation off", warning.getvalue())
        self.assertIn("no-such-architecture", warning.getvalue())


if __name__ == "__main__":
    unittest.main()
