#pragma once
// Particle frames as VTK XML PolyData (.vtp, one per output) plus a ParaView .pvd time-series index,
// rewritten atomically (temporary file + rename) after each frame, so an interrupted run always
// leaves a valid series. Only owned particles are written; ghosts never appear in the output.
//
// One rank:      <dir>/<basename>_NNNNN.vtp and <dir>/<basename>.pvd (which lists the .vtp files).
// Several ranks: every rank writes its piece <dir>/<basename>_NNNNN_rRRRR.vtp, rank 0 writes the
//                master <dir>/<basename>_NNNNN.pvtp that joins them, and the .pvd lists the .pvtp files.
// NNNNN is the output counter (00000, 00001, ...), RRRR the rank.
//
// Point arrays: velocity (3 components, zero-padded below 3D), pressure, density, mass (Float64),
// kind (Int32, ParticleKind), id (Int64, global index), then each extra ScalarField (Float64).
// Field data: TIME (one Float64), which ParaView shows as the frame's time.
// Not collective: a failure throws sph::Error on the rank that hit it.
#include <string>
#include <utility>
#include <vector>

#include "src/io/vtk_files.hpp"
#include "src/particles/particles.hpp"

namespace sph {

template <int D> class ParticleWriter {
 public:
  // Creates output_dir (and its parents); throws sph::Error naming it if that fails.
  explicit ParticleWriter(const std::string& output_dir, const std::string& basename = "particles");

  // Writes frame number frames_written() at time `time` and rewrites the .pvd. Returns the path of
  // the file the .pvd lists for this frame: the .vtp on one rank, the .pvtp master on several.
  std::string write(const Particles<D>& P, double time, const std::vector<ScalarField>& extra = {});

  // For a restart: takes over the frames of an existing .pvd up to time t (later ones are dropped),
  // so numbering and the time series continue.
  void resume(double t);

  int frames_written() const { return series_.size(); }
  std::string pvd_path() const { return series_.pvd_path(); }

 private:
  std::string dir_, base_;
  int rank_ = 0, size_ = 1;
  FrameSeries series_;
};

}  // namespace sph
