#pragma once
// How the work of a run is shared among MPI processes. Every process keeps the whole mesh and
// the whole state, as deal.II's parallel::shared triangulation keeps the whole mesh: what is
// split is the work. Each process assembles the cells and the contact stencils it owns; the
// Newton matrix's rows of the nodes it owns are its part of the distributed Trilinos matrix;
// values, gradients, CCD step bounds and distances are reduced over the processes, so that
// every process takes the same decisions and the same Newton steps. A serial run is one
// process that owns everything and makes no MPI call.
#include <Eigen/Core>

#include <mpi.h>

#include <array>
#include <vector>

namespace ritr
{
  namespace contact
  {
    struct Candidate;
  }

  class WorkShare
  {
  public:
    WorkShare() = default;  // serial: this process alone, without MPI
    // The processes of `communicator` (MPI initialised), started by an MPI launcher: a
    // shared run, even on one process (Trilinos then solves on that one).
    explicit WorkShare(MPI_Comm communicator);

    MPI_Comm     communicator() const { return communicator_; }
    unsigned int rank() const { return rank_; }
    unsigned int size() const { return size_; }
    bool         distributed() const { return shared_; }
    // The process that writes the run's files and prints its progress.
    bool         is_writer() const { return rank_ == 0; }

    // Over all processes (a serial run returns its argument). Every process must call them
    // in the same order: they are collective.
    double sum(double value) const;
    void   sum(Eigen::VectorXd &values) const;  // in place, entry by entry
    double min(double value) const;
    bool   all(bool value) const;
    // rank 0's value on every process.
    bool   from_writer(bool value) const;
    // Every process's value, in rank order, on every process.
    std::vector<double> values_of_all(double value) const;

    // Splits the nodes of a mesh with these cells among the processes (METIS, through
    // deal.II, on the graph of nodes that share a cell); a cell belongs to the owner of most
    // of its nodes (ties: the owner of its first node). One process owns everything.
    template <std::size_t n_vertices>
    void partition(const std::vector<std::array<unsigned int, n_vertices>> &cells, unsigned int n_nodes);

    unsigned int node_owner(const unsigned int node) const { return node_owner_.empty() ? 0 : node_owner_[node]; }
    // The owner of a state entry of a body node (entry i*dim + k of node i), and its component k.
    unsigned int entry_owner(const unsigned int entry) const { return node_owner(entry / dim_); }
    unsigned int entry_component(const unsigned int entry) const { return entry % dim_; }
    unsigned int dim() const { return dim_; }
    bool         owns_cell(const unsigned int cell) const { return cell_owner_.empty() || cell_owner_[cell] == rank_; }
    // A contact candidate belongs to one process by a hash of its primitives: the surface is
    // small, so the stencils are spread evenly rather than by their nodes' owners.
    bool         owns(const contact::Candidate &candidate) const;

  private:
    MPI_Comm                  communicator_ = MPI_COMM_SELF;
    bool                      shared_ = false;
    unsigned int              rank_ = 0, size_ = 1;
    unsigned int              dim_  = 1;  // of the partitioned mesh
    std::vector<unsigned int> node_owner_, cell_owner_;  // empty: serial
  };
} // namespace ritr
