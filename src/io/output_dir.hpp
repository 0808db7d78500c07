#pragma once
// One output directory holds one run, never a mix of two: a directory that already holds a run's
// results (summary.json, particles.pvd, frames, timeseries.csv, checkpoint.bin) is refused unless the
// user says -overwrite, which removes those results first. It removes only the files the runs there
// wrote, as listed in the folder's manifest (.sph_manifest, a name a line, each file noted before it is
// first written): the user's own tables, meshes and backups beside them stay, whatever their names.
// A restart continues the run in the directory that holds its checkpoint.
//
// A run holds an advisory lock (flock) on <dir>/.sph.lock from before that check to its end, so two
// runs started together into one directory cannot both pass the check: the second is refused, naming
// the first one's process. The lock goes with the process, however it ends; the file stays, empty of
// meaning once unlocked.
#include <string>
#include <utility>

namespace sph {

// The lock on an output directory, held by rank 0 while the object lives.
class OutputDirLock {
 public:
  OutputDirLock() = default;
  explicit OutputDirLock(int fd) : fd_(fd) {}
  OutputDirLock(OutputDirLock&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  OutputDirLock& operator=(OutputDirLock&& other) noexcept {
    std::swap(fd_, other.fd_);
    return *this;
  }
  OutputDirLock(const OutputDirLock&) = delete;
  OutputDirLock& operator=(const OutputDirLock&) = delete;
  ~OutputDirLock();

 private:
  int fd_ = -1;
};

// Collective on PETSC_COMM_WORLD. Creates `dir` if needed and locks it for this run. Throws
// sph::Error naming the directory and the fix when another run holds it, or when it holds a run and
// neither `overwrite` nor `continuing` is set.
[[nodiscard]] OutputDirLock prepare_output_dir(const std::string& dir, bool overwrite, bool continuing);

// Notes `path` in the manifest of its folder before the file is first written (once per process;
// every rank may call it). Every writer of a run's outputs calls it: -overwrite removes what it lists.
void note_output(const std::string& path);

// Removes the frames numbered `first` and up (.vtp, .pvtp, pieces): after a restart they belong to
// the abandoned part of the earlier run. Collective.
void remove_frames_from(const std::string& dir, const std::string& basename, int first);

// Whether `checkpoint` lies in `dir` (a restart that continues in place).
bool is_in_directory(const std::string& checkpoint, const std::string& dir);

}  // namespace sph
