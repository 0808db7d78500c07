"""orders.py: observed order, time to reach an error level, error levels, the speed table (the arithmetic
of --self-test)."""

import math
import unittest

from sph_study.orders import nice_levels, observed_order, pareto_table, time_to_reach

# Two power-law lines: A has e = 0.1 / t, B has e = 0.1 / t^2; log-log interpolation is exact.
A = [(1.0, 1e-1), (10.0, 1e-2), (100.0, 1e-3)]
B = [(1.0, 1e-1), (2.0, 2.5e-2), (4.0, 6.25e-3)]


class ObservedOrder(unittest.TestCase):
    def test_second_order(self):  # order 4e-2 -> 1e-2 at h 0.1 -> 0.05 is 2
        self.assertAlmostEqual(observed_order(4e-2, 1e-2, 0.1, 0.05), 2.0, places=12)

    def test_first_order(self):
        self.assertAlmostEqual(observed_order(1e-2, 5e-3, 0.1, 0.05), 1.0, places=12)

    def test_third_order_over_a_factor_3(self):
        self.assertAlmostEqual(observed_order(27e-3, 1e-3, 0.3, 0.1), 3.0, places=12)

    def test_negative_when_the_error_grows(self):
        self.assertAlmostEqual(observed_order(1e-2, 2e-2, 0.1, 0.05), -1.0, places=12)

    def test_strings_are_numbers(self):  # values as read from CSV
        self.assertAlmostEqual(observed_order("4e-2", "1e-2", "0.1", "0.05"), 2.0, places=12)

    def test_undefined(self):
        self.assertIsNone(observed_order(0.0, 1e-2, 0.1, 0.05))      # zero error
        self.assertIsNone(observed_order(-1e-2, 1e-2, 0.1, 0.05))    # negative error
        self.assertIsNone(observed_order(1e-2, 1e-3, 0.1, 0.1))      # equal h
        self.assertIsNone(observed_order(None, 1e-3, 0.1, 0.05))     # missing value
        self.assertIsNone(observed_order("x", 1e-3, 0.1, 0.05))      # not a number
        self.assertIsNone(observed_order(float("nan"), 1e-3, 0.1, 0.05))
        self.assertIsNone(observed_order(float("inf"), 1e-3, 0.1, 0.05))


class TimeToReach(unittest.TestCase):
    def test_at_a_run_point(self):
        t, exact = time_to_reach(A, 1e-2)
        self.assertAlmostEqual(t, 10.0, places=10)
        self.assertTrue(exact)

    def test_interpolated_log_log(self):
        t, exact = time_to_reach(B, 1e-2)
        self.assertAlmostEqual(t, math.sqrt(10.0), places=10)
        self.assertTrue(exact)
        self.assertAlmostEqual(time_to_reach(A, 2e-3)[0], 50.0, places=9)

    def test_unreachable(self):
        self.assertEqual(time_to_reach(B, 1e-3), (None, False))

    def test_above_the_coarsest_error_is_an_upper_bound(self):
        self.assertEqual(time_to_reach(A, 0.5), (1.0, False))

    def test_unusable_points_are_dropped(self):
        self.assertEqual(time_to_reach([], 1e-2), (None, False))
        self.assertEqual(time_to_reach([(None, 1e-2), (0.0, 1e-3), (1.0, float("nan"))], 1e-2), (None, False))
        t, exact = time_to_reach([(None, 1.0)] + A, 1e-2)
        self.assertAlmostEqual(t, 10.0, places=10)
        self.assertTrue(exact)


class NiceLevels(unittest.TestCase):
    def test_1_2_5_steps(self):
        self.assertEqual(nice_levels(3e-3, 0.04), [0.02, 0.01, 0.005])

    def test_narrow_range_gives_5_geometric_2_digit_values(self):
        self.assertEqual(nice_levels(4.416e-3, 6.584e-3), [0.0065, 0.006, 0.0054, 0.0049, 0.0045])

    def test_very_narrow_range(self):
        self.assertGreaterEqual(len(nice_levels(4.41e-3, 4.9e-3)), 3)

    def test_wide_range_keeps_decades(self):
        levels = nice_levels(1e-8, 1.0)
        self.assertLessEqual(len(levels), 8)
        self.assertEqual(levels, sorted(levels, reverse=True))
        for v in levels:
            self.assertAlmostEqual(math.log10(v), round(math.log10(v)), places=9)

    def test_levels_lie_in_the_range_and_decrease(self):
        for lo, hi in ((1e-3, 1e-1), (2e-4, 7e-4), (0.013, 0.9), (5e-6, 5e-6 * 1.5)):
            levels = nice_levels(lo, hi)
            self.assertEqual(levels, sorted(set(levels), reverse=True))
            self.assertTrue(all(lo * (1 - 1e-9) <= v <= hi * (1 + 1e-9) for v in levels), (lo, hi, levels))

    def test_empty_range(self):
        self.assertEqual(nice_levels(0.0, 1.0), [])
        self.assertEqual(nice_levels(1e-2, 1e-3), [])


class ParetoTable(unittest.TestCase):
    def test_given_levels(self):
        rows = pareto_table({"A": A, "B": B}, levels=[1e-2, 5e-3, 1e-3])
        self.assertEqual([r["level"] for r in rows], [1e-2, 5e-3, 1e-3])
        # B ahead at 1e-2 by 10 / sqrt(10)
        self.assertEqual((rows[0]["best"], rows[0]["runner_up"]), ("B", "A"))
        self.assertAlmostEqual(rows[0]["speedup"], math.sqrt(10.0), places=10)
        # only A reaches 5e-3 and 1e-3
        self.assertEqual((rows[1]["best"], rows[1]["runner_up"], rows[1]["speedup"]), ("A", None, None))
        self.assertEqual(rows[2]["best"], "A")
        self.assertEqual(rows[1]["times"]["B"], (None, False))

    def test_automatic_levels_span_the_lines(self):
        auto = pareto_table({"A": A, "B": B})
        self.assertEqual(auto[0]["level"], 0.1)
        self.assertEqual(auto[-1]["level"], 1e-3)

    def test_no_level_reached(self):
        rows = pareto_table({"A": A}, levels=[1e-6])
        self.assertEqual(rows, [{"level": 1e-6, "times": {"A": (None, False)}, "best": None, "runner_up": None,
                                 "speedup": None}])

    def test_lines_without_usable_points(self):
        self.assertEqual(pareto_table({}), [])
        self.assertEqual(pareto_table({"A": [(0.0, 1e-2), (None, 1e-3)]}), [])
        rows = pareto_table({"A": A, "empty": [(1.0, 0.0)]}, levels=[1e-2])
        self.assertEqual(list(rows[0]["times"]), ["A"])


if __name__ == "__main__":
    unittest.main()
