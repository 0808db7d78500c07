#pragma once
// The pieces every VTK output shares: frame names, atomic writes (a temporary file renamed over the
// target, so an interrupted run never leaves a truncated file) and a ParaView .pvd time series that a
// restart takes over. Used by the particle frames and the bodies' surfaces.
#include <string>
#include <utility>
#include <vector>

#include "src/core/error.hpp"

class vtkXMLPolyDataWriter;

namespace sph {

// "<base>_NNNNN" (a frame's stem, shared by the .vtp, the pieces and the .pvtp).
std::string frame_stem(const std::string& base, int frame);
// Escapes a string for use inside a double-quoted XML attribute.
std::string xml_attr(const std::string& s);
// The one-line failure of a write to `path`, from the system's reason `err` (an errno value).
Error write_failure(const std::string& path, int err);
// Writes `text` to `path` through a temporary file renamed over it.
void write_atomically(const std::string& path, const std::string& text);
// Writes `writer`'s input to `path` through a temporary file, as write_atomically: a failed write (a
// full disk) leaves no truncated frame behind, and VTK's own multi-line reports stay off the terminal.
void write_frame(vtkXMLPolyDataWriter* writer, const std::string& path);

// The frames of one series <dir>/<base>.pvd: time and file name (relative to dir) of each frame.
class FrameSeries {
 public:
  FrameSeries(std::string dir, std::string base) : dir_(std::move(dir)), base_(std::move(base)) {}
  int size() const { return static_cast<int>(frames_.size()); }
  std::string pvd_path() const { return dir_ + "/" + base_ + ".pvd"; }
  // Lists a frame and rewrites the .pvd (on rank 0).
  void add(double time, const std::string& file);
  // For a restart: takes over the frames of an existing .pvd up to time t (later ones are dropped).
  void resume(double t);

 private:
  void write_pvd() const;
  std::string dir_, base_;
  std::vector<std::pair<double, std::string>> frames_;
};

}  // namespace sph
