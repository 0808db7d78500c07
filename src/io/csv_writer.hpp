#pragma once
// A CSV time series: a header line, then one row of numbers per call, flushed at once so a run that
// dies keeps every row it wrote. Numbers are written in the shortest form that reads back to the
// same double (round-trip exact); NaN and infinities are written as nan, inf, -inf.
// Only rank 0 of PETSC_COMM_WORLD opens and writes the file; on other ranks every call is a no-op
// apart from the row-length check. Not collective: a failure throws sph::Error on rank 0 only.
#include <cstdio>
#include <string>
#include <vector>

namespace sph {

class CsvWriter {
 public:
  // Creates (truncates) `path` and writes the header line; throws sph::Error naming the file on failure.
  CsvWriter(const std::string& path, const std::vector<std::string>& columns);
  // For a restart: keeps the existing file's rows whose first column `key` is <= resume_at and
  // appends after them (the header must match).
  CsvWriter(const std::string& path, const std::vector<std::string>& columns, std::size_t key, double resume_at);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  // Appends one row; throws sph::Error if values.size() != number of columns, or if writing fails.
  void row(const std::vector<double>& values);

  const std::string& path() const { return path_; }

 private:
  std::FILE* file_ = nullptr;
  std::size_t columns_ = 0;
  std::string path_;
};

}  // namespace sph
