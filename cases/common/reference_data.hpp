#pragma once
// Published reference tables compiled into the program (cases/*/data/*.csv), read as numeric columns.
#include <map>
#include <string>
#include <vector>

namespace sph {

// File name -> contents of every embedded reference file.
const std::map<std::string, std::string>& reference_files();

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  std::vector<double> column(const std::string& name) const;  // throws sph::Error if absent
};

// Parses an embedded CSV: '#' lines are comments, the first other line is the header.
Table reference_table(const std::string& file_name);

}  // namespace sph
