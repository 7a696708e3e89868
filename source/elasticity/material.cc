#include <ritr/elasticity/material.h>

namespace ritr
{
  MaterialModel material_model_from(const std::string &name)
  {
    return value_named(material_model_names, name, "material model");
  }
} // namespace ritr
