#include "src/io/csv_writer.hpp"

#include <petscsys.h>

#include "src/core/error.hpp"

namespace sph {

namespace {
bool is_root() {
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank == 0;
}
}  // namespace

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns)
    : columns_(columns.size()), path_(path) {
  if (!is_root()) return;
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) throw Error("cannot write " + path + "; check that -output_dir is writable");
  for (std::size_t k = 0; k < columns.size(); ++k) std::fprintf(file_, "%s%s", k ? "," : "", columns[k].c_str());
  std::fprintf(file_, "\n");
  std::fflush(file_);
}

CsvWriter::~CsvWriter() {
  if (file_) std::fclose(file_);
}

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_)
    throw Error("internal: CSV row of " + std::to_string(values.size()) + " values for " +
                std::to_string(columns_) + " columns in " + path_);
  if (!file_) return;
  for (std::size_t k = 0; k < values.size(); ++k) std::fprintf(file_, "%s%.12g", k ? "," : "", values[k]);
  std::fprintf(file_, "\n");
  std::fflush(file_);
}

}  // namespace sph
