#pragma once
// Vector- and scalar-valued expressions of position and time ("0; -t*2", "x>0.5"), compiled
// once with deal.II's FunctionParser. Components are separated by ';'. A scalar written
// where a vector is expected is not broadcast: every component must be given.
#include <Eigen/Core>

#include <memory>
#include <string>

namespace ritr
{
  template <int dim>
  class Expression
  {
  public:
    // Throws std::runtime_error with the parser's reason when `text` does not compile to
    // `n_components` components in the variables x, y, z (first dim of them) and t.
    Expression(const std::string &text, unsigned int n_components);
    ~Expression();
    Expression(Expression &&) noexcept;

    double value(const Eigen::Matrix<double, dim, 1> &position, double t, unsigned int component = 0) const;
    Eigen::VectorXd vector_value(const Eigen::Matrix<double, dim, 1> &position, double t) const;
    unsigned int n_components() const { return n_components_; }

  private:
    struct Parser;  // deal.II's FunctionParser, kept out of this header
    std::unique_ptr<Parser> function_;
    unsigned int                           n_components_;
  };
} // namespace ritr
