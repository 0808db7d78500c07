#pragma once
// One output directory holds one run, never a mix of two: a directory that already holds a run's
// results (summary.json, particles.pvd, frames, timeseries.csv, checkpoint.bin) is refused unless the
// user says -overwrite, which removes those results first (frames and MPI pieces, *.csv tables,
// summary, checkpoint, temporary files; other files stay). A restart continues the run in the
// directory that holds its checkpoint.
#include <string>

namespace sph {

// Collective on PETSC_COMM_WORLD. Creates `dir` if needed. Throws sph::Error naming the directory
// and the fix when it holds a run and neither `overwrite` nor `continuing` is set.
void prepare_output_dir(const std::string& dir, bool overwrite, bool continuing);

// Removes the frames numbered `first` and up (.vtp, .pvtp, pieces): after a restart they belong to
// the abandoned part of the earlier run. Collective.
void remove_frames_from(const std::string& dir, const std::string& basename, int first);

// Whether `checkpoint` lies in `dir` (a restart that continues in place).
bool is_in_directory(const std::string& checkpoint, const std::string& dir);

}  // namespace sph
