#include "test_paths.h"

#include <cstdlib>

namespace ritr::test_support
{
  namespace
  {
    std::string from_environment(const char *name, const char *built)
    {
      const char *value = std::getenv(name);
      return value && *value ? value : built;
    }
  } // namespace

  std::string source_dir() { return from_environment("RITR_SOURCE_DIR", RITR_BUILT_SOURCE_DIR); }

  std::string ritr_binary() { return from_environment("RITR_BINARY", RITR_BUILT_BINARY); }
} // namespace ritr::test_support
