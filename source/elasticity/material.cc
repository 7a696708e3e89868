#include <ritr/elasticity/material.h>

#include <stdexcept>

namespace ritr
{
  MaterialModel parse_material_model(const std::string &name)
  {
    if (name == "neo-hookean")
      return MaterialModel::neo_hookean;
    if (name == "linear")
      return MaterialModel::linear;
    if (name == "stvk")
      return MaterialModel::stvk;
    throw std::runtime_error("unknown material model '" + name +
                             "' (expected neo-hookean, linear or stvk)");
  }
} // namespace ritr
