#pragma once
// Small meshes for unit tests: a box made by deal.II, with interior nodes jittered so that no
// element is special.
#include <ritr/mesh/mesh_builder.h>

#include <random>

namespace ritr::test_support
{
  template <int dim>
  SimplexMesh<dim> small_box_mesh(const unsigned int subdivisions = 2, const double jitter = 0.05,
                                  const unsigned int seed = 1)
  {
    BodyDescription body;
    body.shape        = dim == 1 ? "interval" : dim == 2 ? "rectangle" : "box";
    body.subdivisions = {subdivisions, subdivisions, subdivisions};
    SimplexMesh<dim> mesh = build_mesh<dim>({body});
    std::mt19937     rng(seed);
    std::uniform_real_distribution<double> d(-jitter, jitter);
    for (Eigen::Index i = 0; i < mesh.reference.size(); ++i)
      mesh.reference[i] += d(rng) / subdivisions;
    return mesh;
  }

  // A random smooth-ish deformation: stretch, shear, rotation and noise.
  inline Eigen::VectorXd deform(const Eigen::VectorXd &u, const int dim, const double noise,
                                const unsigned int seed = 2)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> d(-noise, noise);
    Eigen::VectorXd                        x = u;
    for (Eigen::Index i = 0; i < u.size(); i += dim)
      {
        x[i] = 1.1 * u[i] + (dim > 1 ? 0.2 * u[i + 1] : 0.0);
        if (dim > 1)
          x[i + 1] = 0.9 * u[i + 1] - 0.1 * u[i];
        for (int k = 0; k < dim; ++k)
          x[i + k] += d(rng);
      }
    return x;
  }
} // namespace ritr::test_support
