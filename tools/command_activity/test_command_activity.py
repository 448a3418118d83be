"""command_activity.py on motor.csv files written here: a constant command has no chatter; a
command that jumps between the bounds every step has one large change per step."""
import io
import os
import sys
import tempfile
import unittest
from contextlib import redirect_stdout

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import command_activity  # noqa: E402


def run_dir(root, name, command_at):
    path = os.path.join(root, name)
    os.makedirs(path)
    with open(os.path.join(path, "motor.csv"), "w") as f:
        f.write("time,theta,omega,command\n")
        for i in range(401):  # 2 s at 5 ms
            t = 0.005 * i
            f.write(f"{t},0,0,{command_at(t)}\n")
    return path


class CommandActivity(unittest.TestCase):
    def test_constant_and_bang_bang_commands(self):
        with tempfile.TemporaryDirectory() as root:
            constant = run_dir(root, "constant", lambda t: 3.6)
            bang = run_dir(root, "bang", lambda t: 7.2 if int(round(t / 0.1)) % 2 else 0.0)
            a = command_activity.activity(command_activity.command_samples(os.path.join(constant, "motor.csv"), 0.1, 0.0),
                                          0.1, 7.2)
            self.assertEqual(a["mean_change"], 0.0)
            self.assertEqual(a["share_at_bounds"], 0.0)
            b = command_activity.activity(command_activity.command_samples(os.path.join(bang, "motor.csv"), 0.1, 0.0),
                                          0.1, 7.2)
            self.assertAlmostEqual(b["mean_change"], 7.2, places=6)
            self.assertAlmostEqual(b["big_changes_per_s"], 10.0, places=6)
            self.assertEqual(b["share_at_bounds"], 1.0)
            out = io.StringIO()
            with redirect_stdout(out):
                self.assertEqual(command_activity.main(["command_activity", constant, bang]), 0)
            self.assertIn("| median of 2 |", out.getvalue())

    def test_a_run_without_motor_csv_is_an_error(self):
        with tempfile.TemporaryDirectory() as root:
            with redirect_stdout(io.StringIO()):
                self.assertEqual(command_activity.main(["command_activity", root]), 2)


if __name__ == "__main__":
    unittest.main()
