#pragma once
// The cases the sph program knows, chosen by name with -case.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "src/run/case.hpp"

namespace sph {

struct CaseEntry {
  std::string name;
  std::string description;
  int default_dim;
  std::function<std::unique_ptr<Case<1>>()> make1;  // empty where the case has no 1D form
  std::function<std::unique_ptr<Case<2>>()> make2;
  std::function<std::unique_ptr<Case<3>>()> make3;
  std::function<int()> input_dim = nullptr;  // the dimension of the case's input (a scene file), if it has one
};

const std::vector<CaseEntry>& case_registry();
const CaseEntry& find_case(const std::string& name);  // throws sph::Error listing the known cases
// The case's dimension when -dim is not given: its input's, else its default.
int case_dimension(const std::string& name);
template <int D> std::unique_ptr<Case<D>> create_case(const std::string& name);

}  // namespace sph
