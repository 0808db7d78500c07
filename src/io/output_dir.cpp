#include "src/io/output_dir.hpp"

#include <petscsys.h>

#include <filesystem>
#include <regex>
#include <system_error>
#include <vector>

#include "src/core/collective.hpp"

namespace fs = std::filesystem;

namespace sph {

namespace {

bool is_result(const std::string& name) {
  static const std::regex result(
      "summary\\.json|particles\\.pvd|timeseries\\.csv|checkpoint\\.bin|particles_[0-9]+(_r[0-9]+)?\\.(vtp|pvtp)");
  return std::regex_match(name, result);
}

// What -overwrite removes: the results, every table and temporary file sph writes.
bool is_removable(const std::string& name) {
  static const std::regex other(".*\\.csv|.*\\.tmp|checkpoint\\.bin.*");
  return is_result(name) || std::regex_match(name, other);
}

std::vector<fs::path> entries(const std::string& dir, bool (*keep)(const std::string&)) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (keep(it->path().filename().string())) out.push_back(it->path());
  return out;
}

PetscMPIInt rank() {
  PetscMPIInt r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

}  // namespace

void prepare_output_dir(const std::string& dir, bool overwrite, bool continuing) {
  std::string error;
  if (rank() == 0 && !continuing) {
    const std::vector<fs::path> found = entries(dir, is_result);
    if (!found.empty() && !overwrite) {
      error = "output directory " + dir + " already holds a run (" + found.front().filename().string() +
              "); pass -overwrite to replace it, -restart to continue it, or choose another -output_dir";
    } else if (!found.empty()) {
      std::error_code ec;
      for (const fs::path& p : entries(dir, is_removable))
        if (!fs::remove(p, ec) && ec) {
          error = "cannot remove " + p.string() + " for -overwrite (" + ec.message() + ")";
          break;
        }
    }
  }
  throw_if_root_failed(error);
}

void remove_frames_from(const std::string& dir, const std::string& basename, int first) {
  if (rank() == 0) {
    const std::regex frame(basename + "_([0-9]+)(_r[0-9]+)?\\.(vtp|pvtp)");
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      std::smatch m;
      const std::string name = it->path().filename().string();
      if (std::regex_match(name, m, frame) && std::stoi(m[1].str()) >= first) {
        std::error_code ignored;
        fs::remove(it->path(), ignored);
      }
    }
  }
  MPI_Barrier(PETSC_COMM_WORLD);
}

bool is_in_directory(const std::string& checkpoint, const std::string& dir) {
  std::error_code ec1, ec2;
  const fs::path a = fs::weakly_canonical(fs::path(checkpoint).parent_path().empty() ? fs::path(".")
                                                                                      : fs::path(checkpoint).parent_path(),
                                          ec1);
  const fs::path b = fs::weakly_canonical(dir.empty() ? fs::path(".") : fs::path(dir), ec2);
  return !ec1 && !ec2 && a == b;
}

}  // namespace sph
