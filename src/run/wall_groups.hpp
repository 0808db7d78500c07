#pragma once
// The groups of wall particles whose force timeseries.csv reports each step: every named body of the
// case, and "walls", the wall particles in no body (src/sph/wall_forces.hpp gives the forces).
// Membership is by the particles' permanent id, so it survives migration, reordering and restarts.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "src/neighbours/neighbourhood.hpp"
#include "src/run/case.hpp"
#include "src/sph/surface_force.hpp"
#include "src/sph/surface_shear.hpp"
#include "src/sph/wall_forces.hpp"

namespace sph {

template <int D> class WallGroups {
 public:
  // The case's bodies (labels by id, the order create() made the particles in) and the wall particles
  // left over. No groups without wall particles.
  // surface_pressure: a body with a closed surface (a YAML scene's) takes its pressure force from the
  // pressure fitted on that surface (src/sph/surface_force.hpp) rather than from the pairs.
  // about: the points the moments are taken about, from the checkpoint a restart resumes (empty: the
  // groups' centroids now, as laid out).
  WallGroups(const Case<D>& run_case, const Particles<D>& P, bool surface_pressure, const nlohmann::json& about)
      : label_(run_case.body_of_particles()) {
    const std::vector<std::string> names = run_case.body_names();
    std::vector<double> count(names.size() + 1, 0.0), volume(names.size() + 1, 0.0);
    std::vector<Vector<D>> sum(names.size() + 1, Vector<D>::Zero());
    // The volume at the reference density: a wall particle's density may vary (WCSPH), and a restart
    // must find the volume its run started with.
    const double rho0 = run_case.physics().rho0;
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] != kWall) continue;
      const std::size_t k = static_cast<std::size_t>(body_of(P.id[i]) + 1);  // 0: walls
      count[k] += 1.0, sum[k] += P.x[i], volume[k] += P.m[i] / rho0;
    }
    MPI_Allreduce(MPI_IN_PLACE, count.data(), static_cast<int>(count.size()), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, volume.data(), static_cast<int>(volume.size()), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    volume_.assign(volume.begin() + 1, volume.end());
    motions_ = run_case.body_motions();
    for (const FreeBody<D>& f : run_case.free_bodies()) free_.push_back(f.active);
    for (Vector<D>& s : sum) MPI_Allreduce(MPI_IN_PLACE, s.data(), D, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    // Body b is group b; the leftover walls come last, and only when there are any.
    for (std::size_t b = 0; b < names.size(); ++b) add(names[b], count[b + 1], sum[b + 1]);
    walls_group_ = count[0] > 0 ? static_cast<int>(names_.size()) : -1;
    if (count[0] > 0) add("walls", count[0], sum[0]);
    // A restart's bodies have moved since the layout: their points come from the checkpoint.
    if (about.is_array() && about.size() == about_.size())
      for (std::size_t g = 0; g < about_.size(); ++g)
        for (int a = 0; a < D; ++a) about_[g][a] = about[g].at(static_cast<std::size_t>(a)).get<double>();
    const std::vector<SurfaceMesh> meshes = run_case.body_surfaces();
    faces_.resize(names.size());
    face_pressure_.resize(names.size());
    if (surface_pressure)
      for (std::size_t b = 0; b < names.size() && b < meshes.size(); ++b)
        if (meshes[b].closed && count[b + 1] > 0) faces_[b] = faces_of(meshes[b]);
  }

  bool empty() const { return names_.empty(); }
  // Body b's faces' pressures from the last forces() (in its surface's cell order); empty where the
  // body's pressure force comes from the pair sums.
  const std::vector<double>& face_pressure(std::size_t b) const { return face_pressure_[b]; }

  // Body b's faces' viscous traction for the current state (in its surface's cell order; empty where
  // its pressure force comes from the pair sums): the viscous pair forces of its particles spread onto
  // its faces, with the rotation's part (src/sph/surface_shear.hpp). For the surface files, so taken
  // when a frame is written, not every step. Refreshes the ghosts as forces() does.
  std::vector<Vector<D>> face_shear(std::size_t b, Particles<D>& P, Neighbourhood<D>& nh, const Kernel<D>& K,
                                    const Physics<D>& physics, const MovingBodies<D>& bodies,
                                    const WallModel<D>* walls) const {
    if (b >= faces_.size() || faces_[b].centre.empty()) return {};
    nh.update(P);
    std::vector<int> group(P.n_owned, -1);
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (P.kind[i] == kWall && body_of(P.id[i]) == static_cast<int>(b)) group[i] = 0;
    std::vector<WallParticleShear<D>> forces;
    wall_group_forces(P, nh.list(), K, P.p, P.rho, group, physics.nu, {about_now(bodies)[b]}, walls, &forces);
    const Faces now = moved(b, bodies);
    std::vector<Vector<D>> shear = spread_shear(forces, K, now.centre, now.area_normal);
    if (b < motions_.size()) add_rotation_shear(shear, now.area_normal, rotation(b, bodies), physics.rho0 * physics.nu);
    return shear;
  }

  // force_<g>_x (total), force_<g>_pressure_x, force_<g>_viscous_x (and _y, _z), moment_<g> (2D;
  // moment_<g>_x, _y, _z in 3D), for every group.
  std::vector<std::string> columns() const {
    std::vector<std::string> c;
    for (const std::string& g : names_) {
      for (const char* part : {"", "_pressure", "_viscous"})
        for (int a = 0; a < D; ++a) c.push_back("force_" + g + part + "_" + "xyz"[a]);
      if (D == 2) c.push_back("moment_" + g);
      else
        for (int a = 0; a < 3; ++a) c.push_back("moment_" + g + "_" + "xyz"[a]);
    }
    return c;
  }

  // Each group's force and moment for the current state; the moment about the group's centroid as
  // laid out, a free body's about its centre of mass now. Refreshes the ghosts' positions and
  // velocities as the step left the owned ones (as the solvers do before their own pair loops); the
  // pressure's and density's ghosts are fresh (docs/developer.md, "Ghosts").
  std::vector<GroupForce<D>> forces(Particles<D>& P, Neighbourhood<D>& nh, const Kernel<D>& K,
                                    const Physics<D>& physics, const MovingBodies<D>& bodies,
                                    const WallModel<D>* walls) {
    nh.update(P);
    std::vector<int> group(P.n_owned, -1);
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (P.kind[i] == kWall) group[i] = body_of(P.id[i]) >= 0 ? body_of(P.id[i]) : walls_group_;
    const std::vector<Vector<D>> about = about_now(bodies);
    std::vector<GroupForce<D>> F = wall_group_forces(P, nh.list(), K, P.p, P.rho, group, physics.nu, about, walls);
    for (std::size_t b = 0; b < faces_.size() && b < F.size(); ++b) {
      if (faces_[b].centre.empty()) continue;
      const Faces now = moved(b, bodies);
      const SurfaceForce<D> S = surface_pressure_force(P, K, now.centre, now.area_normal, P.p, about[b],
                                                       nh.domain().screens.get(), physics.free_surface);
      F[b].moment += S.moment - F[b].pressure_moment;
      F[b].pressure = S.force, F[b].pressure_moment = S.moment;
      face_pressure_[b] = S.face_pressure;
    }
    // The pair sums carry the traction of the viscous term's Laplacian form, mu du/dn; the stress's
    // other part, mu (grad u)^T n, integrates over a body turning at w to a torque -2 mu V w (in 2D
    // and 3D), and to no force (docs/verification/body_forces.md, the Couette torque).
    for (std::size_t b = 0; b < motions_.size() && b < F.size(); ++b)
      F[b].moment -= 2.0 * physics.rho0 * physics.nu * volume_[b] * rotation(b, bodies);
    return F;
  }

  // The columns' values for the groups' forces.
  std::vector<double> row(const std::vector<GroupForce<D>>& F) const {
    std::vector<double> r;
    for (const GroupForce<D>& f : F) {
      for (const Vector<D>& v : {f.total(), f.pressure, f.viscous}) r.insert(r.end(), v.data(), v.data() + D);
      if (D == 2) r.push_back(f.moment[2]);
      else r.insert(r.end(), f.moment.data(), f.moment.data() + 3);
    }
    return r;
  }

  // For the checkpoint: the points the moments are taken about.
  nlohmann::json about() const {
    nlohmann::json j = nlohmann::json::array();
    for (const Vector<D>& a : about_) j.push_back(std::vector<double>(a.data(), a.data() + D));
    return j;
  }

  // For summary.json: each group's wall particles and the point its moment is taken about.
  nlohmann::json describe() const {
    nlohmann::json j = nlohmann::json::object();
    for (std::size_t g = 0; g < names_.size(); ++g) {
      const bool surface = g < faces_.size() && !faces_[g].centre.empty();
      j[names_[g]] = {{"particles", particles_[g]},
                      {"moment_about", std::vector<double>(about_[g].data(), about_[g].data() + D)},
                      {"pressure_force", surface ? "surface" : "pairs"}};
      if (g < free_.size() && free_[g]) j[names_[g]]["moment_about"] = "centre of mass";
      if (surface) j[names_[g]]["surface_faces"] = faces_[g].centre.size();
    }
    return j;
  }

 private:
  int body_of(GlobalIndex id) const {
    return id >= 0 && static_cast<std::size_t>(id) < label_.size() ? label_[static_cast<std::size_t>(id)] : -1;
  }
  // The moment is taken about the group's centroid as laid out (a body's centre when its particles lie
  // symmetrically about it).
  void add(const std::string& name, double count, const Vector<D>& sum) {
    names_.push_back(name);
    particles_.push_back(static_cast<long>(count));
    about_.push_back(count > 0 ? Vector<D>(sum / count) : Vector<D>::Zero());
  }

  // Body b's angular velocity now (b < motions_.size()).
  Eigen::Vector3d rotation(std::size_t b, const MovingBodies<D>& bodies) const {
    const FreeBody<D>* free = bodies.free_body(b);
    return free ? free->omega : Eigen::Vector3d(motions_[b].angular_velocity(bodies.time()) * motions_[b].axis);
  }

  // A body's surface faces as laid out: centres and area normals (outwards).
  struct Faces {
    std::vector<Vector<D>> centre, area_normal;
  };
  static Faces faces_of(const SurfaceMesh& mesh) {
    Faces f;
    for (const std::vector<long>& cell : mesh.cells) {
      const Eigen::Vector3d c = face_centre(mesh, cell), n = face_area_normal(mesh, cell);
      f.centre.push_back(c.head<D>()), f.area_normal.push_back(n.head<D>());
    }
    return f;
  }
  // Body b's faces now: a rigid motion moves each centre and turns each normal with it.
  Faces moved(std::size_t b, const MovingBodies<D>& bodies) const {
    const FreeBody<D>* free = bodies.free_body(b);
    const bool prescribed = b < motions_.size() && motions_[b].moves();
    if (!free && !prescribed) return faces_[b];
    auto place = [&](const Vector<D>& x) { return free ? free->placed(x) : motions_[b].moved(x, 0.0, bodies.time()); };
    Faces f = faces_[b];
    for (std::size_t q = 0; q < f.centre.size(); ++q) {
      const Vector<D> c = place(faces_[b].centre[q]);
      f.area_normal[q] = place(Vector<D>(faces_[b].centre[q] + faces_[b].area_normal[q])) - c;
      f.centre[q] = c;
    }
    return f;
  }
  std::vector<Vector<D>> about_now(const MovingBodies<D>& bodies) const {
    std::vector<Vector<D>> about = about_;
    for (std::size_t b = 0; b < about.size(); ++b)
      if (const FreeBody<D>* free = bodies.free_body(b)) about[b] = free->centre;
    return about;
  }

  std::vector<int> label_;                          // by id: the body's index, -1 for none
  std::vector<Faces> faces_;                        // per body: empty where its pressure force comes from the pairs
  std::vector<std::vector<double>> face_pressure_;  // per body, per face, from the last forces()
  std::vector<double> volume_;                      // per body, as laid out
  std::vector<PrescribedMotion<D>> motions_;
  std::vector<char> free_;  // per body: 1 for a free body
  std::vector<std::string> names_;
  std::vector<long> particles_;
  std::vector<Vector<D>> about_;
  int walls_group_ = -1;
};

}  // namespace sph
