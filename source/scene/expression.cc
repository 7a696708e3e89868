#include <ritr/scene/expression.h>
#include <ritr/common/input_error.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace ritr
{
  template <int dim>
  struct Expression<dim>::Parser : dealii::FunctionParser<dim>
  {
    using dealii::FunctionParser<dim>::FunctionParser;
  };

  namespace
  {
    unsigned int count_components(const std::string &text)
    {
      return 1 + std::count(text.begin(), text.end(), ';');
    }
  } // namespace

  template <int dim>
  Expression<dim>::Expression(const std::string &text, const unsigned int n_components)
    : n_components_(n_components)
  {
    if (count_components(text) != n_components)
      throw std::runtime_error("expression '" + shortened(text) + "' has " +
                               std::to_string(count_components(text)) + " components, expected " +
                               std::to_string(n_components));
    auto parser = std::make_unique<Parser>(n_components);
    const std::string variables = dim == 1 ? "x,t" : dim == 2 ? "x,y,t" : "x,y,z,t";
    // The expression library reports syntax errors on std::cerr before throwing; the
    // caller prints one line of its own instead.
    std::stringstream          silenced;
    std::streambuf *const      previous = std::cerr.rdbuf(silenced.rdbuf());
    const std::shared_ptr<void> restore(nullptr, [previous](void *) { std::cerr.rdbuf(previous); });
    try
      {
        parser->initialize(variables, text, {{"pi", M_PI}}, true);
        // FunctionParser compiles lazily: evaluate once so that syntax errors surface here.
        dealii::Vector<double> v(n_components);
        parser->vector_value(dealii::Point<dim>(), v);
      }
    catch (const std::exception &e)
      {
        throw std::runtime_error("cannot parse expression '" + shortened(text) + "' (variables: " + variables + ")");
      }
    function_ = std::move(parser);
  }

  template <int dim>
  Expression<dim>::~Expression() = default;
  template <int dim>
  Expression<dim>::Expression(Expression &&) noexcept = default;

  template <int dim>
  double Expression<dim>::value(const Eigen::Matrix<double, dim, 1> &position, const double t,
                                const unsigned int component) const
  {
    dealii::Point<dim> p;
    for (int k = 0; k < dim; ++k)
      p[k] = position[k];
    function_->set_time(t);
    return function_->value(p, component);
  }

  template <int dim>
  Eigen::VectorXd Expression<dim>::vector_value(const Eigen::Matrix<double, dim, 1> &position,
                                                const double t) const
  {
    Eigen::VectorXd r(n_components_);
    for (unsigned int c = 0; c < n_components_; ++c)
      r[c] = value(position, t, c);
    return r;
  }

  template class Expression<1>;
  template class Expression<2>;
  template class Expression<3>;
} // namespace ritr
