"""window.py: error norms averaged over a time window of timeseries.csv, against sums done by hand."""

import json
import math
import os
import tempfile
import unittest

from sph_study.window import window_statistics


def write_run(folder, rows, errors=None):
    with open(os.path.join(folder, "timeseries.csv"), "w") as f:
        f.write("step,t,dt,kinetic_energy,ksp_iterations,e_u,e_v\n")
        for r in rows:
            f.write(",".join(str(x) for x in r) + "\n")
    if errors is not None:
        with open(os.path.join(folder, "summary.json"), "w") as f:
            json.dump({"errors": errors}, f)


class WindowStatistics(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        # Steps of dt 0.5 then 1.0; e_u = 1, 2, 3, 4, 5; e_v = 10 everywhere.
        write_run(self.dir, [(1, 0.5, 0.5, 1.0, 3, 1.0, 10.0), (2, 1.0, 0.5, 1.0, 3, 2.0, 10.0),
                             (3, 2.0, 1.0, 1.0, 3, 3.0, 10.0), (4, 3.0, 1.0, 1.0, 3, 4.0, 10.0),
                             (5, 4.0, 1.0, 1.0, 3, 5.0, 10.0)])

    def tearDown(self):
        self.tmp.cleanup()

    def test_time_weighted_mean_min_max(self):
        stats, (t0, t1, count) = window_statistics(self.dir, 1.0, 3.0)
        # Steps at t = 1, 2, 3 with dt 0.5, 1, 1: mean (0.5*2 + 3 + 4) / 2.5 = 3.2.
        self.assertAlmostEqual(stats["e_u"][0], 3.2, places=14)
        self.assertEqual(stats["e_u"][1:], (2.0, 4.0))
        self.assertEqual(stats["e_v"], (10.0, 10.0, 10.0))
        self.assertEqual((t0, t1, count), (1.0, 3.0, 3))

    def test_bookkeeping_columns_are_not_norms(self):
        stats, _ = window_statistics(self.dir, 0.0)
        self.assertEqual(sorted(stats), ["e_u", "e_v"])

    def test_summary_names_the_norms(self):
        write_run(self.dir, [(1, 1.0, 1.0, 1.0, 3, 1.0, 10.0)], errors={"e_v": 10.0})
        stats, _ = window_statistics(self.dir, 0.0)
        self.assertEqual(sorted(stats), ["e_v"])

    def test_open_window_runs_to_the_end(self):
        stats, (t0, t1, count) = window_statistics(self.dir, 2.5)
        self.assertEqual((t0, t1, count), (3.0, 4.0, 2))
        self.assertAlmostEqual(stats["e_u"][0], 4.5, places=14)
        self.assertEqual(window_statistics(self.dir, 2.5, math.inf), window_statistics(self.dir, 2.5))

    def test_empty_window_names_the_run_times(self):
        with self.assertRaisesRegex(ValueError, "no step with 9.0 <= t"):
            window_statistics(self.dir, 9.0)


if __name__ == "__main__":
    unittest.main()
