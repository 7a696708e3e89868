#pragma once
// The L2 transfer between the start-of-step ("old") mesh (u_old, cells) and a candidate
// mesh (u, cells) with the same connectivity (paper sections 5.1-5.2):
//
//   A_t(u)_pq = int psi_p^u psi_q^t,   pi_t(y, u) = Mbar(u)^{-1} A_t(u) y,
//   b(x, y, u) = x^T (A_t(u) (x) I_dim) y,
//
// with x a nodal vector field on the candidate mesh and y one on the old mesh (flat,
// node-major: node i component k at i*dim + k).
//
// Two ways to integrate A_t (TransferIntegration):
//
// exact (triangles only): on the intersection of the two meshes. Each candidate cell is
// clipped by the old cells it overlaps and the quadratic integrand is integrated exactly on
// the overlap polygons (triangle_overlap.h), with dual numbers for the derivatives in u. A_t
// is then C1 in u: moving a node moves the polygons' vertices, and the derivatives include
// the old field's change of slope across old edges inside the candidate cell. Candidate c
// integrates the old field of its own start cell c, extended linearly, over the whole cell,
// and adds on its overlap with every other old cell o the difference of o's field and c's.
// That difference vanishes on the lines o shares with c, where the slivers are: a node the
// optimiser barely moves leaves a sliver of width w along an old edge, whose split between
// the two old cells has second derivatives ~1/w that cancel only in their sum (with the
// fields themselves, 1e-16/w^2 of error: the Hessian was garbage below w ~ 1e-8). Parts of a
// candidate cell outside the old domain take the extension of cell c's field.
//
// quadrature: on the candidate cells only, with a fixed simplex rule whose points are
// located in the old mesh once per candidate (set_candidate). With the located old cell o
// held fixed, the integrand w det J_c(u) lambda_a mu_b(X(u)) is smooth in u: X is linear in
// the candidate cell's nodes, mu is affine in X and det J is a polynomial. All derivatives
// below are of that fixed-assignment integrand, derived by hand (no AD): with
//   phi_q = s_q . Y_q,  s_q = sum_a lambda_a x_a,  Y_q = K_o X_q + k_o = sum_b mu_b y_{o[b]},
// a cell contributes J Phi with Phi = sum_q w_q phi_q, and phi_q is linear in u_c, so
//   d(J Phi)/du   = Phi dJ + J V,                 V_(a,k) = sum_q w_q lambda_a (K_o^T s_q)_k
//   d2(J Phi)/du2 = Phi d2J + dJ V^T + V dJ^T.
//
// Candidate cells must be positively oriented (det J > 0): det J is used without abs().
//
// Typical use per time step: set_old_mesh(u_t) once; then for each trial mesh u of the
// r-ITR optimiser set_candidate(u) and evaluate. Evaluations run in parallel over candidate
// cells (TBB) and are deterministic (fixed summation order).
#include <ritr/transfer/old_mesh_locator.h>
#include <ritr/transfer/transfer_integration.h>
#include <ritr/common/simplex_quadrature.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <vector>

namespace ritr::transfer
{
  template <int dim>
  class TransferOperator
  {
  public:
    static constexpr int n_cell_dofs = dim * (dim + 1); // u (or x) entries of one cell

    using Cell         = std::array<unsigned int, dim + 1>;
    using Triplet      = Eigen::Triplet<double>;
    using SparseMatrix = Eigen::SparseMatrix<double>;

    // Throws std::invalid_argument if the rule is malformed (see check_rule) or exact
    // integration is asked for outside 2D. The rule is unused with exact integration.
    TransferOperator(std::vector<Cell> cells, SimplexQuadrature<dim> quadrature,
                     TransferIntegration integration = TransferIntegration::quadrature);

    // Builds the old-mesh locator; invalidates the candidate.
    void set_old_mesh(const Eigen::VectorXd &u_old, double tolerance = 1e-12);

    // Locates every quadrature point of the candidate mesh u in the old mesh (exact
    // integration: finds the old cells each candidate cell may overlap); all evaluations
    // below refer to this u and this assignment until the next call.
    void set_candidate(const Eigen::VectorXd &u);

    unsigned int                  n_nodes() const { return n_nodes_; }
    unsigned int                  n_cells() const { return cells_.size(); }
    const std::vector<Cell>      &cells() const { return cells_; }
    const SimplexQuadrature<dim> &quadrature() const { return quadrature_; }
    const OldMeshLocator<dim>    &locator() const { return locator_; }
    const Eigen::VectorXd        &candidate() const { return u_; }
    TransferIntegration           integration() const { return integration_; }

    // Quadrature integration only (empty and 0 with exact integration).
    // Old cell of quadrature point q of candidate cell c, at index c * quadrature().size() + q.
    const std::vector<int> &located_cells() const { return located_; }
    // Number of quadrature points found outside the old domain (linear extension used).
    unsigned int n_outside() const { return n_outside_; }

    // A_t(u), n_nodes x n_nodes (scalar; the vector-field operator is A (x) I_dim).
    SparseMatrix transfer_matrix() const;

    // Consistent P1 mass matrix of the candidate mesh with unit density (exact).
    SparseMatrix mass_matrix() const;

    // b(x, y, u).
    double value(const Eigen::VectorXd &x, const Eigen::VectorXd &y) const;

    // db/dx = (A (x) I) y, a candidate-mesh field.
    Eigen::VectorXd gradient_x(const Eigen::VectorXd &y) const;

    // db/du, size n_nodes * dim.
    Eigen::VectorXd gradient_u(const Eigen::VectorXd &x, const Eigen::VectorXd &y) const;

    // Appends scale * d2b/du2 as triplets from per-cell blocks of size n_cell_dofs. With
    // project_psd each scaled block is projected onto the PSD cone first (so pass the sign
    // and weight the term has in the objective as `scale`).
    void add_hessian_u(const Eigen::VectorXd &x, const Eigen::VectorXd &y, double scale,
                       bool project_psd, std::vector<Triplet> &triplets) const;
    SparseMatrix hessian_u(const Eigen::VectorXd &x, const Eigen::VectorXd &y,
                           bool project_psd = false) const;

    // Appends scale * (d2b/du2 + d2b/dxdu + d2b/dudx) per cell: the u-Hessian along moves that
    // carry x with u (x - u fixed; d2b/dx2 = 0), optionally projected per cell.
    void add_hessian_following(const Eigen::VectorXd &x, const Eigen::VectorXd &y, double scale,
                               bool project_psd, std::vector<Triplet> &triplets) const;

    // All of the above that an outer iteration needs, from one evaluation per cell: adds
    // scale * db/du to gu, appends scale * d2b/du2 (following: the following Hessian) to huu
    // and, unless hxu is null, scale * d2b/dxdu to it.
    void add_reference_derivatives(const Eigen::VectorXd &x, const Eigen::VectorXd &y, double scale, bool following,
                                   Eigen::VectorXd &gu, std::vector<Triplet> &huu, std::vector<Triplet> *hxu) const;

    // Appends scale * d2b/dx du: rows in x numbering, columns in u numbering.
    void add_hessian_xu(const Eigen::VectorXd &x, const Eigen::VectorXd &y, double scale,
                        std::vector<Triplet> &triplets) const;
    SparseMatrix hessian_xu(const Eigen::VectorXd &x, const Eigen::VectorXd &y) const;

    // pi_t(y, u) = Mbar(u)^{-1} A_t(u) y for an old-mesh nodal field y with any number of
    // components (y.size() a multiple of n_nodes, node-major).
    Eigen::VectorXd project(const Eigen::VectorXd &y) const;
    // set_candidate(u), then project(y).
    Eigen::VectorXd project(const Eigen::VectorXd &y, const Eigen::VectorXd &u);

  private:
    // Sums per-cell vectors (n_cell_dofs entries per cell, in cell order) into nodal numbering.
    Eigen::VectorXd scatter_cell_vectors(const std::vector<double> &local) const;
    // Appends one n_cell_dofs x n_cell_dofs block per cell, block_of_cell(c), in nodal numbering.
    template <typename BlockOfCell>
    void append_cell_blocks(std::vector<Triplet> &triplets, const BlockOfCell &block_of_cell) const;
    struct OldField; // per old cell: Y(X) = K X + k for the current y
    struct CellTerms;
    std::vector<OldField> old_field(const Eigen::VectorXd &y) const;
    template <bool value, bool grad_u, bool hess_u, bool grad_x, bool mixed>
    void cell_terms(unsigned int c, const Eigen::VectorXd *x,
                    const std::vector<OldField> &field, CellTerms &terms) const;
    // Exact integration (exact_transfer.cc): value (x given) and grad_x in plain arithmetic;
    // with grad_u alone first-order dual numbers, else every entry of CellTerms with
    // second-order ones.
    void exact_cell_values(unsigned int c, const Eigen::VectorXd *x, const std::vector<OldField> &field,
                           CellTerms &terms) const;
    void exact_cell_derivatives(unsigned int c, const Eigen::VectorXd &x, const std::vector<OldField> &field,
                                CellTerms &terms) const;
    // value, grad_x and grad_u only, with first-order dual numbers (first-order outer solves).
    void exact_cell_gradient(unsigned int c, const Eigen::VectorXd &x, const std::vector<OldField> &field,
                             CellTerms &terms) const;
    SparseMatrix exact_transfer_matrix() const;
    void         find_overlaps();  // overlaps_ of the current candidate
    void check_ready(const char *what) const;
    void check_field(const Eigen::VectorXd &v, const char *name) const;

    std::vector<Cell>      cells_;
    SimplexQuadrature<dim> quadrature_;
    TransferIntegration    integration_;
    unsigned int           n_nodes_ = 0;
    OldMeshLocator<dim>    locator_;
    bool                   has_old_mesh_ = false;

    Eigen::VectorXd          u_;
    bool                     has_candidate_ = false;
    std::vector<int>         located_;
    std::vector<std::size_t> block_offsets_; // prefix sums of distinct old cells per cell
    unsigned int             n_outside_ = 0;
    std::vector<std::vector<int>> overlaps_;  // exact: old cells candidate c's clipping overlaps
  };
} // namespace ritr::transfer
