#include <ritr/contact/broad_phase.h>
#include <ritr/parallel/work_share.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <algorithm>

namespace ritr
{
  WorkShare::WorkShare(MPI_Comm communicator)
    : communicator_(communicator)
    , shared_(true)
  {
    int rank = 0, size = 1;
    MPI_Comm_rank(communicator, &rank);
    MPI_Comm_size(communicator, &size);
    rank_ = rank;
    size_ = size;
  }

  double WorkShare::sum(double value) const
  {
    if (distributed())
      MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_SUM, communicator_);
    return value;
  }

  void WorkShare::sum(Eigen::VectorXd &values) const
  {
    if (distributed())
      MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM, communicator_);
  }

  double WorkShare::min(double value) const
  {
    if (distributed())
      MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MIN, communicator_);
    return value;
  }

  bool WorkShare::all(const bool value) const
  {
    int v = value ? 1 : 0;
    if (distributed())
      MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT, MPI_MIN, communicator_);
    return v != 0;
  }

  bool WorkShare::from_writer(const bool value) const
  {
    int v = value ? 1 : 0;
    if (distributed())
      MPI_Bcast(&v, 1, MPI_INT, 0, communicator_);
    return v != 0;
  }

  std::vector<double> WorkShare::values_of_all(const double value) const
  {
    std::vector<double> values(size_, value);
    if (distributed())
      MPI_Allgather(&value, 1, MPI_DOUBLE, values.data(), 1, MPI_DOUBLE, communicator_);
    return values;
  }

  template <std::size_t n_vertices>
  void WorkShare::partition(const std::vector<std::array<unsigned int, n_vertices>> &cells, const unsigned int n_nodes)
  {
    node_owner_.clear();
    cell_owner_.clear();
    dim_ = n_vertices - 1;
    if (size_ == 1)
      return;
    dealii::DynamicSparsityPattern graph(n_nodes, n_nodes);
    for (const auto &cell : cells)
      for (const unsigned int a : cell)
        for (const unsigned int b : cell)
          if (a != b)
            graph.add(a, b);
    dealii::SparsityPattern pattern;
    pattern.copy_from(graph);
    // Every process partitions the same graph with the same (deterministic) METIS call, so
    // they agree on the owners without communicating.
    node_owner_.resize(n_nodes);
    dealii::SparsityTools::partition(pattern, size_, node_owner_, dealii::SparsityTools::Partitioner::metis);
    cell_owner_.resize(cells.size());
    std::vector<unsigned int> votes(size_);
    for (std::size_t c = 0; c < cells.size(); ++c)
      {
        std::fill(votes.begin(), votes.end(), 0u);
        for (const unsigned int n : cells[c])
          ++votes[node_owner_[n]];
        unsigned int owner = node_owner_[cells[c][0]];
        for (unsigned int r = 0; r < size_; ++r)
          if (votes[r] > votes[owner])
            owner = r;
        cell_owner_[c] = owner;
      }
  }

  bool WorkShare::owns(const contact::Candidate &candidate) const
  {
    if (size_ == 1)
      return true;
    const std::uint64_t key = (static_cast<std::uint64_t>(candidate.kind) * 2654435761u) ^
                              (static_cast<std::uint64_t>(candidate.first) * 40503u) ^
                              (static_cast<std::uint64_t>(candidate.second) * 2246822519u);
    return key % size_ == rank_;
  }

  template void WorkShare::partition(const std::vector<std::array<unsigned int, 2>> &, unsigned int);
  template void WorkShare::partition(const std::vector<std::array<unsigned int, 3>> &, unsigned int);
  template void WorkShare::partition(const std::vector<std::array<unsigned int, 4>> &, unsigned int);
} // namespace ritr
