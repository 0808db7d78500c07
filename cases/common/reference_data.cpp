#include "cases/common/reference_data.hpp"

#include <sstream>

#include "src/core/error.hpp"

namespace sph {

std::vector<double> Table::column(const std::string& name) const {
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (columns[c] != name) continue;
    std::vector<double> v;
    for (const auto& r : rows) v.push_back(r.at(c));
    return v;
  }
  throw Error("reference table has no column '" + name + "'");
}

Table reference_table(const std::string& file_name) {
  const auto& files = reference_files();
  const auto it = files.find(file_name);
  if (it == files.end()) throw Error("no embedded reference data '" + file_name + "'");
  Table t;
  std::istringstream in(it->second);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string field;
    std::vector<std::string> cells;
    while (std::getline(fields, field, ',')) cells.push_back(field);
    if (t.columns.empty()) {
      t.columns = cells;
      continue;
    }
    std::vector<double> row;
    for (const auto& c : cells) row.push_back(std::stod(c));
    t.rows.push_back(row);
  }
  return t;
}

}  // namespace sph
