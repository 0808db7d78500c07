# Writes OUTPUT, a C++ file defining sph::program_version(): the release RELEASE (the project's
# version) with `git describe` of SOURCE_DIR at build time: "v0.1.0" on a release tag, "v0.1.0-3-gabc1234"
# three commits after it, "0.1.0+gabc1234" where no tag is reachable (a shallow clone), "0.1.0 (built
# without git)" where the sources have no git metadata (a release tarball). "-dirty": uncommitted changes.
# Run by the sph_version target on every build; the file is rewritten only when the text changes,
# so an unchanged version recompiles nothing.
set(version "${RELEASE} (built without git)")
find_package(Git QUIET)
if(GIT_FOUND AND EXISTS "${SOURCE_DIR}/.git")
  execute_process(COMMAND "${GIT_EXECUTABLE}" describe --tags --always --dirty
                  WORKING_DIRECTORY "${SOURCE_DIR}" OUTPUT_VARIABLE described RESULT_VARIABLE rc
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(rc EQUAL 0 AND described MATCHES "^v[0-9]")
    set(version "${described}")
  elseif(rc EQUAL 0 AND described)
    set(version "${RELEASE}+g${described}")
  endif()
endif()
set(text "// Generated at build time by cmake/version.cmake\n#include \"src/run/provenance.hpp\"\n")
string(APPEND text "const char* sph::program_version() { return \"${version}\"; }\n")
set(old "")
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUTPUT}" "${text}")
endif()
