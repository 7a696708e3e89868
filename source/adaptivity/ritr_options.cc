#include <ritr/adaptivity/ritr_options.h>

namespace ritr
{
  RitrHessian ritr_hessian_from(const std::string &name)
  {
    return value_named(ritr_hessian_names, name, "outer Hessian");
  }

  InertiaForm inertia_form_from(const std::string &name)
  {
    return value_named(inertia_form_names, name, "inertia form");
  }

  PredictorProjection predictor_projection_from(const std::string &name)
  {
    return value_named(predictor_projection_names, name, "predictor projection");
  }

  Admissibility admissibility_from(const std::string &name)
  {
    return value_named(admissibility_names, name, "admissibility");
  }

  TransferIntegrationChoice transfer_integration_from(const std::string &name)
  {
    return value_named(transfer_integration_names, name, "transfer integration");
  }
} // namespace ritr
