"""plots.py: the figures built from rows as collect() makes them (no run folders), and save()."""

import importlib.util
import os
import unittest

from sph_study.tests.support import TempDirCase

HAVE_MATPLOTLIB = importlib.util.find_spec("matplotlib") is not None


def row(nx, wall, errors, ksp=None):
    """A completed run's row with the fields the figures read."""
    return {"status": "completed", "nx": nx, "N": nx * nx, "h": 1.0 / nx, "wall_time_s": wall, "errors": errors,
            "ksp_iterations_mean": ksp, "ksp_iterations_max": None if ksp is None else ksp + 3}


# amplitude_rel is signed: negative at nx 10 and 40. The wcsph nx 10 run took 0.5 s: noise.
GROUPS = {
    "isph": [row(10, 2.0, {"l1_velocity": 4e-2, "amplitude_rel": -3e-2}, ksp=12.0),
             row(20, 8.0, {"l1_velocity": 1e-2, "amplitude_rel": 8e-3}, ksp=14.0),
             row(40, 32.0, {"l1_velocity": 2.5e-3, "amplitude_rel": -2e-3}, ksp=15.0)],
    "wcsph": [row(10, 0.5, {"l1_velocity": 5e-2, "amplitude_rel": 1e-2}),
              row(20, 3.0, {"l1_velocity": 2.5e-2, "amplitude_rel": 5e-3})],
}


def legend_labels(legend):
    return [t.get_text() for t in legend.get_texts()]


def marker_faces(ax):
    """(x, y, face colour) of the single-point marker overlays draw_line adds."""
    from matplotlib.colors import to_hex
    return [(l.get_xdata()[0], l.get_ydata()[0], to_hex(l.get_markerfacecolor()))
            for l in ax.get_lines() if len(l.get_xdata()) == 1]


@unittest.skipUnless(HAVE_MATPLOTLIB, "matplotlib not available")
class Figures(TempDirCase):
    def setUp(self):
        super().setUp()
        from sph_study.plots import plotting
        self.plt = plotting()
        self.addCleanup(self.plt.close, "all")

    def test_pdf_written_beside_png(self):
        from sph_study.plots import figure_error_vs_h, save
        path = os.path.join(self.tmp, "error_vs_h.png")
        save(self.plt, figure_error_vs_h(self.plt, GROUPS, "l1_velocity", "t"), path)
        self.assertEqual(sorted(os.listdir(self.tmp)), ["error_vs_h.pdf", "error_vs_h.png"])
        with open(os.path.join(self.tmp, "error_vs_h.pdf"), "rb") as f:
            self.assertEqual(f.read(5), b"%PDF-")

    def test_signed_metric_plotted_by_magnitude(self):
        from sph_study.plots import figure_error_vs_h
        ax = figure_error_vs_h(self.plt, GROUPS, "amplitude_rel", "t").axes[0]
        self.assertEqual(ax.get_ylabel(), "|amplitude_rel|")
        isph = [l for l in ax.get_lines() if l.get_label() == "isph"][0]
        self.assertEqual(list(isph.get_ydata()), [3e-2, 8e-3, 2e-3])
        # the negative values: open (white) markers, named in the legend
        self.assertEqual([(x, y) for x, y, face in marker_faces(ax) if face == "#ffffff"], [(0.1, 3e-2), (0.025, 2e-3)])
        self.assertIn("open marker: value < 0", legend_labels(ax.get_legend()))

    def test_signed_metric_panel_and_figure_legend(self):
        from sph_study.plots import figure_all_errors_vs_h
        fig = figure_all_errors_vs_h(self.plt, GROUPS, ["l1_velocity", "amplitude_rel"], "t")
        self.assertEqual([ax.get_title() for ax in fig.axes[:2]], ["l1_velocity", "|amplitude_rel|"])
        self.assertIn("open marker: value < 0", legend_labels(fig.legends[0]))

    def test_positive_metric_keeps_its_name_and_markers(self):
        from sph_study.plots import figure_error_vs_h
        ax = figure_error_vs_h(self.plt, GROUPS, "l1_velocity", "t").axes[0]
        self.assertEqual(ax.get_ylabel(), "l1_velocity")
        self.assertEqual(marker_faces(ax), [])
        self.assertNotIn("open marker: value < 0", legend_labels(ax.get_legend()))

    def test_wall_time_under_1_s_greyed_not_dropped(self):
        from sph_study.plots import figure_pareto
        ax = figure_pareto(self.plt, GROUPS, "l1_velocity", "t").axes[0]
        wcsph = [l for l in ax.get_lines() if l.get_label() == "wcsph"][0]
        self.assertEqual(list(wcsph.get_xdata()), [0.5, 3.0])
        self.assertEqual(marker_faces(ax), [(0.5, 5e-2, "#999999")])
        self.assertIn("grey: wall time < 1 s: noise", legend_labels(ax.get_legend()))

    def test_no_noise_entry_without_short_runs(self):
        from sph_study.plots import figure_pareto
        ax = figure_pareto(self.plt, {"isph": GROUPS["isph"]}, "l1_velocity", "t").axes[0]
        self.assertNotIn("grey: wall time < 1 s: noise", legend_labels(ax.get_legend()))

    def test_ksp_iterations_labelled_per_time_step(self):
        from sph_study.plots import figure_ksp
        ax = figure_ksp(self.plt, GROUPS, "t").axes[0]
        self.assertEqual(ax.get_ylabel(), "KSP iterations per time step\n(sum over the step's pressure solves)")
        self.assertEqual(legend_labels(ax.get_legend()), ["isph (mean over steps)", "isph (max over steps)"])

    def test_nothing_to_draw(self):
        from sph_study.plots import figure_error_vs_h, figure_ksp, figure_pareto
        self.assertIsNone(figure_error_vs_h(self.plt, GROUPS, "nothing", "t"))
        self.assertIsNone(figure_pareto(self.plt, GROUPS, "nothing", "t"))
        self.assertIsNone(figure_ksp(self.plt, {"wcsph": GROUPS["wcsph"]}, "t"))


if __name__ == "__main__":
    unittest.main()
