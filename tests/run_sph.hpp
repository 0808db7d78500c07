#pragma once
// Runs the sph program as a user would and reads back its summary.json (end-to-end tests).
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace sph::testing {

struct RunResult {
  int exit_code;
  nlohmann::json summary;  // null when no summary was written
  std::string output_dir;
};

// `args` are sph options; output goes to a fresh directory under the build tree named `tag`.
inline RunResult run_sph(const std::string& tag, const std::string& args) {
  const std::string dir = std::string(SPH_BINARY_DIR) + "/test-output/" + tag;
  std::filesystem::remove_all(dir);
  const std::string cmd = std::string(SPH_EXECUTABLE) + " " + args + " -progress 0 -output_dir " + dir +
                          " > " + dir + ".log 2>&1";
  std::filesystem::create_directories(std::string(SPH_BINARY_DIR) + "/test-output");
  const int status = std::system(cmd.c_str());
  RunResult r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, nullptr, dir};
  std::ifstream in(dir + "/summary.json");
  if (in) in >> r.summary;
  return r;
}

}  // namespace sph::testing
