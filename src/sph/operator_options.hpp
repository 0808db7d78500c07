#pragma once
// The operator options of the incompressible and weakly compressible schemes. A name both read means
// one thing in both (-viscous_laplacian, read here with one text); a choice whose words pick different
// operators in each scheme carries the scheme's prefix (-isph_operators picks the PPE's Laplacian and
// divergence, -wcsph_operators the continuity equation's divergence), as PETSc prefixes each object's.
#include <petscsys.h>

#include <string>

#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"
#include "src/sph/laplacian_smoothing.hpp"

namespace sph {

// The prefixes of the schemes' own operator choices, and those choices' names after it.
inline constexpr const char* kIsphPrefix = "isph_";
inline constexpr const char* kWcsphPrefix = "wcsph_";
inline const char* const scheme_operator_options[] = {"operators", "pressure_gradient"};

// The name of a scheme's own operator choice: "-" + prefix + name ("-isph_operators").
inline std::string scheme_option(const char* prefix, const char* name) { return std::string("-") + prefix + name; }

// Reads the options both schemes share into *viscous_laplacian (a ViscousLaplacian), inside the
// scheme's block; its default differs by scheme (the help text names both).
inline PetscErrorCode read_shared_operator_options(PetscOptionItems* block, PetscInt* viscous_laplacian) {
  PetscFunctionBeginUser;
  PetscCall(option_choice(block, "-viscous_laplacian", viscous_laplacian_help, viscous_laplacian_names, 2,
                          viscous_laplacian_names[*viscous_laplacian], viscous_laplacian, nullptr,
                          OptionLevel::expert));
  PetscFunctionReturn(0);
}

// For a scheme: the unprefixed name of one of its own operator choices, told the prefixed one
// (check_unused_options). Empty for any other option.
inline RenamedOption scheme_operator_rename(const char* prefix, const std::string& option) {
  for (const char* name : scheme_operator_options)
    if (option == name)
      return {prefix + option,
              "the schemes' own operator choices carry their prefix (-isph_, -wcsph_), since the "
              "same words pick different operators in each"};
  return {};
}

}  // namespace sph
