#pragma once

namespace ritr
{
  // Assembly runs on TBB's thread pool (Solver/threads). OpenBLAS (its pthreads build) and
  // OpenMP, which CHOLMOD calls, would each keep a team of their own on the same cores,
  // spinning in sched_yield between calls: on 2 cores two concurrent 2.7K-vertex runs took
  // 12.8 s each with those teams and 10.7 s after this call, and a 100K-vertex factorization
  // was not measurably slower single-threaded (doc/benchmarks.md). Call once at start-up,
  // before any solve.
  void use_one_thread_pool();
} // namespace ritr
