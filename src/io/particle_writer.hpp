#pragma once
// Particle frames as VTK XML PolyData (.vtp, one per output) plus a ParaView .pvd time-series index,
// rewritten atomically after each frame so an interrupted run always leaves a valid series.
// Owned particles only. On several ranks each rank writes a piece and rank 0 a .pvtp that joins them.
#include <string>
#include <utility>
#include <vector>

#include "src/particles/particles.hpp"

namespace sph {

struct ScalarField {
  std::string name;
  const std::vector<double>* values;  // one value per owned particle
};

template <int D> class ParticleWriter {
 public:
  explicit ParticleWriter(const std::string& output_dir, const std::string& basename = "particles");

  // Writes frame number frames_written() at time t; returns the path of the file the .pvd points at.
  std::string write(const Particles<D>& P, double time, const std::vector<ScalarField>& extra = {});
  int frames_written() const { return static_cast<int>(frames_.size()); }

 private:
  void write_pvd() const;

  std::string dir_, base_;
  std::vector<std::pair<double, std::string>> frames_;  // time, file name relative to dir_
};

}  // namespace sph
