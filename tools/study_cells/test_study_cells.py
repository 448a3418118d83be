"""study_cells.py's statistics against hand-computed values."""
import math
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_cells  # noqa: E402


class StudyCells(unittest.TestCase):
    def test_median_interval_of_15_is_the_4th_and_12th(self):
        # n = 15: P(B <= 3) = 576 / 32768, coverage 0.965; k = 5 would cover only 0.882.
        self.assertEqual(study_cells.median_interval(list(range(1, 16))), (4, 12))

    def test_wilcoxon_exact_p(self):
        # Five positive differences: the most extreme of 2^5 sign patterns, either side: p = 2/32.
        self.assertAlmostEqual(study_cells.wilcoxon_p([1, 2, 3, 4, 5]), 2 / 32)
        # Symmetric differences: p = 1.
        self.assertAlmostEqual(study_cells.wilcoxon_p([-1, 1, -2, 2]), 1.0)

    def test_cell_pairs_and_losses(self):
        runs = []
        for seed in (1, 2, 3):
            runs.append({"scene": "A_pm", "seed": seed, "controller": "u", "ate_m": 1.0, "cmplt": 99.0,
                         "lost_track_at_s": None})
            runs.append({"scene": "A_pm", "seed": seed, "controller": "c", "ate_m": 4.0, "cmplt": 100.0,
                         "lost_track_at_s": 50.0 if seed == 1 else None})
        runs.append({"scene": "B_mesh", "seed": 1, "controller": "u", "ate_m": 9.0, "cmplt": 1.0, "lost_track_at_s": None})
        f = study_cells.cell_figures(runs, "_pm$", "u", "c")
        self.assertEqual(f["pairs"], 3)
        self.assertEqual(f["lost"], {"u": 0, "c": 1})
        self.assertEqual(f["median_lost_at"], {"u": None, "c": 50.0})
        self.assertAlmostEqual(f["sum_ratio"], 0.25)
        self.assertAlmostEqual(f["median_ratio"], 0.25)
        self.assertAlmostEqual(f["cmplt_ratio"], 0.99)
        self.assertTrue(math.isclose(f["baseline_median_ate"], 4.0))

    def test_aligned_ate_is_read_when_asked(self):
        runs = [{"scene": "A", "seed": 1, "controller": "u", "ate_m": 1.0, "ate_aligned_m": 3.0, "cmplt": 1.0},
                {"scene": "A", "seed": 1, "controller": "c", "ate_m": 4.0, "ate_aligned_m": 6.0, "cmplt": 1.0}]
        self.assertAlmostEqual(study_cells.cell_figures(runs, "A", "u", "c")["sum_ratio"], 0.25)
        self.assertAlmostEqual(study_cells.cell_figures(runs, "A", "u", "c", "ate_aligned_m")["sum_ratio"], 0.5)


if __name__ == "__main__":
    unittest.main()
