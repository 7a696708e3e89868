#include <ritr/elasticity/cell_energy.h>
#include <ritr/elasticity/stress.h>

#include <cmath>

namespace ritr
{
  template <int dim>
  SmallMatrix<3, double> cauchy_stress(const Material &material, const SmallMatrix<dim, double> &F)
  {
    SmallMatrix<3, double> sigma{};
    if constexpr (dim == 1)
      sigma[0][0] = first_piola_stress<1>(material, F)[0][0];
    else
      {
        SmallMatrix<3, double> F3{};
        F3[2][2] = 1.0;
        for (int i = 0; i < dim; ++i)
          for (int j = 0; j < dim; ++j)
            F3[i][j] = F[i][j];
        // The 2D model uses the 3D Lame constants (plane strain), so the 3D law applies.
        const auto   P = first_piola_stress<3>(material, F3);
        const double J = determinant<3, double>(F3);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
              sigma[i][j] += P[i][k] * F3[j][k] / J;
      }
    return sigma;
  }

  double von_mises(const SmallMatrix<3, double> &sigma)
  {
    const double mean = (sigma[0][0] + sigma[1][1] + sigma[2][2]) / 3;
    double       s_s  = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        {
          // The symmetric part: sigma is symmetric up to round-off.
          const double s = 0.5 * (sigma[i][j] + sigma[j][i]) - (i == j ? mean : 0.0);
          s_s += s * s;
        }
    return std::sqrt(1.5 * s_s);
  }

  template <int dim>
  std::vector<double> cell_von_mises_stresses(const CellMaterials<dim> &materials, const Eigen::VectorXd &x,
                                              const Eigen::VectorXd &u)
  {
    const auto         &mesh = materials.mesh();
    std::vector<double> stresses(mesh.n_cells());
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      {
        const auto F = deformation_gradient<dim, double>(cell_nodes<dim>(x, mesh.cells[c]),
                                                         cell_nodes<dim>(u, mesh.cells[c]));
        stresses[c]  = von_mises(cauchy_stress<dim>(materials.of_cell(c), F));
      }
    return stresses;
  }

  template SmallMatrix<3, double> cauchy_stress<1>(const Material &, const SmallMatrix<1, double> &);
  template SmallMatrix<3, double> cauchy_stress<2>(const Material &, const SmallMatrix<2, double> &);
  template SmallMatrix<3, double> cauchy_stress<3>(const Material &, const SmallMatrix<3, double> &);
  template std::vector<double> cell_von_mises_stresses<1>(const CellMaterials<1> &, const Eigen::VectorXd &,
                                                          const Eigen::VectorXd &);
  template std::vector<double> cell_von_mises_stresses<2>(const CellMaterials<2> &, const Eigen::VectorXd &,
                                                          const Eigen::VectorXd &);
  template std::vector<double> cell_von_mises_stresses<3>(const CellMaterials<3> &, const Eigen::VectorXd &,
                                                          const Eigen::VectorXd &);
} // namespace ritr
