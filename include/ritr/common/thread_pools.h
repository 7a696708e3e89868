#pragma once

namespace ritr
{
  // Assembly runs on TBB's thread pool (Solver/threads). OpenBLAS (its pthreads build) and
  // OpenMP, which CHOLMOD calls with a team of 4, would each keep a team of their own on the
  // same cores, spinning between calls: on 2 cores, without them, CHOLMOD's factorizations
  // take 25-35 % less time from 2.7K to 100K vertices, with bit-identical results
  // (doc/benchmarks.md). Call once at start-up, before any solve.
  void use_one_thread_pool();
} // namespace ritr
