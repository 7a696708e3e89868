#pragma once
// Reading a run's outputs back: the .pvd collection and its VTK XML UnstructuredGrid files
// (ASCII, binary, compressed or appended: the VTK library decodes them all). Throws InputError
// naming the file for anything missing or malformed. Its interface holds Eigen and standard
// types only, so that VTK's headers stay out of the translation units that use it.
#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace ritr
{
  struct PvdFrame
  {
    double                time;
    std::filesystem::path file; // resolved against the .pvd's folder
  };

  // The DataSet entries (timestep, file) of a ParaView collection, in file order.
  std::vector<PvdFrame> read_pvd(const std::filesystem::path &pvd_file);

  // An UnstructuredGrid of lines, triangles or tetrahedra (one kind only).
  struct VtuGrid
  {
    unsigned int                           dim = 0; // 1 lines, 2 triangles, 3 tetrahedra
    std::vector<std::array<double, 3>>     points;  // three coordinates, trailing zeros below 3D
    std::vector<std::vector<unsigned int>> cells;   // dim + 1 point indices each
    // The numeric point arrays by name: one row per point, one column per component.
    std::map<std::string, Eigen::MatrixXd> point_fields;
  };

  VtuGrid read_vtu(const std::filesystem::path &vtu_file);
} // namespace ritr
