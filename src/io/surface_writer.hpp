#pragma once
// A body's surface beside the particle frames, for ParaView: <dir>/body_<name>_NNNNN.vtp (lines in 2D,
// triangles in 3D) and the series <dir>/body_<name>.pvd, one frame with each particle frame, the
// surface placed where the body is. Written by rank 0 (every rank holds the whole surface).
#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

#include "src/io/vtk_files.hpp"

namespace sph {

struct SurfaceMesh {
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<long>> cells;  // point indices: segments (2D) or polygons (3D)
  bool lines = false;                    // the cells are line segments
  // The cells enclose the body, each ordered so that face_area_normal points out of it (a segment
  // a -> b: (b - a) turned clockwise, in the z = 0 plane).
  bool closed = false;
};

// A cell's centre (its points' mean) and its area times its unit normal (a segment's length times
// its normal; a polygon's, by the fan from its first point).
inline Eigen::Vector3d face_centre(const SurfaceMesh& mesh, const std::vector<long>& cell) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const long k : cell) c += Eigen::Vector3d(mesh.points[static_cast<std::size_t>(k)].data());
  return c / static_cast<double>(cell.size());
}
inline Eigen::Vector3d face_area_normal(const SurfaceMesh& mesh, const std::vector<long>& cell) {
  const auto point = [&](std::size_t k) {
    return Eigen::Vector3d(mesh.points[static_cast<std::size_t>(cell[k])].data());
  };
  if (cell.size() == 2) {
    const Eigen::Vector3d d = point(1) - point(0);
    return {d[1], -d[0], 0.0};
  }
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (std::size_t k = 1; k + 1 < cell.size(); ++k) n += 0.5 * (point(k) - point(0)).cross(point(k + 1) - point(0));
  return n;
}

class SurfaceWriter {
 public:
  SurfaceWriter(const std::string& output_dir, const std::string& body);
  // With `pressure` (one value a cell), the cells carry it and the traction -p n it exerts on the body;
  // with `shear` too (the viscous traction, a vector a cell), that as `shear` and the traction is the sum.
  void write(const SurfaceMesh& surface, double time, const std::vector<double>* pressure = nullptr,
             const std::vector<std::array<double, 3>>* shear = nullptr);
  void resume(double t) { series_.resume(t); }
  int frames_written() const { return series_.size(); }
  std::string basename() const { return base_; }

 private:
  std::string dir_, base_;
  FrameSeries series_;
};

}  // namespace sph
