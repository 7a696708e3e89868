// The VTU pieces go through VTK's own XML writer (binary, zlib-compressed, appended data).
// This is the only translation unit that includes VTK headers: the rest of the simulator
// sees Eigen types only (vtk_files.h).
#include <ritr/common/atomic_file.h>
#include <ritr/output/vtk_files.h>

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <iomanip>
#include <stdexcept>

namespace ritr
{
  namespace
  {
    int vtk_cell_type(const std::size_t n_nodes)
    {
      switch (n_nodes)
        {
          case 1: return VTK_VERTEX;
          case 2: return VTK_LINE;
          case 3: return VTK_TRIANGLE;
          default: return VTK_TETRA;
        }
    }

    vtkNew<vtkDoubleArray> vtk_array(const VtuField &field)
    {
      vtkNew<vtkDoubleArray> array;
      array->SetName(field.name.c_str());
      array->SetNumberOfComponents(static_cast<int>(field.components));
      array->SetNumberOfTuples(field.values.size() / field.components);
      std::copy(field.values.data(), field.values.data() + field.values.size(), array->GetPointer(0));
      return array;
    }

    vtkNew<vtkUnstructuredGrid> vtk_grid(const VtuPiece &piece)
    {
      vtkNew<vtkPoints> points;
      points->SetDataTypeToDouble();
      points->SetNumberOfPoints(piece.points.rows());
      for (Eigen::Index i = 0; i < piece.points.rows(); ++i)
        points->SetPoint(i, piece.points(i, 0), piece.points(i, 1), piece.points(i, 2));

      vtkNew<vtkUnstructuredGrid> grid;
      grid->SetPoints(points);
      grid->Allocate(static_cast<vtkIdType>(piece.cells.size()));
      std::vector<vtkIdType> ids;
      for (const auto &cell : piece.cells)
        {
          ids.assign(cell.begin(), cell.end());
          grid->InsertNextCell(vtk_cell_type(cell.size()), static_cast<vtkIdType>(ids.size()), ids.data());
        }
      for (const auto &field : piece.point_data)
        grid->GetPointData()->AddArray(vtk_array(field));
      for (const auto &field : piece.cell_data)
        grid->GetCellData()->AddArray(vtk_array(field));
      return grid;
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
    const auto grid = vtk_grid(piece);
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetInputData(grid);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();  // raw bytes: base64 would make the files a third larger
    writer->SetCompressorTypeToZLib();
    // Level 1 writes a 100K-vertex frame twice as fast as VTK's default 5, for 2% more bytes
    // (doc/benchmarks.md).
    writer->SetCompressionLevel(1);
    // VTK writes into memory and write_file_atomically puts the bytes in place, so that a
    // killed run never leaves a torn file.
    writer->WriteToOutputStringOn();
    if (writer->Write() != 1)
      throw std::runtime_error("VTK could not write '" + path + "'");
    const std::string bytes = writer->GetOutputString();
    write_file_atomically(path, [&](std::ostream &out) { out << bytes; });
  }

  void PvdCollection::add(const double time, const std::string &file)
  {
    entries_.emplace_back(time, file);
    write();
  }

  void PvdCollection::assign(std::vector<std::pair<double, std::string>> entries)
  {
    entries_ = std::move(entries);
    write();
  }

  void PvdCollection::write() const
  {
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
