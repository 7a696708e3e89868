// ritr: frictionally contacting elastodynamics and statics with IPC, on fixed or r-adapted
// meshes. Parses the command line and the scene, runs it, maps failures to exit codes:
// 0 success, 2 bad input, 3 a step that did not converge, 1 anything else.
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
           "exit codes: 0 done (or nothing left to resume), 2 bad input or no usable checkpoint,\n"
           "            3 a step did not converge\n";
  }

  template <int dim>
  void run(const ritr::Scene &scene, const bool resume)
  {
    ritr::Simulation<dim> simulation(scene);
    // A resumed run says where it resumes once its checkpoint has passed the checks, so that
    // a refused checkpoint stays a one-line error.
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
  std::vector<std::string> arguments(argv + 1, argv + argc);
  const auto resume_flag = std::find(arguments.begin(), arguments.end(), "--resume");
  const bool resume      = resume_flag != arguments.end();
  if (resume)
    arguments.erase(resume_flag);
  if (arguments.size() != 1 || (resume && arguments[0].rfind("--", 0) == 0))
    {
      print_usage(std::cerr);
      return 2;
    }
  const std::string argument = arguments[0];
  if (argument == "--help" || argument == "-h")
    {
      print_usage(std::cout);
      return 0;
    }
  if (argument == "--print-parameters")
    {
      ritr::print_parameters(std::cout);
      return 0;
    }
  try
    {
      const ritr::Scene scene = ritr::read_scene(argument);
      ritr::use_one_thread_pool();
      std::unique_ptr<tbb::global_control> threads;
      if (scene.solver.threads > 0)
        threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                        scene.solver.threads);
      switch (scene.dimension)
        {
          case 1: run<1>(scene, resume); break;
          case 2: run<2>(scene, resume); break;
          default: run<3>(scene, resume); break;
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
