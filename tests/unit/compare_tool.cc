// ritr-compare: boundary extraction, Hausdorff distances against hand-computed values, centroids,
// the readers (ASCII as ritr wrote before its VTK writer, compressed binary as ritr writes now)
// and the whole tool on two tiny runs written here.
#include <ritr/common/input_error.h>
#include <ritr/compare/boundary.h>
#include <ritr/compare/energy_log.h>
#include <ritr/compare/hausdorff.h>
#include <ritr/compare/run_comparison.h>
#include <ritr/compare/vtk_reader.h>

#include <gtest/gtest.h>
#include <run_ritr.h>
#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

using namespace ritr::compare;
namespace fs = std::filesystem;

namespace
{
  DeformedMesh translated(DeformedMesh mesh, const Point &shift)
  {
    for (Point &p : mesh.points)
      for (int k = 0; k < 3; ++k)
        p[k] += shift[k];
    return mesh;
  }

  // The axis-aligned square [x0, x0 + size] x [y0, y0 + size] as two triangles.
  DeformedMesh square(const double x0, const double y0, const double size)
  {
    return {2,
            {{x0, y0, 0}, {x0 + size, y0, 0}, {x0 + size, y0 + size, 0}, {x0, y0 + size, 0}},
            {{0, 1, 2}, {0, 2, 3}}};
  }

  // Regular n-gon of radius 1 around the origin, fanned from its centre.
  DeformedMesh circle_polygon(const unsigned int n)
  {
    DeformedMesh mesh{2, {{0, 0, 0}}, {}};
    for (unsigned int i = 0; i < n; ++i)
      {
        const double angle = 2 * M_PI * i / n;
        mesh.points.push_back({std::cos(angle), std::sin(angle), 0});
        mesh.cells.push_back({0, 1 + i, 1 + (i + 1) % n});
      }
    return mesh;
  }

  // The unit cube as six tetrahedra around its diagonal (Kuhn): vertex index = x + 2y + 4z.
  DeformedMesh unit_cube()
  {
    DeformedMesh mesh{3, {}, {}};
    for (unsigned int v = 0; v < 8; ++v)
      mesh.points.push_back({double(v & 1), double((v >> 1) & 1), double((v >> 2) & 1)});
    for (const auto &[a, b] : {std::pair{1u, 2u}, {1u, 4u}, {2u, 1u}, {2u, 4u}, {4u, 1u}, {4u, 2u}})
      mesh.cells.push_back({0, a, a + b, 7});
    return mesh;
  }

  double hausdorff(const DeformedMesh &a, const DeformedMesh &b)
  {
    return hausdorff_distance(extract_boundary(a), extract_boundary(b));
  }
} // namespace

TEST(CompareBoundary, KeepsFacetsOfExactlyOneCell)
{
  EXPECT_EQ(extract_boundary(square(0, 0, 1)).facets.size(), 4u);
  EXPECT_EQ(extract_boundary(circle_polygon(12)).facets.size(), 12u);
  EXPECT_EQ(extract_boundary(unit_cube()).facets.size(), 12u);
  const DeformedMesh rod{1, {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}}, {{0, 1}, {1, 2}}};
  const Boundary     ends = extract_boundary(rod);
  ASSERT_EQ(ends.facets.size(), 2u);
  EXPECT_EQ(ends.facets[0][0] + ends.facets[1][0], 2u);
}

TEST(CompareHausdorff, OffsetSquares)
{
  EXPECT_NEAR(hausdorff(square(0, 0, 1), square(0.3, 0, 1)), 0.3, 1e-12);
}

TEST(CompareHausdorff, SquareScaledAboutItsCentre)
{
  // Scaling by 2 about (0.5, 0.5): every point of the small boundary is 0.5 from the large one,
  // but the large square's corners are 0.5 * sqrt(2) from the small square's corners.
  const Boundary small = extract_boundary(square(0, 0, 1)), large = extract_boundary(square(-0.5, -0.5, 2));
  EXPECT_NEAR(one_sided_distance(small, large), 0.5, 1e-12);
  EXPECT_NEAR(hausdorff_distance(small, large), 0.5 * std::sqrt(2.0), 1e-12);
}

TEST(CompareHausdorff, ShiftedCirclePolygon)
{
  const double d = 0.05;
  EXPECT_NEAR(hausdorff(circle_polygon(64), translated(circle_polygon(64), {d, 0, 0})), d, 0.02 * d);
}

TEST(CompareHausdorff, ShiftedCubeSurface)
{
  EXPECT_NEAR(hausdorff(unit_cube(), translated(unit_cube(), {0.25, 0, 0})), 0.25, 1e-12);
}

TEST(CompareHausdorff, SymmetricMaxOfOneSidedDistances)
{
  // [0.4, 0.6]^2 inside [0, 1]^2: the inner boundary is at most 0.4 from the outer one (edge
  // midpoints), the outer corners are 0.4 * sqrt(2) from the inner corners.
  const Boundary inner = extract_boundary(square(0.4, 0.4, 0.2)), outer = extract_boundary(square(0, 0, 1));
  EXPECT_NEAR(one_sided_distance(inner, outer), 0.4, 1e-12);
  EXPECT_NEAR(one_sided_distance(outer, inner), 0.4 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(hausdorff_distance(inner, outer), 0.4 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(hausdorff_distance(outer, inner), 0.4 * std::sqrt(2.0), 1e-12);
}

TEST(CompareHausdorff, RodEndPoints)
{
  const DeformedMesh a{1, {{0, 0, 0}, {1, 0, 0}}, {{0, 1}}}, b{1, {{0.1, 0, 0}, {1.3, 0, 0}}, {{0, 1}}};
  EXPECT_NEAR(hausdorff(a, b), 0.3, 1e-12);
}

TEST(CompareHausdorff, RejectsDifferentDimensions)
{
  EXPECT_THROW(hausdorff(square(0, 0, 1), unit_cube()), ritr::InputError);
}

TEST(CompareCentroid, IsAreaWeighted)
{
  // A fan from an off-centre interior node: the vertex mean would move, the centroid does not.
  DeformedMesh fan{2, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.2, 0.3, 0}}, {}};
  for (unsigned int i = 0; i < 4; ++i)
    fan.cells.push_back({4, i, (i + 1) % 4});
  const Point c = centroid(fan);
  EXPECT_NEAR(c[0], 0.5, 1e-14);
  EXPECT_NEAR(c[1], 0.5, 1e-14);
  const Point cube = centroid(unit_cube());
  EXPECT_NEAR(cube[2], 0.5, 1e-14);
}

namespace
{
  // A 2D mesh in the ASCII VTU layout of ritr's former hand-made writer (older runs).
  void write_ascii_vtu(const fs::path &file, const DeformedMesh &mesh)
  {
    std::ofstream out(file);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << mesh.points.size() << "\" NumberOfCells=\""
        << mesh.cells.size() << "\">\n"
        << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Point &p : mesh.points)
      out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const auto &c : mesh.cells)
      out << c[0] << ' ' << c[1] << ' ' << c[2] << " \n";
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < mesh.cells.size(); ++i)
      out << 3 * (i + 1) << '\n';
    out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < mesh.cells.size(); ++i)
      out << "5\n";
    out << "</DataArray>\n</Cells>\n<PointData>\n</PointData>\n<CellData>\n</CellData>\n</Piece>\n"
        << "</UnstructuredGrid>\n</VTKFile>\n";
  }

  // A run folder: the square shifted right by shift(t) at each frame time, solution.pvd, and a
  // log.csv with ritr's header whose energy is 10 + t (rows from the first step on, as ritr's).
  template <typename Shift>
  void write_run(const fs::path &dir, const std::vector<double> &times, const Shift &shift)
  {
    fs::create_directories(dir);
    std::ofstream pvd(dir / "solution.pvd"), log(dir / "log.csv");
    pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
    log << "step,time,n_vertices,energy,inner_newton_iterations,outer_iterations,wall_seconds\n";
    for (std::size_t i = 0; i < times.size(); ++i)
      {
        const std::string file = "solution-0000" + std::to_string(i) + ".vtu";
        write_ascii_vtu(dir / file, square(shift(times[i]), 0, 1));
        pvd << "<DataSet timestep=\"" << times[i] << "\" group=\"\" part=\"0\" file=\"" << file << "\"/>\n";
        if (i > 0)
          log << i << ',' << times[i] << ",4," << 10 + times[i] << ",3,0,0.01\n";
      }
    pvd << "</Collection>\n</VTKFile>\n";
  }

  fs::path fresh_directory(const std::string &name)
  {
    const fs::path dir = fs::temp_directory_path() / ("ritr_compare_test_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
  }

  double json_number(const std::string &json, const std::string &key)
  {
    std::smatch m;
    EXPECT_TRUE(std::regex_search(json, m, std::regex("\"" + key + "\": ([-0-9.e]+)"))) << key;
    return m.empty() ? NAN : std::stod(m[1]);
  }

  // Message of the InputError that `f` throws, empty if it throws none.
  template <typename F>
  std::string input_error(const F &f)
  {
    try
      {
        f();
      }
    catch (const ritr::InputError &e)
      {
        return e.what();
      }
    return "";
  }
} // namespace

TEST(CompareReader, ReadsCompressedAppendedVtuWrittenByVtk)
{
  const fs::path               file = fresh_directory("binary") / "tet.vtu";
  vtkNew<vtkPoints>            points;
  vtkNew<vtkUnstructuredGrid>  grid;
  const DeformedMesh           cube = unit_cube();
  for (const Point &p : cube.points)
    points->InsertNextPoint(p.data());
  grid->SetPoints(points);
  for (const auto &c : cube.cells)
    {
      const vtkIdType ids[4] = {c[0], c[1], c[2], c[3]};
      grid->InsertNextCell(VTK_TETRA, 4, ids);
    }
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(grid);
  writer->SetFileName(file.c_str());
  writer->SetDataModeToAppended();
  writer->SetCompressorTypeToZLib();
  ASSERT_EQ(writer->Write(), 1);

  const DeformedMesh read = read_deformed_mesh(file);
  EXPECT_EQ(read.dim, 3u);
  EXPECT_EQ(read.points, cube.points);
  EXPECT_EQ(read.cells, cube.cells);
}

TEST(CompareRuns, PairsFramesByTimeAndWritesJson)
{
  const fs::path root = fresh_directory("runs");
  // B has an extra frame (0.15) and writes 0.2 with a rounding difference; A's 0.3 has no partner.
  write_run(root / "a", {0.0, 0.1, 0.2, 0.3}, [](double) { return 0.0; });
  write_run(root / "b", {0.0, 0.1, 0.15, 0.2000001}, [](double t) { return t; });
  fs::remove(root / "b" / "log.csv"); // energies of B unknown

  std::ostringstream json;
  write_json(json, compare_runs(root / "a", root / "b"));
  const std::string s = json.str();
  EXPECT_EQ(json_number(s, "frames"), 3);
  // Files carry six significant digits, as ritr's, so B's last square sits at x = 0.2.
  EXPECT_NEAR(json_number(s, "max_hausdorff"), 0.2, 1e-12);
  EXPECT_NEAR(json_number(s, "mean_hausdorff"), 0.1, 1e-12);
  EXPECT_NEAR(json_number(s, "centroid_distance_mean"), 0.1, 1e-12);
  EXPECT_NE(s.find("{\"time\": 0, \"hausdorff\": 0, \"energy_a\": null, \"energy_b\": null"), std::string::npos) << s;
  EXPECT_NE(s.find("{\"time\": 0.1, \"hausdorff\": 0.1, \"energy_a\": 10.1, \"energy_b\": null"), std::string::npos)
    << s;
  EXPECT_EQ(s.find("\"time\": 0.3"), std::string::npos) << s;
}

TEST(CompareRuns, BadInputNamesTheFile)
{
  const fs::path root = fresh_directory("bad");
  EXPECT_NE(input_error([&] { compare_runs(root / "missing", root / "missing"); }).find("missing"), std::string::npos);

  fs::create_directories(root / "empty");
  EXPECT_NE(input_error([&] { compare_runs(root / "empty", root / "empty"); }).find("solution.pvd"),
            std::string::npos);

  write_run(root / "a", {0.0, 0.1}, [](double) { return 0.0; });
  write_run(root / "late", {0.5}, [](double) { return 0.0; });
  EXPECT_NE(input_error([&] { compare_runs(root / "a", root / "late"); }).find("no frame times in common"),
            std::string::npos);

  std::ofstream(root / "a" / "solution-00001.vtu") << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Unstr";
  EXPECT_NE(input_error([&] { compare_runs(root / "a", root / "a"); }).find("solution-00001.vtu"),
            std::string::npos);

  std::ofstream(root / "a" / "log.csv") << "step,t,e\n1,0.1,3\n";
  EXPECT_NE(input_error([&] { EnergyLog log(root / "a" / "log.csv"); }).find("'time'"), std::string::npos);
}

TEST(CompareRuns, ExecutableExitsWithTwoAndOneLine)
{
  const auto r = ritr::test_support::run_command(std::string(RITR_COMPARE_BINARY) + " /nonexistent/a /nonexistent/b");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find("/nonexistent/a"), std::string::npos) << r.output;
}
