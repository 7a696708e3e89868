#include <ritr/common/thread_pools.h>

// Weak: a BLAS without OpenBLAS's extension, or a build without OpenMP, leaves them null.
extern "C"
{
  void openblas_set_num_threads(int) __attribute__((weak));
  void omp_set_num_threads(int) __attribute__((weak));
  void omp_set_max_active_levels(int) __attribute__((weak));
}

namespace ritr
{
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
