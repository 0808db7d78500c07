#include "src/io/output_dir.hpp"

#include <fcntl.h>
#include <petscsys.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <system_error>
#include <vector>

#include "src/core/collective.hpp"

namespace fs = std::filesystem;

namespace sph {

namespace {

bool is_result(const std::string& name) {
  static const std::regex result(
      "summary\\.json|particles\\.pvd|timeseries\\.csv|checkpoint\\.bin|particles_[0-9]+(_r[0-9]+)?\\.(vtp|pvtp)|"
      "body_[A-Za-z0-9_]+\\.pvd|body_[A-Za-z0-9_]+_[0-9]+\\.vtp");
  return std::regex_match(name, result);
}

constexpr const char* kManifest = ".sph_manifest";

std::vector<fs::path> entries(const std::string& dir, bool (*keep)(const std::string&)) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (keep(it->path().filename().string())) out.push_back(it->path());
  return out;
}

// The files this process has noted, so each is appended to its folder's manifest once.
std::set<std::string>& noted() {
  static std::set<std::string> files;
  return files;
}

std::string folder_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

// The names the manifest of `dir` lists (plain names in `dir`: a line naming another folder is no
// output of a run there and is skipped), and whether there is a manifest at all.
std::vector<std::string> manifest_names(const std::string& dir, bool* exists) {
  std::ifstream in((fs::path(dir) / kManifest).string());
  *exists = static_cast<bool>(in);
  std::vector<std::string> names;
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line != "." && line != ".." && line.find('/') == std::string::npos) names.push_back(line);
  return names;
}

// -overwrite: removes each listed file and its temporary twin, then the manifest; "" or the failure.
std::string remove_listed(const std::string& dir, const std::vector<std::string>& names) {
  std::error_code ec;
  for (const std::string& name : names)
    for (const fs::path& p : {fs::path(dir) / name, fs::path(dir) / (name + ".tmp")})
      if (!fs::remove(p, ec) && ec) return "cannot remove " + p.string() + " for -overwrite (" + ec.message() + ")";
  fs::remove(fs::path(dir) / kManifest, ec);
  // This process may write the same names again: they go into the new manifest.
  const std::string prefix = (fs::path(dir) / "").string();
  for (auto it = noted().begin(); it != noted().end();)
    it = it->compare(0, prefix.size(), prefix) == 0 ? noted().erase(it) : std::next(it);
  return "";
}

PetscMPIInt rank() {
  PetscMPIInt r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

// Takes the directory's lock without waiting; on failure returns -1 and says why in `error`.
int lock_directory(const std::string& dir, std::string* error) {
  std::error_code ec;
  // Said here: left to the lock file's open, a read-only file system read as "No such file".
  if (!fs::create_directories(dir, ec) && ec) {
    *error = "cannot create the output directory " + dir + " (" + ec.message() + "); choose a writable -output_dir";
    return -1;
  }
  const std::string path = (fs::path(dir) / ".sph.lock").string();
  const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    *error = "cannot create " + path + " (" + std::strerror(errno) + "); check that -output_dir is writable";
    return -1;
  }
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int why = errno;
    char holder[64] = "";
    const ssize_t n = pread(fd, holder, sizeof holder - 1, 0);
    holder[n > 0 ? n : 0] = '\0';
    holder[std::strcspn(holder, "\n")] = '\0';
    close(fd);
    *error = why == EWOULDBLOCK ? "output directory " + dir + " is in use by another run (" +
                                      (holder[0] ? std::string(holder) : std::string("process id not yet written")) +
                                      "); wait for it to end or choose another -output_dir"
                                : "cannot lock " + path + " (" + std::strerror(why) + ")";
    return -1;
  }
  char host[256] = "";
  gethostname(host, sizeof host - 1);
  const std::string holder = "pid " + std::to_string(getpid()) + (host[0] ? std::string(" on ") + host : "") + "\n";
  if (ftruncate(fd, 0) != 0 || pwrite(fd, holder.data(), holder.size(), 0) < 0) {
    // The lock holds all the same; only the refusal of a second run names no process.
  }
  return fd;
}

}  // namespace

OutputDirLock::~OutputDirLock() {
  if (fd_ >= 0) close(fd_);  // releases the flock
}

OutputDirLock prepare_output_dir(const std::string& dir, bool overwrite, bool continuing) {
  std::string error;
  int fd = -1;
  if (rank() == 0) fd = lock_directory(dir, &error);
  OutputDirLock lock(fd);
  throw_if_root_failed(error);
  if (rank() == 0 && !continuing) {
    const std::vector<fs::path> found = entries(dir, is_result);
    if (!found.empty() && !overwrite) {
      error = "output directory " + dir + " already holds a run (" + found.front().filename().string() +
              "); pass -overwrite to replace it, -restart to continue it, or choose another -output_dir";
    } else if (!found.empty()) {
      bool listed = false;
      const std::vector<std::string> names = manifest_names(dir, &listed);
      error = listed ? remove_listed(dir, names)
                     : "output directory " + dir + " holds results (" + found.front().filename().string() +
                           ") that no manifest of a run lists (" + kManifest +
                           ", written by sph since it keeps one); -overwrite removes only the files a run "
                           "lists there: remove the old results yourself or choose another -output_dir";
    }
  }
  throw_if_root_failed(error);
  return lock;
}

void note_output(const std::string& path) {
  const std::string dir = folder_of(path);
  const std::string name = fs::path(path).filename().string();
  if (!noted().insert((fs::path(dir) / name).string()).second) return;
  // One short line in append mode: the ranks' lines do not mix. A manifest that cannot be written
  // costs only -overwrite's cleaning; the output's own write reports an unwritable folder.
  const int fd = open((fs::path(dir) / kManifest).c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return;
  const std::string line = name + "\n";
  [[maybe_unused]] const ssize_t written = write(fd, line.data(), line.size());
  close(fd);
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
  const fs::path a = fs::weakly_canonical(
      fs::path(checkpoint).parent_path().empty() ? fs::path(".") : fs::path(checkpoint).parent_path(), ec1);
  const fs::path b = fs::weakly_canonical(dir.empty() ? fs::path(".") : fs::path(dir), ec2);
  return !ec1 && !ec2 && a == b;
}

}  // namespace sph
