#pragma once
// Refusing, up front, what cannot fit in memory: a mesh refined too often or an obstacle of
// too many spikes would otherwise end in std::bad_alloc after a long wait.
#include <string>

namespace ritr
{
  // This machine's physical memory in bytes.
  double physical_memory_bytes();

  // Why `count` items (`items`, e.g. "cells") of at least `bytes_each` bytes each cannot be
  // held ("" when they can): "make 8.2e+11 cells, which need at least 1.6e+15 bytes of memory
  // (this machine has 2.5e+10)". `count` is a double so that the estimate itself cannot
  // overflow.
  std::string memory_problem(double count, double bytes_each, const std::string &items);
} // namespace ritr
