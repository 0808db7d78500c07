#include "src/io/csv_writer.hpp"

#include <petscsys.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "src/core/error.hpp"
#include "src/io/output_dir.hpp"

namespace sph {

namespace {

bool is_root() {
  PetscMPIInt rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank == 0;
}

// Shortest decimal form that parses back to exactly `x` (C++17 std::to_chars).
void append_number(std::string& line, double x) {
  if (std::isnan(x)) {
    line += "nan";
    return;
  }
  if (std::isinf(x)) {
    line += x > 0 ? "inf" : "-inf";
    return;
  }
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  line.append(buf, res.ptr);
}

}  // namespace

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns)
    : columns_(columns.size()), path_(path) {
  if (!is_root()) return;
  note_output(path);
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) throw Error("cannot write " + path + "; check that -output_dir is writable");
  std::string header;
  for (std::size_t k = 0; k < columns.size(); ++k) header += (k ? "," : "") + columns[k];
  header += '\n';
  if (std::fputs(header.c_str(), file_) < 0 || std::fflush(file_) != 0) {
    std::fclose(file_);
    file_ = nullptr;
    throw Error("failed writing " + path + " (disk full?)");
  }
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns, std::size_t key,
                     double resume_at)
    : columns_(columns.size()), path_(path) {
  if (!is_root()) return;
  note_output(path);
  std::vector<std::string> kept;
  {
    std::ifstream in(path);
    std::string line;
    bool header = true;
    while (std::getline(in, line)) {
      if (header) {
        header = false;
        continue;
      }
      std::size_t start = 0;
      for (std::size_t k = 0; k < key && start != std::string::npos; ++k) start = line.find(',', start) + 1;
      if (start != std::string::npos && std::strtod(line.c_str() + start, nullptr) <= resume_at) kept.push_back(line);
    }
  }
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) throw Error("cannot write " + path + "; check that -output_dir is writable");
  std::string text;
  for (std::size_t k = 0; k < columns.size(); ++k) text += (k ? "," : "") + columns[k];
  text += '\n';
  for (const auto& l : kept) text += l + '\n';
  if (std::fputs(text.c_str(), file_) < 0 || std::fflush(file_) != 0) throw Error("failed writing " + path);
}

CsvWriter::~CsvWriter() {
  if (file_) std::fclose(file_);
}

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_)
    throw Error("internal: CSV row of " + std::to_string(values.size()) + " values for " + std::to_string(columns_) +
                " columns in " + path_);
  if (!file_) return;
  std::string line;
  line.reserve(24 * values.size() + 1);
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (k) line += ',';
    append_number(line, values[k]);
  }
  line += '\n';
  if (std::fputs(line.c_str(), file_) < 0 || std::fflush(file_) != 0)
    throw Error("failed writing " + path_ + " (disk full?)");
}

}  // namespace sph
