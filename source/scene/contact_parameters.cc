// Subsection Contact of a parameter file.
#include <ritr/common/input_error.h>
#include <ritr/scene/parameter_text.h>
#include <ritr/scene/scene.h>

#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <cstdlib>

namespace ritr
{
  namespace
  {
    namespace Patterns = dealii::Patterns;

    // Barrier stiffness 0 in the struct is "adaptive" in the file; any other is positive.
    const std::string adaptive_stiffness = "adaptive";

    std::string barrier_stiffness_text(const double stiffness)
    {
      return stiffness == 0 ? adaptive_stiffness : prm_value(stiffness);
    }

    double barrier_stiffness_from(const std::string &text)
    {
      if (text == adaptive_stiffness)
        return 0;
      char        *end       = nullptr;
      const double stiffness = std::strtod(text.c_str(), &end);
      if (end == text.c_str() || *end != '\0' || !(stiffness > 0) || !std::isfinite(stiffness))
        throw EntryError("Contact/barrier stiffness", "must be 'adaptive' or a positive number");
      return stiffness;
    }
  } // namespace

  void ContactScene::declare_parameters(dealii::ParameterHandler &prm)
  {
    const ContactScene d;
    prm.enter_subsection("Contact");
    prm.declare_entry("enabled", prm_value(d.enabled), Patterns::Bool(), "IPC contact between bodies, with obstacles, and self-contact.");
    prm.declare_entry("dhat", prm_value(d.dhat), Patterns::Double(0), "Barrier activation distance.");
    prm.declare_entry("barrier stiffness", barrier_stiffness_text(d.barrier_stiffness), Patterns::Anything(), "'adaptive' (IPC's initialisation and doubling rule) or a fixed positive value.");
    prm.declare_entry("friction coefficient", prm_value(d.friction_coefficient), Patterns::Double(0), "Coulomb friction coefficient mu (0: frictionless).");
    prm.declare_entry("epsilon v", prm_value(d.epsilon_v), Patterns::Double(0), "Friction smoothing velocity eps_v [m/s]; positive when there is friction.");
    prm.declare_entry("friction iterations", prm_value(d.friction_iterations), Patterns::Integer(1), "Lagged friction updates per step.");
    prm.declare_entry("self contact", prm_value(d.self_contact), Patterns::Bool(), "Contact within one body and between bodies.");
    prm.leave_subsection();
  }

  void ContactScene::parse_parameters(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    enabled              = prm.get_bool("enabled");
    dhat                 = prm.get_double("dhat");
    barrier_stiffness    = barrier_stiffness_from(prm.get("barrier stiffness"));
    friction_coefficient = prm.get_double("friction coefficient");
    epsilon_v            = prm.get_double("epsilon v");
    friction_iterations  = prm.get_integer("friction iterations");
    self_contact         = prm.get_bool("self contact");
    prm.leave_subsection();
    if (!(dhat > 0))
      throw EntryError("Contact/dhat", "must be positive");
    if (enabled && friction_coefficient > 0 && !(epsilon_v > 0))
      throw EntryError("Contact/epsilon v", "must be positive when the friction coefficient is");
  }
} // namespace ritr
