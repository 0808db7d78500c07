// Pressure probes (src/run/probes.hpp): the Shepard mean against fields it must read exactly (a linear
// field at points the lattice is symmetric about, walls holding the field continued), a dry probe,
// periodic images; and in still water against the hydrostatic rho g depth, both schemes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "src/run/probes.hpp"
#include "tests/run_sph.hpp"

namespace {

using sph::testing::run_sph;
using sph::testing::timeseries_column;

// A lattice of particles at (i + 1/2) dx in [0, 1]^2, those with y < 0.3 of the given kind below a
// fluid above, each with the pressure p(x).
template <class F> sph::Particles<2> lattice(double dx, int lower_kind, F p) {
  sph::Particles<2> P;
  const int n = static_cast<int>(std::lround(1.0 / dx));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const sph::Vector<2> x((i + 0.5) * dx, (j + 0.5) * dx);
      P.add(x, sph::Vector<2>::Zero(), dx * dx, 1.0, p(x), x[1] < 0.3 ? lower_kind : sph::kFluid);
    }
  return P;
}

double read(const sph::Particles<2>& P, const sph::Domain<2>& domain, const sph::Vector<2>& at) {
  const sph::Kernel<2> K(sph::KernelType::QuinticSpline, 0.05);
  return sph::probe_pressures(P, domain, K, {{"p", at}})[0];
}

TEST(Probes, ReadALinearFieldExactlyWhereTheLatticeIsSymmetric) {
  auto linear = [](const sph::Vector<2>& x) { return 2.0 + 3.0 * x[0] - 5.0 * x[1]; };
  const sph::Domain<2> box;
  // In the fluid, at a particle and between four.
  const sph::Particles<2> fluid = lattice(0.025, sph::kFluid, linear);
  for (const sph::Vector<2>& at : {sph::Vector<2>(0.5125, 0.6125), sph::Vector<2>(0.5, 0.6)})
    EXPECT_NEAR(read(fluid, box, at), linear(at), 1e-12);
  // On the face between walls that hold the field continued and the fluid above: as a flush transducer.
  const sph::Particles<2> walls = lattice(0.025, sph::kWall, linear);
  EXPECT_NEAR(read(walls, box, sph::Vector<2>(0.5, 0.3)), linear(sph::Vector<2>(0.5, 0.3)), 1e-12);
  // The walls' pressure counts: with theirs at zero the face reads less.
  sph::Particles<2> dry_walls = walls;
  for (std::size_t i = 0; i < dry_walls.n_owned; ++i)
    if (dry_walls.kind[i] == sph::kWall) dry_walls.p[i] = 0.0;
  EXPECT_LT(read(dry_walls, box, sph::Vector<2>(0.5, 0.3)), 0.75 * linear(sph::Vector<2>(0.5, 0.3)));
}

TEST(Probes, ReadZeroWhereNoParticleReaches) {
  const sph::Particles<2> P = lattice(0.025, sph::kFluid, [](const sph::Vector<2>&) { return 7.0; });
  sph::Domain<2> box;
  box.hi = sph::Vector<2>(2.0, 2.0);
  EXPECT_EQ(read(P, box, sph::Vector<2>(1.5, 1.5)), 0.0);
}

// p = sin(2 pi x) is odd about x = 0: a probe there reads 0 only with the images across the periodic
// side (without them it sees one side only).
TEST(Probes, SeeAcrossAPeriodicSide) {
  const sph::Particles<2> P =
      lattice(0.025, sph::kFluid, [](const sph::Vector<2>& x) { return std::sin(2 * M_PI * x[0]); });
  sph::Domain<2> periodic;
  periodic.periodic = {true, false};
  EXPECT_NEAR(read(P, periodic, sph::Vector<2>(0.0, 0.5)), 0.0, 1e-12);
  EXPECT_GT(read(P, sph::Domain<2>(), sph::Vector<2>(0.0, 0.5)), 0.05);
}

// Still water 0.5 deep in a tank: probes on the far wall's face and in the water read rho g depth,
// each scheme's mean over the run within 1 % (measured: 0.1 % and 0.2 %).
TEST(Probes, ReadTheHydrostaticPressureInStillWater) {
  const std::string dir = std::string(SPH_BINARY_DIR) + "/test-output";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/probes_still_water.yaml";
  std::ofstream(path)
      << "dimension: 2\nbox: [-0.2, 1.2, -0.2, 1.0]\ngravity: [0, -9.81]\nnu: 1.0e-3\nrho0: 1000\n"
         "free_surface: true\nt_end: 0.5\nregions:\n"
         "  - {role: wall, shape: difference, of: [{box: [-0.2, 1.2, -0.2, 1.0]}, {box: [0, 1, 0, 1.1]}]}\n"
         "  - {role: fluid, shape: box, bounds: [0, 1, 0, 0.5], pressure: hydrostatic}\n"
         "probes:\n  - {name: wall, at: [1, 0.25]}\n  - {name: inside, at: [0.5, 0.1]}\n";
  for (const char* solver : {"isph", "wcsph"}) {
    const auto r = run_sph(std::string("probes_") + solver, "-case scene -scene_file " + path +
                                                                " -nx 20 -output_interval 0 -checkpoint_interval 0 "
                                                                "-threads 1 -solver " +
                                                                solver);
    ASSERT_EQ(r.exit_code, 0) << solver;
    for (const auto& [name, depth] : {std::pair<const char*, double>{"wall", 0.25}, {"inside", 0.4}}) {
      const std::vector<double> p = timeseries_column(r, std::string("probe_") + name + "_p");
      ASSERT_FALSE(p.empty()) << solver << " " << name;
      double mean = 0.0;
      for (double v : p) mean += v / p.size();
      EXPECT_NEAR(mean / (1000 * 9.81 * depth), 1.0, 0.01) << solver << " " << name;
    }
  }
}

}  // namespace
