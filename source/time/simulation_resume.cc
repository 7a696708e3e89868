// Checkpoints and resuming: a run killed between two frames continues from the last
// checkpoint as if it had never stopped. The checkpoint holds what carries over from one
// step to the next -- the state (u, x, v, obstacle vertices), the step and time, the step
// reports and invariant violations that log.csv and summary.json are made of, and the run's
// totals. Nothing else does: every solver setting of a step (barrier stiffness, lagged
// friction, the transfer's old mesh) is initialised from the start-of-step state.
#include <ritr/common/input_error.h>
#include <ritr/common/wall_clock.h>
#include <ritr/output/checkpoint.h>
#include <ritr/output/run_directory.h>
#include <ritr/scene/parameters.h>
#include <ritr/time/simulation.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

namespace ritr
{
  namespace fs = std::filesystem;

  namespace
  {
    std::string read_text(const fs::path &file)
    {
      std::ifstream in(file, std::ios::binary);
      return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    }

    // The rows of a CSV file with a header whose first column is the step, up to `step`.
    std::string rows_up_to(const fs::path &file, const unsigned int step)
    {
      std::istringstream lines(read_text(file));
      std::string        line, rows;
      std::getline(lines, line);  // the header
      while (std::getline(lines, line) && !lines.eof())  // a last line without '\n' is torn
        {
          std::istringstream fields(line);
          unsigned long      row_step = 0;
          if (fields >> row_step && row_step <= step)
            rows += line + '\n';
        }
      return rows;
    }

    // The steps of the `solution-NNNNN.vtu` frames in `directory`.
    std::set<unsigned int> solution_frame_steps(const fs::path &directory)
    {
      std::set<unsigned int> steps;
      std::error_code        ec;
      for (const auto &entry : fs::directory_iterator(directory, ec))
        {
          const std::string name = entry.path().filename().string();
          const std::string prefix = "solution-", suffix = ".vtu";
          if (name.size() > prefix.size() + suffix.size() && name.rfind(prefix, 0) == 0 &&
              name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
            {
              const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
              if (digits.find_first_not_of("0123456789") == std::string::npos)
                steps.insert(static_cast<unsigned int>(std::stoul(digits)));
            }
        }
      return steps;
    }

    // The steps up to a checkpoint's `last_step` that have frames: the scene's
    // (`writes_frame`), the checkpoint's own (a checkpoint comes with a frame, at the last
    // step too, which a later end time makes a step in between) and those of the ends of a
    // run's earlier parts (in `directory`: the frames up to a checkpoint are).
    template <typename WritesFrame>
    std::vector<unsigned int> frame_steps(const unsigned int last_step, const fs::path &directory,
                                          const WritesFrame &writes_frame)
    {
      const std::set<unsigned int> earlier_ends = solution_frame_steps(directory);
      std::vector<unsigned int>    steps;
      for (unsigned int s = 0; s <= last_step; ++s)
        if (writes_frame(s) || s == last_step || earlier_ends.count(s))
          steps.push_back(s);
      return steps;
    }

    template <typename T>
    std::uint64_t hash_of(const std::vector<T> &v, const std::uint64_t hash)
    {
      return fnv1a(v.data(), v.size() * sizeof(T), hash);
    }

    std::uint64_t hash_of(const Eigen::VectorXd &v, const std::uint64_t hash)
    {
      return fnv1a(v.data(), v.size() * sizeof(double), hash);
    }

    // "Section/entry" -> value of a Scene::parameter_listing.
    std::map<std::string, std::string> entries_of(const std::string &listing)
    {
      const auto entries = listing_entries(listing);
      return {entries.begin(), entries.end()};
    }

    // The first entry, but for those that leave a run unchanged, whose value differs between
    // `scene_file`'s entries `here` and a checkpoint's `there`, with both values; empty if none.
    std::string entry_difference(const std::string &here, const std::string &there, const std::string &scene_file)
    {
      const auto here_entries = entries_of(here), there_entries = entries_of(there);
      const auto value        = [](const std::map<std::string, std::string> &entries, const std::string &name) {
        const auto e = entries.find(name);
        return e == entries.end() ? std::string("its default") : e->second;
      };
      std::set<std::string> names;
      for (const auto *entries : {&here_entries, &there_entries})
        for (const auto &[name, v] : *entries)
          names.insert(name);
      for (const auto &name : names)
        if (!leaves_the_run_unchanged(name) && value(here_entries, name) != value(there_entries, name))
          return name + " is " + value(here_entries, name) + " in " + scene_file + ", " +
                 value(there_entries, name) + " in the checkpoint's scene";
      return "";
    }
  } // namespace

  template <int dim>
  std::uint64_t Simulation<dim>::scene_fingerprint(const std::string &listing) const
  {
    // The entries set away from their defaults, as parsed (comments and layout do not count),
    // and what they produced from files the scene names (meshes, obstacles).
    std::uint64_t h = fnv1a(listing.data(), listing.size());
    h = hash_of(mesh_.cells, h);
    for (const Eigen::VectorXd *v : {&problem_->initial_reference, &problem_->initial_positions,
                                     &problem_->initial_velocity, &problem_->initial_obstacle_positions})
      h = hash_of(*v, h);
    return h;
  }

  template <int dim>
  void Simulation<dim>::write_checkpoint() const
  {
    if (!outputs_)
      return;
    ScopedTimer timer(outputs_->output_seconds);
    Checkpoint  c;
    c.dimension            = dim;
    c.scene_hash           = scene_hash_;
    c.scene_entries        = scene_.parameter_listing;
    c.step                 = step_;
    c.time                 = time_;
    c.u                    = u_;
    c.x                    = x_;
    c.v                    = v_;
    c.obstacle_positions   = obstacle_positions_;
    c.barrier_stiffness    = barrier_stiffness_;
    c.history              = history_;
    c.invariant_violations = invariant_violations_;
    c.final_energy_terms   = last_step_terms_;
    c.stepper_state        = stepper_->carried_state();
    c.wall_seconds         = wall_seconds();
    c.output_seconds       = outputs_->output_seconds;
    c.linear_solve_seconds = earlier_.linear_solve_seconds + newton_solver().seconds_in_linear_solves();
    c.symbolic_factorizations =
      earlier_.symbolic_factorizations + newton_solver().linear_solver().n_symbolic_analyses();
    c.numeric_factorizations = earlier_.numeric_factorizations + newton_solver().linear_solver().n_factorizations();
    ritr::write_checkpoint((outputs_->directory / "checkpoint.bin").string(), c);
  }

  template <int dim>
  std::vector<std::string> Simulation<dim>::frame_files(const unsigned int last_step) const
  {
    std::vector<std::string> files;
    const auto scene_frame = [&](const unsigned int s) { return writes_frame(s); };
    for (const unsigned int s : frame_steps(last_step, scene_.output_directory, scene_frame))
      {
        for (const char *stem : {"solution", "reference"})
          files.push_back(numbered_output(stem, s, ".vtu"));
        if (!obstacles_.empty())
          files.push_back(numbered_output("obstacles", s, ".vtu"));
        if (scene_.write_nodal_csv)
          files.push_back(numbered_output("nodes", s, ".csv"));
      }
    return files;
  }

  template <int dim>
  bool Simulation<dim>::resume()
  {
    // The directory is this process's before anything in it is read; everything is read and
    // checked before the first file is written.
    claim_output_directory(true);
    const fs::path    directory = scene_.output_directory;
    const std::string file      = (directory / "checkpoint.bin").string();
    const Checkpoint  c         = read_checkpoint(file);
    if (c.dimension != dim)
      throw InputError(file + ": is of a " + std::to_string(c.dimension) + "D run, " + scene_.parameter_file +
                       " is " + std::to_string(dim) + "D");
    // The same scene: the same entries, compared by value, so that a checkpoint of a ritr that
    // listed entries this one leaves out still resumes; and the same meshes and initial state,
    // by the checkpoint's fingerprint taken again with its own listing.
    if (const std::string entry = entry_difference(scene_.parameter_listing, c.scene_entries, scene_.parameter_file);
        !entry.empty())
      throw InputError(file + ": belongs to another scene (" + entry + ")");
    if (scene_fingerprint(c.scene_entries) != c.scene_hash)
      throw InputError(file + ": belongs to another scene (the meshes or initial state that " +
                       scene_.parameter_file + " gives differ)");
    const unsigned int n_steps = scene_.n_steps();
    if (c.u.size() != u_.size() || c.x.size() != x_.size() || c.v.size() != v_.size() ||
        c.obstacle_positions.size() != obstacle_positions_.size() || c.history.size() != c.step)
      throw InputError(file + ": is corrupted (its sizes do not match the scene)");
    // The end time is not part of the scene: a run goes on to a later one, not back.
    if (c.step > n_steps)
      {
        std::ostringstream why;
        why << file << ": is at step " << c.step << " (t = " << c.time << "), past the end time of "
            << scene_.parameter_file << " (" << scene_.end_time << ", step " << n_steps << ")";
        throw InputError(why.str());
      }
    if (c.time > scene_.end_time)
      throw InputError(file + ": is corrupted (its time is past the scene's end time)");
    try
      {
        stepper_->restore_carried_state(c.stepper_state);
      }
    catch (const std::invalid_argument &e)
      {
        throw InputError(file + ": is corrupted (" + e.what() + ")");
      }
    if (c.step == n_steps &&
        read_text(directory / "summary.json").find("\"complete\": true") != std::string::npos)
      return false;
    // The collections will list every frame up to the checkpoint: each must be there.
    for (const std::string &frame : frame_files(c.step))
      if (std::error_code ec; !fs::is_regular_file(directory / frame, ec))
        throw InputError((directory / frame).string() + ": is missing, and " + file +
                         " builds on it (run the scene without --resume to start over)");
    // newton.csv is the one output that cannot be rebuilt from the checkpoint.
    const std::string newton_rows = scene_.solver.newton_log ? rows_up_to(directory / "newton.csv", c.step) : "";

    u_                    = c.u;
    x_                    = c.x;
    v_                    = c.v;
    obstacle_positions_   = c.obstacle_positions;
    barrier_stiffness_    = c.barrier_stiffness;
    step_                 = c.step;
    time_                 = c.time;
    history_              = c.history;
    invariant_violations_ = c.invariant_violations;
    last_step_terms_      = c.final_energy_terms;
    earlier_.wall_seconds            = c.wall_seconds;
    earlier_.linear_solve_seconds    = c.linear_solve_seconds;
    earlier_.symbolic_factorizations = c.symbolic_factorizations;
    earlier_.numeric_factorizations  = c.numeric_factorizations;
    start_                           = std::chrono::steady_clock::now();

    create_outputs();
    if (outputs_)
      outputs_->output_seconds = c.output_seconds;
    write_summary(wall_seconds(), false);  // by every process: it gathers their memory peaks
    if (outputs_)
      rewrite_outputs_up_to_checkpoint(newton_rows);
    run_steps();
    return true;
  }

  template <int dim>
  void Simulation<dim>::rewrite_outputs_up_to_checkpoint(const std::string &newton_rows)
  {
    const fs::path directory = scene_.output_directory;
    // The collections list the frames up to the checkpoint before later frames go, so
    // that no collection ever names a missing file.
    std::vector<std::pair<double, std::string>> solution, reference, obstacles;
    const auto scene_frame = [&](const unsigned int s) { return writes_frame(s); };
    for (const unsigned int s : frame_steps(step_, directory, scene_frame))
      {
        const double t = s == 0 ? scene_.start_time : history_[s - 1].time;
        solution.emplace_back(t, numbered_output("solution", s, ".vtu"));
        reference.emplace_back(t, numbered_output("reference", s, ".vtu"));
        obstacles.emplace_back(t, numbered_output("obstacles", s, ".vtu"));
      }
    outputs_->solution.assign(solution);
    outputs_->reference.assign(reference);
    if (!obstacles_.empty())
      outputs_->obstacles.assign(obstacles);
    remove_outputs_after(directory, step_);
    for (const auto &r : history_)
      append_log_row(r);
    outputs_->newton_log << newton_rows;
    flush_logs();

    std::cout << "ritr: " << scene_.parameter_file << ": resuming after step " << step_ << '/' << scene_.n_steps()
              << " (t = " << time_ << ") -> " << scene_.output_directory << std::endl;
  }

  template class Simulation<1>;
  template class Simulation<2>;
  template class Simulation<3>;
} // namespace ritr
