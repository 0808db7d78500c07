"""The scene package without the program: lattice counts against the geometry, the hydrostatic start,
the refusals, and a file read back through VTK."""
import os
import tempfile
import unittest

from sph_scene import FLUID, MOVING, WALL, SCENES, cavity, check_lattice, falling_block, still_water


class Counts(unittest.TestCase):
    def test_cavity_2d_counts_follow_the_lattice(self):
        # nx^2 fluid in a ring of wall layers; the lid is the layers above the fluid and above the
        # upstream wall (that corner block moves with it, as in -case lid_driven_cavity).
        nx, layers = 8, 4
        fluid, wall, moving = cavity(nx=nx, wall_layers=layers).counts()
        self.assertEqual(fluid, nx * nx)
        self.assertEqual(wall + moving, (nx + 2 * layers) ** 2 - nx * nx)
        self.assertEqual(moving, (nx + layers) * layers)

    def test_cavity_3d_counts_follow_the_lattice(self):
        nx, layers = 5, 4
        fluid, wall, moving = cavity(nx=nx, dim=3).counts()
        self.assertEqual(fluid, nx ** 3)
        self.assertEqual(fluid + wall + moving, (nx + 2 * layers) ** 3)


class Hydrostatic(unittest.TestCase):
    def test_still_water_starts_at_rho_g_depth(self):
        s = still_water(nx=10)
        g, depth = -s.params["gravity"][1], 0.5
        for x, p, k in zip(s.x, s.p, s.kind):
            if k == FLUID:
                self.assertAlmostEqual(p, s.params["rho0"] * g * (depth - x[1]), places=12)
                self.assertLess(x[1], depth)

    def test_still_water_strip_fits_its_period_with_dx2_per_particle(self):
        for lattice in ("square", "hexagonal"):
            with self.subTest(lattice=lattice):
                nx = 20
                s = still_water(nx=nx, side_walls=False, lattice=lattice)
                self.assertEqual(s.params["periodic"], [1, 0])
                width = s.params["box"][1] - s.params["box"][0]
                fluid = [(x, p) for x, p, k in zip(s.x, s.p, s.kind) if k == FLUID]
                top = max(x[1] for x, _ in fluid)
                # Rows fill the period: no two particles of a row closer across it than along it.
                xs = sorted({round(x[0], 12) for x, _ in fluid if abs(x[1] - fluid[0][0][1]) < 1e-12})
                self.assertAlmostEqual(xs[0] + width - xs[-1], xs[1] - xs[0], places=12)
                # One particle per dx^2 below the level, which is half a row above the top row.
                level = max(p + x[1] for x, p in fluid)
                self.assertAlmostEqual(len(fluid) / (width * level), nx * nx, delta=0.01 * nx * nx)
                self.assertGreater(level, top)
                self.assertAlmostEqual(min(p + x[1] for x, p in fluid), level, places=12)

    def test_every_scene_builds_with_fluid_and_walls(self):
        for name, build in SCENES.items():
            with self.subTest(scene=name):
                fluid, wall, moving = build(nx=8).counts()
                self.assertGreater(fluid, 0)
                self.assertGreater(wall + moving, 0)


class Refusals(unittest.TestCase):
    def test_too_coarse_or_wall_less_is_refused(self):
        self.assertRaises(ValueError, check_lattice, 3)
        self.assertRaises(ValueError, check_lattice, 8, 0)
        self.assertRaises(ValueError, cavity, nx=3)

    def test_unknown_obstacle_shape_is_refused(self):
        self.assertRaises(ValueError, falling_block, nx=8, obstacle_shape="cube")


class RoundTrip(unittest.TestCase):
    def test_written_file_reads_back(self):
        from vtkmodules.util.numpy_support import vtk_to_numpy
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
        s = cavity(nx=8)
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "cavity.vtp")
            s.write(path)
            r = vtkXMLPolyDataReader()
            r.SetFileName(path)
            r.Update()
            out = r.GetOutput()
            self.assertEqual(out.GetNumberOfPoints(), len(s))
            kind = vtk_to_numpy(out.GetPointData().GetArray("kind"))
            self.assertEqual([int((kind == k).sum()) for k in (FLUID, WALL, MOVING)], list(s.counts()))
            self.assertAlmostEqual(out.GetFieldData().GetArray("dx").GetValue(0), s.params["dx"])


if __name__ == "__main__":
    unittest.main()
