// ritr: frictionally contacting elastodynamics and statics with IPC, on fixed or r-adapted
// meshes. Parses the command line and the scene, runs it, maps failures to exit codes:
// 0 success, 2 bad input, 3 a step that did not converge, 1 anything else.
#include <ritr/common/input_error.h>
#include <ritr/common/number_text.h>
#include <ritr/common/thread_pools.h>
#include <ritr/scene/parameters.h>
#include <ritr/time/simulation.h>

#include <deal.II/base/mpi.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace
{

  void print_usage(std::ostream &out)
  {
    out << "usage: ritr SCENE.prm           run a scene (outputs go to its 'output directory');\n"
           "                                mpirun -np N ritr SCENE.prm shares a fixed-mesh run\n"
           "                                among N processes\n"
           "       ritr SCENE.prm --resume  continue a stopped run of the scene from the last\n"
           "                                checkpoint.bin in its output directory (a finished\n"
           "                                one, to a later end time)\n"
           "       ritr --print-parameters  every parameter with its documentation and default\n"
           "       ritr --help\n"
           "exit codes: 0 done (or nothing left to resume), 2 bad input, no usable checkpoint or\n"
           "            an output directory another run is using, 3 a step did not converge\n";
  }

  // What the command line asks for.
  struct Command
  {
    enum
    {
      run,
      help,
      print_parameters
    } action = run;
    std::string scene;
    bool        resume = false;
  };

  // Throws ritr::InputError, one line, for a command line that is not one of the usages.
  Command parse_command_line(const std::vector<std::string> &arguments)
  {
    const auto misuse = [](const std::string &what) {
      return ritr::InputError(what + " (usage: ritr SCENE.prm [--resume] | ritr --print-parameters | ritr --help)");
    };
    Command                  command;
    std::vector<std::string> scenes;
    unsigned int             actions = 0;  // --help and --print-parameters
    for (const std::string &argument : arguments)
      {
        const bool help = argument == "--help" || argument == "-h";
        if (argument == "--resume")
          command.resume = true;
        else if (help || argument == "--print-parameters")
          {
            command.action = help ? Command::help : Command::print_parameters;
            ++actions;
          }
        else if (argument.rfind("-", 0) == 0)
          throw misuse("unknown option '" + ritr::shortened(argument) + "'");
        else
          scenes.push_back(argument);
      }
    if (actions > 0 && (actions > 1 || command.resume || !scenes.empty()))
      throw misuse("--help and --print-parameters stand alone");
    if (actions == 0 && scenes.size() != 1)
      throw misuse(scenes.empty() ? "no scene file given" : "more than one scene file given");
    if (actions == 0)
      command.scene = scenes[0];
    return command;
  }

  template <int dim>
  void run(const ritr::Scene &scene, const bool resume, const ritr::WorkShare &share)
  {
    ritr::Simulation<dim> simulation(scene, share);
    // Every process runs the simulation; the writer (rank 0) alone prints and writes.
    std::ostream quiet(nullptr);
    std::ostream &out = share.is_writer() ? std::cout : quiet;
    // The output directory is taken before anything is printed, so that a refusal (another
    // run holds it, it cannot be created) is the only line. A resumed run says where it
    // resumes once its checkpoint has passed the checks, for the same reason.
    simulation.claim_output_directory(resume);
    if (!resume)
      {
        out << "ritr: " << scene.parameter_file << ": " << dim << "D " << scene.mode << ", "
            << simulation.mesh().n_nodes() << " vertices, " << simulation.mesh().n_cells() << " cells, "
            << simulation.scene().n_steps() << " steps"
            << (scene.start_from.empty() ? std::string() :
                                           " from t = " + ritr::number_text(simulation.scene().start_time) + " (" + scene.start_from + ")")
            << (share.distributed() ? " on " + std::to_string(share.size()) +
                                        (share.size() == 1 ? " process" : " processes") + " (" +
                                        ritr::name_of(ritr::distributed_solver_names, scene.solver.distributed_solver) +
                                        " solver)" :
                                      std::string())
            << " -> " << scene.output_directory << std::endl;
        simulation.run();
      }
    else if (!simulation.resume())
      {
        out << "ritr: the run in " << scene.output_directory << " is already complete; nothing to resume"
            << std::endl;
        return;
      }
    out << "ritr: done; results in " << scene.output_directory
        << " (solution.pvd, reference.pvd, log.csv, summary.json)" << std::endl;
  }

  // Whether an MPI launcher (mpirun, mpiexec, srun) started this process: Open MPI, MPICH
  // and PMI/PMIx (Slurm) name the process's rank in its environment.
  bool started_by_mpi_launcher()
  {
    for (const char *variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
      if (std::getenv(variable))
        return true;
    return false;
  }
} // namespace

int main(int argc, char **argv)
{
  // Started by a launcher, the processes share the run, and deal.II splits the cores among the
  // processes of a node. Alone, this is a serial run without MPI: Open MPI would start a
  // daemon for a process of its own (a "singleton"), which costs every run its start-up.
  std::optional<dealii::Utilities::MPI::MPI_InitFinalize> mpi;
  if (started_by_mpi_launcher())
    mpi.emplace(argc, argv);
  const ritr::WorkShare share = mpi ? ritr::WorkShare(MPI_COMM_WORLD) : ritr::WorkShare();
  // Input errors and failed steps happen on every process alike (each reads the same scene,
  // and every decision of a step is taken on values reduced over the processes): the writer
  // says it once and all exit with its code.
  const auto fail = [&](const std::string &what, const int code) {
    if (share.is_writer() && !what.empty())
      std::cerr << "ritr: error: " << what << std::endl;
    return code;
  };
  Command command;
  try
    {
      command = parse_command_line(std::vector<std::string>(argv + 1, argv + argc));
    }
  catch (const ritr::InputError &e)
    {
      return fail(e.what(), 2);
    }
  if (command.action != Command::run)
    {
      if (share.is_writer())
        command.action == Command::help ? print_usage(std::cout) : ritr::print_parameters(std::cout);
      return 0;
    }
  try
    {
      const ritr::Scene scene = ritr::read_scene(command.scene);
      ritr::use_one_thread_pool();
      ritr::set_factorization_threads(scene.solver.factorization_threads);
      std::unique_ptr<tbb::global_control> threads;
      if (scene.solver.threads > 0)
        threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                        scene.solver.threads);
      switch (scene.dimension)
        {
          case 1: run<1>(scene, command.resume, share); break;
          case 2: run<2>(scene, command.resume, share); break;
          default: run<3>(scene, command.resume, share); break;
        }
    }
  catch (const ritr::InputError &e)
    {
      return fail(e.what(), 2);
    }
  catch (const ritr::ConvergenceError &e)
    {
      return fail(std::string(e.what()) + "; steps written so far are kept", 3);
    }
  catch (const std::exception &e)
    {
      // Possibly on this process alone: the others would wait for it forever.
      std::cerr << "ritr: error: " << e.what() << std::endl;
      if (share.distributed())
        MPI_Abort(share.communicator(), 1);
      return 1;
    }
  return 0;
}
