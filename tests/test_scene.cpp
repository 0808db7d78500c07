// End-to-end: scenes read from files (-case scene) written by scripts/make-scene. The dam break from a
// file is the built-in dam break, to round-off; the periodic array of cylinders gives the Stokes drag
// of Sangani & Acrivos (1982).
#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "run_sph.hpp"

namespace {

using sph::testing::run_sph;

// Writes a scene with scripts/make-scene into the test output folder; returns its path.
std::string make_scene(const std::string& file, const std::string& args) {
  const std::string dir = std::string(SPH_BINARY_DIR) + "/test-output";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + file;
  const std::string cmd = std::string(SPH_SOURCE_DIR) + "/scripts/make-scene " + args + " -o " + path + " > /dev/null";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return path;
}

// Fluid positions by particle id in a run's last frame (one rank: particles_00001.vtp with
// -output_interval 0).
std::map<long, std::array<double, 3>> last_fluid_positions(const std::string& run_dir) {
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((run_dir + "/particles_00001.vtp").c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  vtkDataArray* id = poly->GetPointData()->GetArray("id");
  vtkDataArray* kind = poly->GetPointData()->GetArray("kind");
  std::map<long, std::array<double, 3>> x;
  for (vtkIdType i = 0; id && kind && i < poly->GetNumberOfPoints(); ++i)
    if (kind->GetComponent(i, 0) == 0) poly->GetPoint(i, x[static_cast<long>(id->GetComponent(i, 0))].data());
  return x;
}

// make-scene's dam break without the obstacle is -case dam_break's scene particle for particle (order,
// positions, hydrostatic pressure, box, physics): the runs must agree to round-off, the surge front
// Z = (max fluid x + dx/2) / a as the case measures it, and every fluid particle.
void expect_same_dam_break(const std::string& solver) {
  const std::string file = make_scene("dam_break_16.vtp", "dam_break --nx 16 --no-obstacle");
  const std::string common = " -solver " + solver + " -t_end 0.7 -output_interval 0 -threads 1";
  const auto builtin = run_sph("dam_break_builtin_" + solver, "-case dam_break -nx 16" + common);
  const auto scene = run_sph("dam_break_scene_" + solver, "-case scene -scene_file " + file + common);
  ASSERT_EQ(builtin.exit_code, 0);
  ASSERT_EQ(scene.exit_code, 0);
  EXPECT_EQ(builtin.summary["steps"], scene.summary["steps"]);
  const auto a = last_fluid_positions(builtin.output_dir), b = last_fluid_positions(scene.output_dir);
  ASSERT_EQ(a.size(), 512u);  // 16 x 32 fluid particles
  ASSERT_EQ(b.size(), a.size());
  double worst = 0.0, front = -1e300;
  for (const auto& [id, x] : a) {
    ASSERT_TRUE(b.count(id));
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(x[c] - b.at(id)[c]));
    front = std::max(front, b.at(id)[0]);
  }
  const double dx = 1.0 / 16, Z = front + 0.5 * dx;  // a = 1
  const double Z_builtin = builtin.summary["errors"]["front_position"].get<double>();
  EXPECT_GT(Z_builtin, 1.2);  // the column did collapse: the comparison is not of two starts
  EXPECT_NEAR(Z, Z_builtin, 1e-12 * Z_builtin);
  EXPECT_LT(worst, 1e-12);
}

TEST(Scene, DamBreakFileMatchesBuiltinCaseIsph) { expect_same_dam_break("isph"); }
TEST(Scene, DamBreakFileMatchesBuiltinCaseWcsph) { expect_same_dam_break("wcsph"); }

// Stokes flow through a periodic square array of cylinders, the geometry of Morris, Fox & Zhu (1997,
// J. Comput. Phys. 136:214, section 4.3: radius a = 0.2 L, solid fraction c = pi a^2 / L^2 = 0.1257),
// driven by a body force g along x, at Re = U L / nu ~ 0.03. Reference: the dimensionless drag per
// unit length K = F / (mu U) of Sangani & Acrivos (1982, Int. J. Multiphase Flow 8:193), their series
// for the square array, K = 4 pi / (-ln(c)/2 - 0.738 + c - 0.887 c^2 + 2.038 c^3) = 30.30 at this c
// (it gives 24.81 at c = 0.1, their Table 1: 24.83). U is the superficial (cell-averaged) velocity and
// F the drag in the equivalent pressure-driven flow, F = rho g L^2 (the body force acts on the fluid
// only; the pressure-driven flow's mean gradient also acts across the cylinder's area). At steady
// state, K = g L^4 / (nu * sum_fluid(m u) / rho) with L = rho = 1. Measured 29.55 at nx 30 (t = 0.5,
// 2.5% low) and 29.99 at nx 48 (t = 0.3, 1.0% low); 5% is the bound. Taking F = rho g A_fluid
// instead would give 25.9, 15% low at every resolution: the pressure-driven definition matters.
// Dimensionless drag K = F / (mu U) of a steady run of the cylinder scene (F = rho g L^2, L = 1).
double steady_drag(const sph::testing::RunResult& r) {
  const double g = r.summary["physics"]["gravity"][0].get<double>(), nu = r.summary["physics"]["nu"].get<double>();
  // Momentum along x at the end and a tenth of the run earlier: the flow must be steady.
  std::ifstream in(r.output_dir + "/timeseries.csv");
  std::string line;
  std::getline(in, line);
  std::vector<std::pair<double, double>> series;  // (t, momentum_x)
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(row, cell, ',')) v.push_back(std::atof(cell.c_str()));
    series.emplace_back(v[1], v[4]);  // step, t, dt, kinetic_energy, momentum_x
  }
  EXPECT_GT(series.size(), 10u);
  if (series.empty()) return std::nan("");
  const double t_end = series.back().first, mx = series.back().second;
  double earlier = mx;
  for (const auto& [t, m] : series)
    if (t <= 0.9 * t_end) earlier = m;
  EXPECT_LT(std::abs(mx - earlier) / mx, 0.005) << "not steady";
  return g / (nu * mx);
}

// Sangani & Acrivos (1982) square-array series at Morris et al.'s solid fraction.
double sangani_acrivos_drag() {
  const double c = M_PI * 0.2 * 0.2;
  return 4 * M_PI / (-0.5 * std::log(c) - 0.738 + c - 0.887 * c * c + 2.038 * c * c * c);
}

// In the steady flow the cylinder (the scene's only walls) holds the fluid against the body force:
// the force on it, from the pair sums (src/sph/wall_forces.hpp), equals the fluid's mass times g.
// Measured at nx 30: ISPH 0.994, WCSPH 0.996 of it (docs/verification/body_forces.md).
void expect_force_balances_body_force(const sph::testing::RunResult& r) {
  const double g = r.summary["physics"]["gravity"][0].get<double>();
  const double body_force = g * r.summary["conservation"]["fluid_mass"].get<double>();
  const std::vector<double> drag = sph::testing::timeseries_column(r, "force_walls_x");
  ASSERT_FALSE(drag.empty());
  EXPECT_NEAR(drag.back() / body_force, 1.0, 0.01) << "force on the cylinder " << drag.back();
}

TEST(Scene, CylinderArrayDragMatchesSanganiAcrivos) {
  const std::string file = make_scene("cylinders_30.vtp", "cylinders --nx 30");
  const auto r =
      run_sph("cylinders_scene", "-case scene -scene_file " + file + " -t_end 0.5 -output_interval 0 -threads 1");
  ASSERT_EQ(r.exit_code, 0);
  const double reference = sangani_acrivos_drag(), K = steady_drag(r);
  EXPECT_NEAR(reference, 30.30, 0.01);
  EXPECT_NEAR(K, reference, 0.05 * reference) << "K = " << K;
  expect_force_balances_body_force(r);
}

// WCSPH at its default sound speed: at Re ~ 0.03 the pressure scale is the body-force head, not
// rho U^2, and c0 must follow it (Morris et al. 1997). With c0 = 10 U_ref = 1 the fluid was compressed
// and K came out 43% low; c0 from the head, 10 sqrt(g L) = 10, gives 4.9% (measured, nx 30). The bound,
// 10%, separates the two; the ISPH test above holds the 5% of the reference.
TEST(Scene, CylinderArrayDragWcsphDefaultSoundSpeed) {
  const std::string file = make_scene("cylinders_30w.vtp", "cylinders --nx 30");
  const auto r = run_sph("cylinders_scene_wcsph",
                         "-case scene -scene_file " + file + " -solver wcsph -t_end 0.5 -output_interval 0 -threads 1");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.summary["models"]["equation_of_state"]["c0_set_by"], "body-force head sqrt(|g| H)");
  const double reference = sangani_acrivos_drag(), K = steady_drag(r);
  EXPECT_NEAR(K, reference, 0.1 * reference) << "K = " << K;
  expect_force_balances_body_force(r);
}

}  // namespace
