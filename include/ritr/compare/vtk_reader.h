#pragma once
// Reading a run's solution series: the .pvd collection and its VTK XML UnstructuredGrid files
// (ASCII, binary, compressed or appended: the VTK library decodes them all). Throws InputError
// naming the file for anything missing or malformed.
#include <ritr/compare/deformed_mesh.h>

#include <filesystem>
#include <vector>

namespace ritr::compare
{
  struct PvdFrame
  {
    double                time;
    std::filesystem::path file; // resolved against the .pvd's folder
  };

  // The DataSet entries (timestep, file) of a ParaView collection, in file order.
  std::vector<PvdFrame> read_pvd(const std::filesystem::path &pvd_file);

  // Points and cells of an UnstructuredGrid of lines, triangles or tetrahedra (one kind only).
  DeformedMesh read_vtu(const std::filesystem::path &vtu_file);
} // namespace ritr::compare
