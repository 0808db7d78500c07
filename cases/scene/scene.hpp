#pragma once
// A scene read from a file (-case scene -scene_file FILE): the particles of a VTK XML PolyData file
// (cases/scene/scene_file.hpp), or shapes in a YAML file (.yaml, .yml) sampled at the run's spacing
// (cases/scene/scene_yaml.hpp), with the parameters from its field data, each overridden by its option:
//   -scene_dx (dx)           particle spacing; required from one or the other (mass = rho0 dx^D)
//   -nx                      YAML scenes only: dx = 1/nx (a .vtp scene's particles are fixed)
//   -scene_box (box)         xmin,xmax,ymin,ymax[,zmin,zmax]; default: the particles' bounding box
//                            grown by dx/2 (a box is needed along periodic axes)
//   -scene_periodic (periodic: one 0/1 flag per axis)   periodic axes, "x,y", or "none"
//   -gravity (gravity), -nu (nu, default 0), -rho0 (rho0, default 1), -t_end (t_end, default 1)
//   -U (U)                   reference speed; default: the largest particle speed or the free-fall
//                            speed sqrt(2 |g| H) over the fluid's height H, whichever is larger
//   -free_surface (free_surface)   default: on when some fluid particle lies on a face of the filled
//                            region (neither walls nor fluid nor a periodic image within 2 dx on a side)
// Fixed-wall particles (kind 1) are at rest; moving-wall particles (kind 2) keep their place and their
// velocity enters the walls' no-slip condition, as the lid of the lid-driven cavity: a wall sliding along
// itself. The scene has no reference solution: no error norms.
#include <array>
#include <string>
#include <vector>

#include "cases/scene/scene_file.hpp"
#include "cases/scene/scene_geometry.hpp"
#include "cases/scene/scene_yaml.hpp"
#include "src/run/case.hpp"

namespace sph {

// The options as given; *_set: given on the command line (then they override the file).
struct SceneOptions {
  char path[PETSC_MAX_PATH_LEN] = "", periodic[64] = "";
  PetscInt nx = 0;
  PetscBool nx_set = PETSC_FALSE;
  PetscReal dx = 0, box[6] = {}, gravity[3] = {}, nu = 0, rho0 = 1, U = 0;
  PetscInt box_n = 6, gravity_n = 3;
  PetscBool free_surface = PETSC_FALSE;
  PetscBool dx_set = PETSC_FALSE, box_set = PETSC_FALSE, periodic_set = PETSC_FALSE, gravity_set = PETSC_FALSE,
            nu_set = PETSC_FALSE, rho0_set = PETSC_FALSE, U_set = PETSC_FALSE, free_surface_set = PETSC_FALSE;
};

template <int D> class SceneCase : public Case<D> {
 public:
  std::string name() const override { return "scene"; }
  std::string output_name() const override;
  void set_from_options() override;
  void create(Particles<D>& P, Domain<D>& domain) const override;
  double spacing() const override { return dx_; }
  int resolution() const override;
  Physics<D> physics() const override { return physics_; }
  double default_t_end() const override { return t_end_; }
  double wall_thickness() const override { return walls_; }
  std::string thin_walls(double thickness_dx, double support_dx) const override;
  nlohmann::json parameters() const override;
  std::vector<std::string> body_names() const override { return bodies_; }
  std::vector<int> body_of_particles() const override { return body_; }
  std::vector<char> free_slip_of_particles() const override { return free_slip_; }
  std::vector<signed char> wall_pressure_of_particles() const override { return wall_pressure_; }
  std::vector<PrescribedMotion<D>> body_motions() const override { return motions_; }
  std::vector<FreeBody<D>> free_bodies() const override { return free_; }
  std::vector<SurfaceMesh> body_surfaces() const override { return surfaces_; }
  std::vector<OpenBoundary<D>> open_boundaries() const override;
  std::vector<Probe<D>> probes() const override { return probes_; }

 private:
  void read_file();           // the .vtp file, or the YAML file sampled at -nx, -scene_dx or its dx
  void resolve_parameters();  // file field data, then the options that override it
  void resolve_spacing();
  void resolve_box();
  void resolve_physics();          // rho0, nu, t_end, gravity, free surface
  void resolve_reference_speed();  // U: given, else the fastest particle, body or inlet, or the fall
  const std::vector<double>* field(const char* name, std::size_t want, const std::string& shape) const;
  double scalar(const char* name, PetscBool set, double opt, double fallback) const;
  void check_particles_in_box() const;
  std::vector<FreeBody<D>> free_bodies_of(const std::vector<MotionSpec>& specs, double dx) const;
  void check_moving_walls(const PointGrid<D>& grid, const std::vector<Vector<D>>& x) const;

  SceneFile file_;
  bool yaml_ = false;
  std::vector<int> body_;                     // YAML scenes: per particle, index into bodies_ (-1: none)
  std::vector<char> free_slip_;               // per particle, 1 on free-slip walls (empty: none)
  std::vector<signed char> wall_pressure_;    // per particle, a wall group's own WallPressure (empty: none)
  std::vector<std::string> bodies_;           // YAML scenes: the names of the bodies
  std::vector<PrescribedMotion<D>> motions_;  // YAML scenes: per body
  std::vector<FreeBody<D>> free_;             // YAML scenes: per body, active where the fluid moves it
  std::vector<SurfaceMesh> surfaces_;         // YAML scenes: per body, at t = 0
  std::vector<Probe<D>> probes_;              // YAML scenes: the pressure probes
  std::vector<OpenBoundary<D>> open_;         // YAML scenes: inlets and outlets
  // YAML scenes: the thin plates (src/neighbours/screens.hpp), and per particle the plate face it
  // stands for (0: none; empty without plates).
  std::vector<typename Screens<D>::Plate> plates_;
  std::vector<std::int8_t> plate_face_;
  Domain<D> box_;
  Physics<D> physics_;
  double dx_ = 0.0, t_end_ = 1.0, walls_ = 0.0;
  Vector<D> thinnest_at_ = Vector<D>::Zero();
  SceneOptions opt_;
  bool free_surface_given_ = false, free_surface_detected_ = false;
};

// The dimension of the scene named by -scene_file (2 when none is given: the case then asks for one).
int scene_file_dimension();

}  // namespace sph
