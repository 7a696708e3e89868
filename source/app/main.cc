// ritr: frictionally contacting elastodynamics and statics with IPC, on fixed or r-adapted
// meshes. Parses the command line and the scene, runs it, maps failures to exit codes:
// 0 success, 2 bad input, 3 a step that did not converge, 1 anything else.
#include <ritr/common/input_error.h>
#include <ritr/common/thread_pools.h>
#include <ritr/scene/parameters.h>
#include <ritr/time/simulation.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace
{
  void print_usage(std::ostream &out)
  {
    out << "usage: ritr SCENE.prm           run a scene (outputs go to its 'output directory')\n"
           "       ritr SCENE.prm --resume  continue a stopped run of the scene from the last\n"
           "                                checkpoint.bin in its output directory\n"
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
  void run(const ritr::Scene &scene, const bool resume)
  {
    ritr::Simulation<dim> simulation(scene);
    // The output directory is taken before anything is printed, so that a refusal (another
    // run holds it, it cannot be created) is the only line. A resumed run says where it
    // resumes once its checkpoint has passed the checks, for the same reason.
    simulation.claim_output_directory(resume);
    if (!resume)
      {
        std::cout << "ritr: " << scene.parameter_file << ": " << dim << "D " << scene.mode << ", "
                  << simulation.mesh().n_nodes() << " vertices, " << simulation.mesh().n_cells() << " cells, "
                  << scene.n_steps() << " steps -> " << scene.output_directory << std::endl;
        simulation.run();
      }
    else if (!simulation.resume())
      {
        std::cout << "ritr: the run in " << scene.output_directory << " is already complete; nothing to resume"
                  << std::endl;
        return;
      }
    std::cout << "ritr: done; results in " << scene.output_directory
              << " (solution.pvd, reference.pvd, log.csv, summary.json)" << std::endl;
  }
} // namespace

int main(int argc, char **argv)
{
  Command command;
  try
    {
      command = parse_command_line(std::vector<std::string>(argv + 1, argv + argc));
    }
  catch (const ritr::InputError &e)
    {
      std::cerr << "ritr: error: " << e.what() << std::endl;
      return 2;
    }
  if (command.action == Command::help)
    {
      print_usage(std::cout);
      return 0;
    }
  if (command.action == Command::print_parameters)
    {
      ritr::print_parameters(std::cout);
      return 0;
    }
  try
    {
      const ritr::Scene scene = ritr::read_scene(command.scene);
      ritr::use_one_thread_pool();
      std::unique_ptr<tbb::global_control> threads;
      if (scene.solver.threads > 0)
        threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                        scene.solver.threads);
      switch (scene.dimension)
        {
          case 1: run<1>(scene, command.resume); break;
          case 2: run<2>(scene, command.resume); break;
          default: run<3>(scene, command.resume); break;
        }
    }
  catch (const ritr::InputError &e)
    {
      std::cerr << "ritr: error: " << e.what() << std::endl;
      return 2;
    }
  catch (const ritr::ConvergenceError &e)
    {
      std::cerr << "ritr: error: " << e.what() << "; steps written so far are kept" << std::endl;
      return 3;
    }
  catch (const std::exception &e)
    {
      std::cerr << "ritr: error: " << e.what() << std::endl;
      return 1;
    }
  return 0;
}
