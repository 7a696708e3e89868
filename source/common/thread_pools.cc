#include <ritr/common/thread_pools.h>

#include <algorithm>

// Weak: a BLAS without OpenBLAS's extension, or a build without OpenMP, leaves them null.
extern "C"
{
  void openblas_set_num_threads(int) __attribute__((weak));
  void omp_set_num_threads(int) __attribute__((weak));
  void omp_set_max_active_levels(int) __attribute__((weak));
}

namespace ritr
{
  namespace
  {
    unsigned int factorization_threads = 1;
  }

  void set_factorization_threads(const unsigned int threads) { factorization_threads = std::max(1u, threads); }

  LargeFactorizationThreads::LargeFactorizationThreads(const double flops)
  {
    raised_ = factorization_threads > 1 && flops >= large_factorization_flops && openblas_set_num_threads;
    if (raised_)
      openblas_set_num_threads(static_cast<int>(factorization_threads));
  }

  LargeFactorizationThreads::~LargeFactorizationThreads()
  {
    if (raised_)
      openblas_set_num_threads(1);
  }

  void use_one_thread_pool()
  {
    if (openblas_set_num_threads)
      openblas_set_num_threads(1);
    if (omp_set_num_threads)
      omp_set_num_threads(1);
    // CHOLMOD's supernodal factorization asks for a team of 4 in a num_threads clause,
    // which overrides the line above; with no active level allowed, every parallel region
    // runs on the calling thread alone.
    if (omp_set_max_active_levels)
      omp_set_max_active_levels(0);
  }
} // namespace ritr
