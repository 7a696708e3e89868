#pragma once

namespace ritr
{
  // Assembly runs on TBB's thread pool (Solver/threads). OpenBLAS (its pthreads build) and
  // OpenMP, which CHOLMOD calls with a team of 4, would each keep a team of their own on the
  // same cores, spinning between calls: on 2 cores, without them, CHOLMOD's factorizations
  // take 25-35 % less time from 2.7K to 100K vertices, with bit-identical results
  // (doc/benchmarks.md). Call once at start-up, before any solve.
  void use_one_thread_pool();

  // Opt-in exception (Solver/factorization threads): OpenBLAS runs on `threads` threads in
  // factorizations of at least large_factorization_flops, where its team gains more than it
  // spins (3D meshes from about 40K vertices); 1, the default, keeps one pool throughout.
  constexpr double large_factorization_flops = 1e10;
  void set_factorization_threads(unsigned int threads);

  // OpenBLAS on the factorization threads while it lives, if the factorization it guards
  // takes `flops` of at least large_factorization_flops; back on one thread after.
  class LargeFactorizationThreads
  {
  public:
    explicit LargeFactorizationThreads(double flops);
    ~LargeFactorizationThreads();
    LargeFactorizationThreads(const LargeFactorizationThreads &)            = delete;
    LargeFactorizationThreads &operator=(const LargeFactorizationThreads &) = delete;

  private:
    bool raised_ = false;
  };
} // namespace ritr
