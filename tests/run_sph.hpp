#pragma once
// Runs the sph program as a user would and reads back its summary.json (end-to-end tests).
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "src/io/checkpoint.hpp"

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
  const std::string cmd =
      std::string(SPH_EXECUTABLE) + " " + args + " -progress 0 -output_dir " + dir + " > " + dir + ".log 2>&1";
  std::filesystem::create_directories(std::string(SPH_BINARY_DIR) + "/test-output");
  const int status = std::system(cmd.c_str());
  RunResult r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, nullptr, dir};
  std::ifstream in(dir + "/summary.json");
  if (in) in >> r.summary;
  return r;
}

// A checkpoint's state: its field data, time, step and solver scalars, without the record of the runs
// that wrote it (history, wall times), which differs between a whole run and a resumed one.
// Empty when the file is missing or damaged.
inline std::string checkpoint_state(const std::string& path) {
  const std::size_t data = sph::checkpoint_data_bytes(path);
  if (data == 0) return "";
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto header = nlohmann::json::parse(bytes.substr(data, bytes.size() - data - 24));
  return bytes.substr(0, data) + header["t"].dump() + header["step"].dump() + header["scalars"].dump();
}

// One column of a run's timeseries.csv, by its header name (empty when the file or column is missing).
inline std::vector<double> timeseries_column(const RunResult& r, const std::string& name) {
  std::ifstream in(r.output_dir + "/timeseries.csv");
  std::string line, cell;
  std::getline(in, line);
  std::stringstream header(line);
  int column = -1;
  for (int k = 0; std::getline(header, cell, ','); ++k)
    if (cell == name) column = k;
  std::vector<double> values;
  while (column >= 0 && std::getline(in, line)) {
    std::stringstream row(line);
    for (int k = 0; k <= column && std::getline(row, cell, ','); ++k)
      if (k == column) values.push_back(std::atof(cell.c_str()));
  }
  return values;
}

}  // namespace sph::testing
