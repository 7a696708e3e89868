#include <ritr/scene/adaptivity_options.h>

#include <stdexcept>

namespace ritr
{
  namespace
  {
    [[noreturn]] void unknown(const std::string &what, const std::string &name)
    {
      throw std::invalid_argument("unknown " + what + " '" + name + "'");
    }
  } // namespace

  RitrHessian ritr_hessian_from(const std::string &name)
  {
    if (name == "truncated")
      return RitrHessian::truncated;
    if (name == "full")
      return RitrHessian::full;
    if (name == "filtered")
      return RitrHessian::filtered;
    unknown("outer Hessian", name);
  }

  InertiaForm inertia_form_from(const std::string &name)
  {
    if (name == "corrected")
      return InertiaForm::corrected;
    if (name == "uncorrected")
      return InertiaForm::uncorrected;
    unknown("inertia form", name);
  }

  PredictorProjection predictor_projection_from(const std::string &name)
  {
    if (name == "in-optimization")
      return PredictorProjection::in_optimization;
    if (name == "after-optimization")
      return PredictorProjection::after_optimization;
    unknown("predictor projection", name);
  }

  Admissibility admissibility_from(const std::string &name)
  {
    if (name == "none")
      return Admissibility::none;
    if (name == "geometric")
      return Admissibility::geometric;
    if (name == "physical")
      return Admissibility::physical;
    if (name == "both")
      return Admissibility::both;
    unknown("admissibility", name);
  }
} // namespace ritr
