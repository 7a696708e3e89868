// Solver/factorization threads: OpenBLAS runs on more than one thread only inside a
// factorization of at least large_factorization_flops, and is back on one after it, so that
// everything else keeps one thread pool (TBB's) and the default keeps results bit-identical.
#include <ritr/common/thread_pools.h>

#include <gtest/gtest.h>

extern "C" int openblas_get_num_threads() __attribute__((weak));

namespace
{
  int blas_threads() { return openblas_get_num_threads(); }
} // namespace

TEST(FactorizationThreads, OnlyLargeFactorizationsRaiseTheBlasThreads)
{
  if (!openblas_get_num_threads)
    GTEST_SKIP() << "the BLAS linked is not OpenBLAS";
  ritr::use_one_thread_pool();
  ASSERT_EQ(blas_threads(), 1);

  // The default: one thread whatever the factorization.
  ritr::set_factorization_threads(1);
  {
    const ritr::LargeFactorizationThreads guard(1e12);
    EXPECT_EQ(blas_threads(), 1);
  }

  ritr::set_factorization_threads(2);
  {
    const ritr::LargeFactorizationThreads guard(0.5 * ritr::large_factorization_flops);
    EXPECT_EQ(blas_threads(), 1) << "a small factorization keeps one thread";
  }
  {
    const ritr::LargeFactorizationThreads guard(ritr::large_factorization_flops);
    EXPECT_EQ(blas_threads(), 2) << "a large factorization takes the factorization threads";
  }
  EXPECT_EQ(blas_threads(), 1) << "back on one thread after the factorization";
  ritr::set_factorization_threads(1);
}
