// The outputs of a run (the output contract of the design notes): VTU/PVD files, log.csv,
// summary.json, and the run's ownership of its output directory.
#include <ritr/common/atomic_file.h>
#include <ritr/common/input_error.h>
#include <ritr/common/wall_clock.h>
#include <ritr/elasticity/stress.h>
#include <ritr/metrics/mesh_metrics.h>
#include <ritr/output/checkpoint.h>
#include <ritr/output/run_directory.h>
#include <ritr/output/vtk_files.h>
#include <ritr/terms/contact_barrier_term.h>
#include <ritr/time/simulation.h>

#include <array>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

namespace ritr
{
  namespace
  {

    std::string json_string(const std::string &text)
    {
      std::ostringstream s;
      s << '"';
      for (const char c : text)
        if (c == '"' || c == '\\')
          s << '\\' << c;
        else if (static_cast<unsigned char>(c) < 0x20)
          s << "\\u" << std::hex << std::setw(4) << std::setfill('0') << int(c) << std::dec;
        else
          s << c;
      s << '"';
      return s.str();
    }
  } // namespace

  template <int dim>
  void Simulation<dim>::write_step_output(const unsigned int step)
  {
    const Eigen::VectorXd forces = contact_forces();  // by every process of a shared run
    if (!outputs_)
      return;
    RunOutputs &out = *outputs_;
    const auto dir = out.directory;
    // Writes STEM-NNNNN.vtu and lists it in its collection; the time goes to output_seconds.
    const auto write_piece = [&](const std::string &stem, const VtuPiece &p, PvdCollection &collection) {
      ScopedTimer       timer(out.output_seconds);
      const std::string file = numbered_output(stem, step, ".vtu");
      write_vtu((dir / file).string(), p);
      collection.add(time_, file);
    };

    VtuPiece piece;
    for (const auto &cell : mesh_.cells)
      piece.cells.emplace_back(cell.begin(), cell.end());
    const auto vector_field = [&](const std::string &name, const Eigen::VectorXd &v) {
      return VtuField{name, 3, pad_to_3d(v, dim)};
    };
    const auto scalar_field = [](const std::string &name, const std::vector<double> &v) {
      return VtuField{name, 1, Eigen::Map<const Eigen::VectorXd>(v.data(), v.size())};
    };
    piece.point_data = {vector_field("displacement", x_ - u_), vector_field("velocity", v_),
                        vector_field("reference_position", u_), vector_field("contact_force", forces),
                        VtuField{"contact_pressure", 1, nodal_contact_pressures(mesh_, x_, forces)}};
    const std::vector<double> material_ids(mesh_.cell_material.begin(), mesh_.cell_material.end());
    piece.cell_data = {scalar_field("strain", cell_strains(mesh_, x_, u_)),
                       scalar_field("von_mises_stress", cell_von_mises_stresses(materials(), x_, u_)),
                       scalar_field("material_id", material_ids),
                       scalar_field("element_quality", cell_qualities(mesh_, u_))};

    const auto as_points = [&](const Eigen::VectorXd &p) {
      const Eigen::VectorXd padded = pad_to_3d(p, dim);
      return Eigen::MatrixXd(Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
        padded.data(), padded.size() / 3, 3));
    };
    piece.points = as_points(x_);
    write_piece("solution", piece, out.solution);
    piece.points = as_points(u_);
    write_piece("reference", piece, out.reference);

    if (!obstacles_.empty())
      {
        VtuPiece     obstacle_piece;
        obstacle_piece.points = as_points(obstacle_positions_);
        unsigned int offset   = 0;
        for (const auto &o : obstacles_)
          {
            if constexpr (dim == 1)
              obstacle_piece.cells.push_back({offset});
            for (const auto &e : o.edges)
              obstacle_piece.cells.push_back({offset + e[0], offset + e[1]});
            for (const auto &f : o.faces)
              obstacle_piece.cells.push_back({offset + f[0], offset + f[1], offset + f[2]});
            offset += o.rest_vertices.size();
          }
        write_piece("obstacles", obstacle_piece, out.obstacles);
      }

    if (scene_.write_nodal_csv)
      write_file_atomically((dir / numbered_output("nodes", step, ".csv")).string(), [&](std::ostream &s) {
        const char *axes = "xyz";
        s << "id";
        for (const char *q : {"u", "x", "v"})
          for (int k = 0; k < dim; ++k)
            s << ',' << q << '_' << axes[k];
        s << '\n';
        for (unsigned int i = 0; i < mesh_.n_nodes(); ++i)
          {
            s << i;
            for (const Eigen::VectorXd *q : {&u_, &x_, &v_})
              for (int k = 0; k < dim; ++k)
                s << ',' << (*q)[i * dim + k];
            s << '\n';
          }
      });
  }

  template <int dim>
  void Simulation<dim>::write_summary(const double total_seconds, const bool complete,
                                      const std::string &failure) const
  {
    unsigned int newton = 0, outer = 0, trials = 0;
    std::array<unsigned int, outer_stop_names.size()> stops{};
    double       inner_seconds = 0, transfer_seconds = 0, outer_seconds = 0, max_sliding = 0;
    for (const auto &r : history_)
      {
        newton += r.newton_iterations;
        outer += r.outer_iterations;
        trials += r.line_search_trials;
        inner_seconds += r.inner_seconds;
        transfer_seconds += r.transfer_seconds;
        outer_seconds += r.outer_solve_seconds;
        max_sliding = std::max(max_sliding, r.sliding_violation);
        if (r.outer_stop)
          ++stops[static_cast<std::size_t>(*r.outer_stop)];
      }
    // Collective: every process calls write_summary at the same points of the run.
    const std::vector<double> peak_rss = problem_->work_share.values_of_all(static_cast<double>(peak_rss_bytes()));
    if (!outputs_)
      return;
    write_file_atomically((outputs_->directory / "summary.json").string(), [&](std::ostream &s) {
      s << "{\n  \"complete\": " << (complete ? "true" : "false") << ",\n";
      if (!failure.empty())
        s << "  \"failure\": " << json_string(failure) << ",\n";
      s << "  \"scene\": " << json_string(scene_.parameter_file) << ",\n"
        << "  \"dimension\": " << dim << ",\n"
        << "  \"mode\": \"" << scene_.mode << "\",\n"
        << "  \"adaptivity\": " << (scene_.adaptivity.enabled ? "true" : "false") << ",\n"
        << "  \"steps\": " << history_.size() << ",\n"
        << "  \"n_vertices\": " << mesh_.n_nodes() << ",\n"
        << "  \"n_cells\": " << mesh_.n_cells() << ",\n"
        << "  \"mpi_ranks\": " << problem_->work_share.size() << ",\n"
        << "  \"total_wall_seconds\": " << total_seconds << ",\n"
        << "  \"wall_seconds_per_step\": " << total_seconds / std::max<std::size_t>(1, history_.size()) << ",\n"
        << "  \"linear_solve_seconds\": " << earlier_.linear_solve_seconds + newton_solver().seconds_in_linear_solves()
        << ",\n"
        << "  \"symbolic_factorizations\": "
        << earlier_.symbolic_factorizations + newton_solver().n_symbolic_analyses() << ",\n"
        << "  \"numeric_factorizations\": "
        << earlier_.numeric_factorizations + newton_solver().n_factorizations() << ",\n"
        << "  \"peak_rss_bytes\": " << *std::max_element(peak_rss.begin(), peak_rss.end()) << ",\n"
        << "  \"peak_rss_bytes_per_process\": [" << [&] {
             std::string list;
             for (const double bytes : peak_rss)
               list += (list.empty() ? "" : ", ") + std::to_string(static_cast<std::uint64_t>(bytes));
             return list;
           }() << "],\n"
        << "  \"final_energy\": " << (history_.empty() ? 0.0 : history_.back().energy) << ",\n"
        << [&] {
             // The last step's energy term by term (complete runs; see run_steps).
             std::string split;
             for (const auto &[name, value] : last_step_terms_)
               {
                 std::ostringstream v;
                 v << std::setprecision(17) << value;
                 split += (split.empty() ? "" : ", ") + json_string(name) + ": " + v.str();
               }
             return last_step_terms_.empty() ? std::string() : "  \"final_energy_terms\": {" + split + "},\n";
           }()
        << "  \"total_newton_iterations\": " << newton << ",\n"
        << "  \"total_outer_iterations\": " << outer << ",\n"
        << "  \"total_line_search_trials\": " << trials << ",\n"
        << "  \"outer_stops\": {" << [&] {
             std::string counts;
             for (const auto &[stop, name] : outer_stop_names)
               counts += (counts.empty() ? "\"" : ", \"") + std::string(name) +
                         "\": " + std::to_string(stops[static_cast<std::size_t>(stop)]);
             return counts;
           }() << "},\n"
        << "  \"inner_solve_seconds\": " << inner_seconds << ",\n"
        << "  \"transfer_seconds\": " << transfer_seconds << ",\n"
        << "  \"outer_solve_seconds\": " << outer_seconds << ",\n"
        << "  \"output_seconds\": " << outputs_->output_seconds << ",\n"
        << "  \"max_sliding_violation\": " << max_sliding << ",\n"
        << "  \"invariant_violations\": [";
      for (std::size_t i = 0; i < invariant_violations_.size(); ++i)
        s << (i ? ", " : "") << json_string(invariant_violations_[i]);
      s << "]\n}\n";
    });
  }

  template <int dim>
  void Simulation<dim>::log_newton_iteration(const NewtonIterationRecord &record, const Eigen::VectorXd &z)
  {
    // Collective in a shared run: every process computes it, the writer writes it.
    const double distance = terms_.has_contact() ? terms_.active_minimum_distance(z, terms_.candidates_at(z)) :
                                                   std::numeric_limits<double>::infinity();
    if (!outputs_)
      return;  // a simulation driven step by step (tests) writes no files
    if (logged_step_ != step_ + 1)
      logged_step_ = step_ + 1, logged_solve_ = 0;
    if (record.iteration == 0)
      ++logged_solve_;
    auto       &s       = outputs_->newton_log;
    const auto *barrier = terms_.template find<ContactBarrierTerm<dim>>();
    s << logged_step_ << ',' << logged_solve_ << ',' << record.iteration << ',' << std::setprecision(17)
      << record.energy << std::setprecision(6) << ',' << record.energy_change << ',' << record.predicted_decrease
      << ',' << record.step_norm << ',' << record.gradient_norm << ',' << record.ccd_bound << ',' << record.alpha
      << ',' << record.prescribed_moving << ',' << record.judged_by_gradient << ',' << record.hessian_shift << ','
      << record.exact_hessian << ','
      << (barrier ? barrier->stiffness() : 0.0) << ','
      << distance << ',' << record.trust_radius << ',' << record.cg_iterations << '\n';
  }

  template <int dim>
  bool Simulation<dim>::writes_frame(const unsigned int step) const
  {
    return step % scene_.output_every == 0 || step == scene_.n_steps();
  }

  template <int dim>
  double Simulation<dim>::wall_seconds() const
  {
    return earlier_.wall_seconds + seconds_since(start_);
  }

  template <int dim>
  void Simulation<dim>::create_outputs()
  {
    if (!is_writer())
      return;
    outputs_ = std::make_unique<RunOutputs>(scene_.output_directory);
    // Twelve digits: energies of refinement rungs are compared with each other, and six
    // digits (the stream default) hid differences of 1e-6 relative.
    outputs_->log << std::setprecision(12);
    outputs_->log << "step,time,n_vertices,energy,inner_newton_iterations,outer_iterations,line_search_trials,"
                     "initial_objective,sliding_violation,min_distance,min_reference_measure,"
                     "min_deformed_jacobian,inner_solve_seconds,transfer_seconds,outer_solve_seconds,"
                     "wall_seconds,outer_stop\n";
    outputs_->newton_log << "step,solve,iteration,energy,energy_change,predicted_decrease,step_norm,"
                            "gradient_norm,ccd_bound,alpha,prescribed_moving,judged_by_gradient,hessian_shift,exact_hessian,"
                            "barrier_stiffness,min_active_distance,trust_radius,cg_iterations\n";
  }

  template <int dim>
  void Simulation<dim>::append_log_row(const StepReport &r)
  {
    if (!outputs_)
      return;
    outputs_->log << r.step << ',' << r.time << ',' << mesh_.n_nodes() << ',' << r.energy << ','
                  << r.newton_iterations << ',' << r.outer_iterations << ',' << r.line_search_trials << ','
                  << r.initial_objective << ',' << r.sliding_violation << ',' << r.min_distance << ','
                  << r.min_reference_measure << ',' << r.min_deformed_jacobian << ',' << r.inner_seconds << ','
                  << r.transfer_seconds << ',' << r.outer_solve_seconds << ',' << r.wall_seconds << ','
                  << (r.outer_stop ? name_of(outer_stop_names, *r.outer_stop) : "") << '\n';
  }

  template <int dim>
  void Simulation<dim>::flush_logs() const
  {
    if (!outputs_)
      return;
    write_file_atomically((outputs_->directory / "log.csv").string(),
                          [&](std::ostream &s) { s << outputs_->log.str(); });
    if (scene_.solver.newton_log)
      write_file_atomically((outputs_->directory / "newton.csv").string(),
                            [&](std::ostream &s) { s << outputs_->newton_log.str(); });
  }

  template <int dim>
  void Simulation<dim>::claim_output_directory(const bool resuming)
  {
    if (claimed_)
      return;
    claimed_ = true;
    // In a shared run the writer claims the directory and tells the others whether it could;
    // they stop quietly with it (InputError without a text of its own: the writer says why).
    const WorkShare &share = problem_->work_share;
    if (!share.is_writer())
      {
        if (!share.from_writer(true))
          throw InputError("");
        return;
      }
    try
      {
        claim_directory(resuming);
      }
    catch (const InputError &)
      {
        share.from_writer(false);
        throw;
      }
    share.from_writer(true);
  }

  template <int dim>
  void Simulation<dim>::claim_directory(const bool resuming)
  {
    namespace fs             = std::filesystem;
    const fs::path directory = scene_.output_directory;
    const auto     refuse    = [&](const std::string &what) {
      throw InputError(scene_.where("output directory") + ": '" + shortened(directory.string()) + "' " + what);
    };
    std::error_code ec;
    if (resuming)
      {
        // A resume creates nothing: without the directory there is no checkpoint.
        if (!fs::is_directory(directory, ec))
          throw no_checkpoint_error((directory / "checkpoint.bin").string());
      }
    else if (fs::create_directories(directory, ec); ec)
      refuse("cannot be created: " + ec.message());
    try
      {
        directory_lock_ = std::make_unique<OutputDirectoryLock>(directory);
      }
    catch (const std::runtime_error &e)
      {
        refuse(e.what());
      }
  }

  template <int dim>
  void Simulation<dim>::run()
  {
    // From here on the directory belongs to this run (the scene has been validated): its
    // summary says "complete": false until the end, and nothing of a previous run stays.
    claim_output_directory(false);
    create_outputs();
    write_summary(0, false);
    if (outputs_)
      remove_previous_outputs(outputs_->directory);
    flush_logs();
    write_step_output(0);
    start_ = std::chrono::steady_clock::now();
    write_checkpoint();
    run_steps();
  }

  template <int dim>
  void Simulation<dim>::run_steps()
  {
    const unsigned int n_steps    = scene_.n_steps();
    const unsigned int first_step = step_;
    try
      {
        while (step_ < n_steps)
          {
            const StepReport r = advance();
            // The final energy term by term while the terms hold the last step's context; the
            // last checkpoint keeps it for a run resumed after it.
            if (step_ == n_steps)
              {
                const Eigen::VectorXd z = state();
                last_step_terms_        = terms_.values(z, terms_.candidates_at(z));
              }
            append_log_row(r);
            flush_logs();
            // The checkpoint comes last: every file it accounts for is in place before it.
            if (writes_frame(step_))
              {
                write_step_output(step_);
                write_checkpoint();
              }
            const double elapsed = seconds_since(start_);
            if (is_writer())
              std::cout << "step " << r.step << '/' << n_steps << "  t=" << std::setprecision(4) << r.time
                      << "  newton=" << r.newton_iterations << "  E=" << std::setprecision(6) << r.energy
                      << "  elapsed=" << std::setprecision(3) << wall_seconds() << "s  eta="
                      << elapsed / (r.step - first_step) * (n_steps - r.step) << "s" << std::endl;
          }
      }
    catch (const ConvergenceError &e)
      {
        flush_logs();  // newton.csv then shows the iterations of the failed step
        write_summary(wall_seconds(), false, e.what());
        throw;
      }
    catch (const InputError &e)
      {
        // An expression that is not finite at a later step's time (Problem::targets).
        write_summary(wall_seconds(), false, e.what());
        throw InputError(std::string(e.what()) + "; steps written so far are kept");
      }
    write_summary(wall_seconds(), true);
  }

  template class Simulation<1>;
  template class Simulation<2>;
  template class Simulation<3>;
} // namespace ritr
