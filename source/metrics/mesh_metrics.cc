#include <ritr/metrics/mesh_metrics.h>

#include <Eigen/Geometry>

#include <sys/resource.h>

#include <cmath>

namespace ritr
{
  template <int dim>
  std::vector<double> cell_strains(const SimplexMesh<dim> &mesh, const Eigen::VectorXd &x,
                                   const Eigen::VectorXd &u)
  {
    std::vector<double> s(mesh.n_cells());
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      {
        const auto F = multiply<dim, double>(edge_matrix<dim, double>(cell_nodes<dim>(x, mesh.cells[c])),
                                             inverse<dim, double>(edge_matrix<dim, double>(cell_nodes<dim>(u, mesh.cells[c]))));
        double norm2 = 0;
        for (int i = 0; i < dim; ++i)
          for (int j = 0; j < dim; ++j)
            {
              double e = -(i == j ? 1.0 : 0.0);
              for (int k = 0; k < dim; ++k)
                e += F[k][i] * F[k][j];
              norm2 += e * e;
            }
        s[c] = 0.5 * std::sqrt(norm2);
      }
    return s;
  }

  template <int dim>
  std::vector<double> cell_qualities(const SimplexMesh<dim> &mesh, const Eigen::VectorXd &p)
  {
    std::vector<double> q(mesh.n_cells(), 1.0);
    if constexpr (dim > 1)
      {
        // Regular simplex with unit edges: measure sqrt(3)/4 (2D), sqrt(2)/12 (3D).
        const double regular = dim == 2 ? std::sqrt(3.0) / 4 : std::sqrt(2.0) / 12;
        const int    n_edges = dim == 2 ? 3 : 6;
        for (unsigned int c = 0; c < mesh.n_cells(); ++c)
          {
            const auto nodes = cell_nodes<dim>(p, mesh.cells[c]);
            double     sum   = 0;
            for (int a = 0; a <= dim; ++a)
              for (int b = a + 1; b <= dim; ++b)
                for (int k = 0; k < dim; ++k)
                  sum += (nodes[a][k] - nodes[b][k]) * (nodes[a][k] - nodes[b][k]);
            const double measure = simplex_measure<dim, double>(nodes);
            const double mean_edge2 = sum / n_edges;
            q[c] = measure <= 0 ? 0.0 : std::pow(measure / regular, 2.0 / dim) / mean_edge2;
          }
      }
    return q;
  }

  template <int dim>
  double min_deformed_jacobian(const SimplexMesh<dim> &mesh, const Eigen::VectorXd &x,
                               const Eigen::VectorXd &u)
  {
    double j = std::numeric_limits<double>::max();
    for (const auto &cell : mesh.cells)
      j = std::min(j, simplex_measure<dim, double>(cell_nodes<dim>(x, cell)) /
                        simplex_measure<dim, double>(cell_nodes<dim>(u, cell)));
    return j;
  }

  namespace
  {
    // Measure times outward unit normal of a boundary facet (oriented outward) at positions x.
    template <int dim>
    Vec<dim> facet_area_vector(const typename SimplexMesh<dim>::Facet &facet, const Eigen::VectorXd &x)
    {
      const auto node = [&](const int a) -> Vec<dim> { return x.segment<dim>(facet[a] * dim); };
      if constexpr (dim == 2)
        {
          const Vec<2> t = node(1) - node(0);
          return Vec<2>(t[1], -t[0]);  // the boundary runs counter-clockwise
        }
      else
        return 0.5 * (node(1) - node(0)).cross(node(2) - node(0));
    }
  } // namespace

  template <int dim>
  Eigen::VectorXd nodal_contact_pressures(const SimplexMesh<dim> &mesh, const Eigen::VectorXd &x,
                                          const Eigen::VectorXd &contact_forces)
  {
    Eigen::VectorXd pressure = Eigen::VectorXd::Zero(mesh.n_nodes());
    if constexpr (dim == 1)
      {
        for (const auto &facet : mesh.boundary_facets)
          pressure[facet[0]] = std::abs(contact_forces[facet[0]]);
      }
    else
      {
        Eigen::VectorXd measure = Eigen::VectorXd::Zero(mesh.n_nodes());
        Eigen::VectorXd area_vector = Eigen::VectorXd::Zero(x.size());
        for (const auto &facet : mesh.boundary_facets)
          {
            const Vec<dim> a = facet_area_vector<dim>(facet, x);
            for (const unsigned int n : facet)
              {
                measure[n] += a.norm() / dim;
                area_vector.segment<dim>(n * dim) += a;
              }
          }
        for (unsigned int n = 0; n < mesh.n_nodes(); ++n)
          if (measure[n] > 0)
            {
              const Vec<dim> normal = area_vector.segment<dim>(n * dim).normalized();
              pressure[n] = -normal.dot(contact_forces.segment<dim>(n * dim)) / measure[n];
            }
      }
    return pressure;
  }

  long peak_rss_bytes()
  {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss * 1024L;  // Linux reports kilobytes
  }

  template <int dim>
  double bounding_box_diagonal(const Eigen::VectorXd &p)
  {
    double diagonal2 = 0;
    for (int k = 0; k < dim; ++k)
      {
        const auto coordinates = Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<dim>>(p.data() + k, p.size() / dim);
        diagonal2 += std::pow(coordinates.maxCoeff() - coordinates.minCoeff(), 2);
      }
    return std::sqrt(diagonal2);
  }

  template double bounding_box_diagonal<1>(const Eigen::VectorXd &);
  template double bounding_box_diagonal<2>(const Eigen::VectorXd &);
  template double bounding_box_diagonal<3>(const Eigen::VectorXd &);
  template std::vector<double> cell_strains<1>(const SimplexMesh<1> &, const Eigen::VectorXd &, const Eigen::VectorXd &);
  template std::vector<double> cell_strains<2>(const SimplexMesh<2> &, const Eigen::VectorXd &, const Eigen::VectorXd &);
  template std::vector<double> cell_strains<3>(const SimplexMesh<3> &, const Eigen::VectorXd &, const Eigen::VectorXd &);
  template std::vector<double> cell_qualities<1>(const SimplexMesh<1> &, const Eigen::VectorXd &);
  template std::vector<double> cell_qualities<2>(const SimplexMesh<2> &, const Eigen::VectorXd &);
  template std::vector<double> cell_qualities<3>(const SimplexMesh<3> &, const Eigen::VectorXd &);
  template Eigen::VectorXd nodal_contact_pressures<1>(const SimplexMesh<1> &, const Eigen::VectorXd &,
                                                      const Eigen::VectorXd &);
  template Eigen::VectorXd nodal_contact_pressures<2>(const SimplexMesh<2> &, const Eigen::VectorXd &,
                                                      const Eigen::VectorXd &);
  template Eigen::VectorXd nodal_contact_pressures<3>(const SimplexMesh<3> &, const Eigen::VectorXd &,
                                                      const Eigen::VectorXd &);
  template double min_deformed_jacobian<1>(const SimplexMesh<1> &, const Eigen::VectorXd &, const Eigen::VectorXd &);
  template double min_deformed_jacobian<2>(const SimplexMesh<2> &, const Eigen::VectorXd &, const Eigen::VectorXd &);
  template double min_deformed_jacobian<3>(const SimplexMesh<3> &, const Eigen::VectorXd &, const Eigen::VectorXd &);
} // namespace ritr
