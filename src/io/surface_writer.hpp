#pragma once
// A body's surface beside the particle frames, for ParaView: <dir>/body_<name>_NNNNN.vtp (lines in 2D,
// triangles in 3D) and the series <dir>/body_<name>.pvd, one frame with each particle frame, the
// surface placed where the body is. Written by rank 0 (every rank holds the whole surface).
#include <array>
#include <string>
#include <vector>

#include "src/io/vtk_files.hpp"

namespace sph {

struct SurfaceMesh {
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<long>> cells;  // point indices: segments (2D) or polygons (3D)
  bool lines = false;                    // the cells are line segments
};

class SurfaceWriter {
 public:
  SurfaceWriter(const std::string& output_dir, const std::string& body);
  void write(const SurfaceMesh& surface, double time);
  void resume(double t) { series_.resume(t); }
  int frames_written() const { return series_.size(); }
  std::string basename() const { return base_; }

 private:
  std::string dir_, base_;
  FrameSeries series_;
};

}  // namespace sph
