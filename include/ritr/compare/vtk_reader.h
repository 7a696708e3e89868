#pragma once
// A run's frames as ritr-compare sees them (output/vtk_reader.h reads the files).
#include <ritr/compare/deformed_mesh.h>
#include <ritr/output/vtk_reader.h>

#include <filesystem>

namespace ritr::compare
{
  using ritr::PvdFrame;
  using ritr::read_pvd;

  // The deformed simplices of a frame.
  DeformedMesh read_deformed_mesh(const std::filesystem::path &vtu_file);
} // namespace ritr::compare
