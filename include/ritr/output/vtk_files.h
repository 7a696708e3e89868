#pragma once
// ParaView output: unstructured-grid VTU pieces (VTK XML, binary and compressed, written by
// the VTK library) and the PVD collections that index them by time. Every file is written
// atomically (temporary name, then rename). Only Eigen types here: VTK's headers stay in
// vtk_files.cc.
#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace ritr
{
  struct VtuField
  {
    std::string     name;
    unsigned int    components;  // 1 or 3 (vectors are padded to 3 for ParaView)
    Eigen::VectorXd values;      // n_entities * components
  };

  struct VtuPiece
  {
    Eigen::MatrixXd                        points;  // n x 3
    std::vector<std::vector<unsigned int>> cells;   // vertex lists (1, 2, 3 or 4 nodes)
    std::vector<VtuField>                  point_data, cell_data;
  };

  void write_vtu(const std::string &path, const VtuPiece &piece);

  // A PVD collection of (time, file name relative to the collection) entries.
  class PvdCollection
  {
  public:
    explicit PvdCollection(std::string path) : path_(std::move(path)) {}
    void add(double time, const std::string &file);  // appends and rewrites the collection
    // Replaces the entries and rewrites the collection (a resumed run's frames so far).
    void assign(std::vector<std::pair<double, std::string>> entries);

  private:
    void write() const;

    std::string                                 path_;
    std::vector<std::pair<double, std::string>> entries_;
  };

  // Pads dim-component nodal vectors (entry i*dim + k) to 3 components.
  Eigen::VectorXd pad_to_3d(const Eigen::VectorXd &values, int dim);
} // namespace ritr
