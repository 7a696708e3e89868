#pragma once
// checkpoint.bin: what a run carries from one step to the next, written with every VTU frame
// so that `ritr SCENE.prm --resume` continues a killed run from its last frame. Doubles are
// stored raw, so a resumed run repeats the uninterrupted one bit for bit; a checksum catches
// torn or damaged files, and the file is written atomically like every other output.
#include <ritr/common/input_error.h>
#include <ritr/time/step_report.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace ritr
{
  struct Checkpoint
  {
    unsigned int  dimension  = 0;
    std::uint64_t scene_hash = 0;  // fingerprint of the scene (see Simulation::resume)
    unsigned int  step       = 0;  // steps done
    double        time       = 0;
    // The state: reference and deformed body nodes, their velocity, the obstacle vertices.
    Eigen::VectorXd u, x, v, obstacle_positions;
    double          barrier_stiffness = 0;  // the contact barrier's after the last step
    // One report per step done: log.csv is rewritten from them, summary.json adds them up.
    std::vector<StepReport>  history;
    std::vector<std::string> invariant_violations;
    // The last step's energy term by term (summary.json's final_energy_terms), once the run
    // has made its last step; empty before.
    std::vector<std::pair<std::string, double>> final_energy_terms;
    // What the stepper carries from one step to the next besides the state (Stepper::
    // carried_state: r-ITR's quasi-Newton curvature and trust region); empty for a fixed mesh.
    Eigen::VectorXd stepper_state;
    // Totals of summary.json that no step report holds, over the run so far.
    double        wall_seconds = 0, output_seconds = 0, linear_solve_seconds = 0;
    std::uint64_t symbolic_factorizations = 0, numeric_factorizations = 0;
    // The scene's entries set away from their defaults (Scene::parameter_listing), to name
    // the first entry that differs when another scene's checkpoint is refused.
    std::string scene_entries;
  };

  // Writes `checkpoint` to `path` atomically (temporary name, then rename).
  void write_checkpoint(const std::string &path, const Checkpoint &checkpoint);

  // The refusal to resume when there is no checkpoint at `path`.
  InputError no_checkpoint_error(const std::string &path);

  // Reads a checkpoint; throws InputError naming the file and what is wrong with it (missing,
  // not a checkpoint, another format version, truncated, corrupted, or contents that no run
  // writes: a state or time that is not finite, step reports out of order).
  Checkpoint read_checkpoint(const std::string &path);

  // 64-bit FNV-1a of `bytes` bytes, continuing from `hash` (fingerprints, not security).
  std::uint64_t fnv1a(const void *data, std::size_t bytes, std::uint64_t hash = 14695981039346656037ull);
} // namespace ritr
