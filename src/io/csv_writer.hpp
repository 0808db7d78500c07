#pragma once
// A CSV time series: a header line, then one row of numbers per call, flushed at once so a run that
// dies keeps every row it wrote. Only rank 0 writes.
#include <cstdio>
#include <string>
#include <vector>

namespace sph {

class CsvWriter {
 public:
  CsvWriter(const std::string& path, const std::vector<std::string>& columns);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  void row(const std::vector<double>& values);

 private:
  std::FILE* file_ = nullptr;
  std::size_t columns_ = 0;
  std::string path_;
};

}  // namespace sph
