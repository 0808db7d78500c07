# Writes OUTPUT, a C++ file defining sph::program_version(): `git describe` of SOURCE_DIR at build
# time, or "unknown (built without git)" where the sources have no git metadata (a release tarball).
# Run by the sph_version target on every build; the file is rewritten only when the text changes,
# so an unchanged version recompiles nothing.
set(version "unknown (built without git)")
find_package(Git QUIET)
if(GIT_FOUND AND EXISTS "${SOURCE_DIR}/.git")
  execute_process(COMMAND "${GIT_EXECUTABLE}" describe --tags --always --dirty
                  WORKING_DIRECTORY "${SOURCE_DIR}" OUTPUT_VARIABLE described RESULT_VARIABLE rc
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(rc EQUAL 0 AND described)
    set(version "${described}")
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
