#include <ritr/common/atomic_file.h>
#include <ritr/output/vtk_files.h>

#include <iomanip>

namespace ritr
{
  namespace
  {
    int vtk_cell_type(const std::size_t n_nodes)
    {
      switch (n_nodes)
        {
          case 1: return 1;   // VTK_VERTEX
          case 2: return 3;   // VTK_LINE
          case 3: return 5;   // VTK_TRIANGLE
          default: return 10; // VTK_TETRA
        }
    }

    void write_fields(std::ostream &out, const std::vector<VtuField> &fields)
    {
      for (const auto &f : fields)
        {
          out << "<DataArray type=\"Float64\" Name=\"" << f.name << "\" NumberOfComponents=\""
              << f.components << "\" format=\"ascii\">\n";
          for (Eigen::Index i = 0; i < f.values.size(); ++i)
            out << f.values[i] << ((i + 1) % f.components == 0 ? '\n' : ' ');
          out << "</DataArray>\n";
        }
    }
  } // namespace

  Eigen::VectorXd pad_to_3d(const Eigen::VectorXd &values, const int dim)
  {
    const Eigen::Index n = values.size() / dim;
    Eigen::VectorXd    r = Eigen::VectorXd::Zero(3 * n);
    for (Eigen::Index i = 0; i < n; ++i)
      for (int k = 0; k < dim; ++k)
        r[3 * i + k] = values[i * dim + k];
    return r;
  }

  void write_vtu(const std::string &path, const VtuPiece &piece)
  {
    write_file_atomically(path, [&](std::ostream &out) {
      out << "<?xml version=\"1.0\"?>\n"
          << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
          << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << piece.points.rows()
          << "\" NumberOfCells=\"" << piece.cells.size() << "\">\n";
      out << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
      for (Eigen::Index i = 0; i < piece.points.rows(); ++i)
        out << piece.points(i, 0) << ' ' << piece.points(i, 1) << ' ' << piece.points(i, 2) << '\n';
      out << "</DataArray>\n</Points>\n<Cells>\n"
          << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
      for (const auto &c : piece.cells)
        {
          for (const auto v : c)
            out << v << ' ';
          out << '\n';
        }
      out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
      std::size_t offset = 0;
      for (const auto &c : piece.cells)
        out << (offset += c.size()) << '\n';
      out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
      for (const auto &c : piece.cells)
        out << vtk_cell_type(c.size()) << '\n';
      out << "</DataArray>\n</Cells>\n<PointData>\n";
      write_fields(out, piece.point_data);
      out << "</PointData>\n<CellData>\n";
      write_fields(out, piece.cell_data);
      out << "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    });
  }

  void PvdCollection::add(const double time, const std::string &file)
  {
    entries_.emplace_back(time, file);
    write_file_atomically(path_, [&](std::ostream &out) {
      // Full precision: runs are paired frame by frame on these times (ritr-compare).
      out << std::setprecision(17);
      out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
      for (const auto &[t, f] : entries_)
        out << "<DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << f << "\"/>\n";
      out << "</Collection>\n</VTKFile>\n";
    });
  }
} // namespace ritr
