#include <ritr/common/symmetric_product.h>

#include <cassert>

// The Fortran BLAS interface: every BLAS the project can link (OpenBLAS, the reference BLAS)
// provides it, without a CBLAS header.
extern "C" void dsymv_(const char *uplo, const int *n, const double *alpha, const double *a, const int *lda,
                       const double *x, const int *incx, const double *beta, double *y, const int *incy);

namespace ritr
{
  Eigen::VectorXd symmetric_product(const Eigen::MatrixXd &lower, const Eigen::VectorXd &p)
  {
    assert(lower.rows() == lower.cols() && lower.cols() == p.size());
    const int       n = int(p.size()), one = 1;
    const double    alpha = 1.0, beta = 0.0;
    Eigen::VectorXd y(n);
    if (n > 0)
      dsymv_("L", &n, &alpha, lower.data(), &n, p.data(), &one, &beta, y.data(), &one);
    return y;
  }
} // namespace ritr
