#pragma once
// Where a test finds the source tree (scenes, meshes, documents) and the ritr executable:
// RITR_SOURCE_DIR and RITR_BINARY from the environment when set (ctest sets both), otherwise
// the paths of the build that compiled the tests, so that a test executable also runs by
// itself. Compiled once, in test_paths.cc, so that only that file knows the build's paths.
#include <string>

namespace ritr::test_support
{
  std::string source_dir();
  std::string ritr_binary();
} // namespace ritr::test_support
