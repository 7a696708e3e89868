#include <ritr/common/input_error.h>
#include <ritr/output/vtk_reader.h>

#include <vtkCallbackCommand.h>
#include <vtkCellType.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <string>

namespace ritr
{
  namespace
  {
    [[noreturn]] void fail(const std::filesystem::path &file, const std::string &what)
    {
      throw InputError(file.string() + ": " + what);
    }

    // VTK reports problems as error events of whichever object met them and, unobserved, prints
    // them as multi-line logs. Observing them keeps stderr to our one line and keeps the reason:
    // the first message, stripped of VTK's "In file, line" header and object address.
    class VtkErrors
    {
    public:
      VtkErrors()
      {
        command_->SetClientData(&first_);
        command_->SetCallback([](vtkObject *, unsigned long, void *client, void *message) {
          auto &first = *static_cast<std::string *>(client);
          if (first.empty() && message != nullptr)
            first = static_cast<const char *>(message);
        });
      }

      vtkCommand *command() const
      {
        return command_;
      }

      void observe(vtkObject *object) const
      {
        object->AddObserver(vtkCommand::ErrorEvent, command_.Get());
      }

      // Throws when an error was reported.
      void check(const std::filesystem::path &file, const std::string &what) const
      {
        if (first_.empty())
          return;
        std::string reason = first_;
        if (const auto p = reason.rfind("): "); p != std::string::npos)
          reason = reason.substr(p + 3);
        while (!reason.empty() && (reason.back() == '\n' || reason.back() == ' '))
          reason.pop_back();
        fail(file, what + " (" + reason + ")");
      }

    private:
      vtkNew<vtkCallbackCommand> command_;
      std::string                first_;
    };

    unsigned int cell_dimension(const int vtk_type)
    {
      switch (vtk_type)
        {
          case VTK_LINE: return 1;
          case VTK_TRIANGLE: return 2;
          case VTK_TETRA: return 3;
          default: return 0;
        }
    }
  } // namespace

  std::vector<PvdFrame> read_pvd(const std::filesystem::path &pvd_file)
  {
    if (!std::filesystem::is_regular_file(pvd_file))
      fail(pvd_file, "no such file");
    const VtkErrors        errors;
    vtkNew<vtkXMLDataParser> parser;
    errors.observe(parser);
    parser->SetFileName(pvd_file.c_str());
    const int parsed = parser->Parse();
    errors.check(pvd_file, "not a valid XML file");
    vtkXMLDataElement *root = parser->GetRootElement();
    if (!parsed || root == nullptr || std::string(root->GetName()) != "VTKFile" ||
        root->GetAttribute("type") == nullptr || std::string(root->GetAttribute("type")) != "Collection")
      fail(pvd_file, "not a ParaView collection (expected <VTKFile type=\"Collection\">)");
    vtkXMLDataElement *collection = root->FindNestedElementWithName("Collection");
    if (collection == nullptr)
      fail(pvd_file, "no <Collection> element");

    std::vector<PvdFrame> frames;
    for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i)
      {
        vtkXMLDataElement *entry = collection->GetNestedElement(i);
        if (std::string(entry->GetName()) != "DataSet")
          continue;
        double      time = 0.0;
        const char *file = entry->GetAttribute("file");
        if (!entry->GetScalarAttribute("timestep", time) || file == nullptr)
          fail(pvd_file, "DataSet entry " + std::to_string(i) + " lacks a numeric timestep or a file");
        frames.push_back({time, pvd_file.parent_path() / file});
      }
    return frames;
  }

  VtuGrid read_vtu(const std::filesystem::path &vtu_file)
  {
    if (!std::filesystem::is_regular_file(vtu_file))
      fail(vtu_file, "no such file");
    const VtkErrors                      errors;
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    errors.observe(reader);
    errors.observe(reader->GetExecutive());
    reader->SetReaderErrorObserver(errors.command());
    reader->SetParserErrorObserver(errors.command());
    if (!reader->CanReadFile(vtu_file.c_str()))
      {
        errors.check(vtu_file, "not a VTK XML UnstructuredGrid file");
        fail(vtu_file, "not a VTK XML UnstructuredGrid file");
      }
    reader->SetFileName(vtu_file.c_str());
    reader->Update();
    errors.check(vtu_file, "invalid VTK XML UnstructuredGrid file");

    vtkUnstructuredGrid *grid = reader->GetOutput();
    VtuGrid              mesh;
    mesh.points.resize(grid->GetNumberOfPoints());
    for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
      grid->GetPoint(i, mesh.points[i].data());
    vtkPointData *data = grid->GetPointData();
    for (int a = 0; a < data->GetNumberOfArrays(); ++a)
      {
        vtkDataArray *array = data->GetArray(a);
        if (array == nullptr || array->GetName() == nullptr)
          continue;  // not numeric, or nameless: nothing to look it up by
        auto &field = mesh.point_fields[array->GetName()];
        field.resize(array->GetNumberOfTuples(), array->GetNumberOfComponents());
        for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
          for (int k = 0; k < array->GetNumberOfComponents(); ++k)
            field(i, k) = array->GetComponent(i, k);
      }

    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
      {
        const unsigned int d = cell_dimension(grid->GetCellType(c));
        if (d == 0)
          fail(vtu_file, "cell " + std::to_string(c) + " has VTK type " + std::to_string(grid->GetCellType(c)) +
                           "; expected lines, triangles or tetrahedra");
        if (mesh.dim != 0 && d != mesh.dim)
          fail(vtu_file, "mixes cells of dimension " + std::to_string(mesh.dim) + " and " + std::to_string(d));
        mesh.dim = d;
        grid->GetCellPoints(c, ids);
        std::vector<unsigned int> &cell = mesh.cells.emplace_back();
        for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
          cell.push_back(static_cast<unsigned int>(ids->GetId(k)));
      }
    if (mesh.cells.empty())
      fail(vtu_file, "has no cells");
    return mesh;
  }
} // namespace ritr
