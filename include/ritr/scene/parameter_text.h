#pragma once
// Values as a parameter file writes them, for the defaults that the schema declares from
// the scene structs' default values.
#include <string>
#include <vector>

namespace ritr
{
  // The shortest text that reads back as the same double: fixed notation for magnitudes
  // from 0.01 to 9999 ("0.01", "9.81", "1000"), a bare exponent otherwise ("1e-05" is
  // "1e-5", 100000 is "1e5").
  std::string prm_value(double value);
  std::string prm_value(int value);
  std::string prm_value(unsigned int value);
  std::string prm_value(bool value);  // true|false
  // Comma-separated ("0,-9.81,0").
  std::string prm_value(const std::vector<double> &values);
  std::string prm_value(const std::vector<unsigned int> &values);
} // namespace ritr
