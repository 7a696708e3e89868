// ritr: frictionally contacting elastodynamics and statics with IPC, on fixed or r-adapted
// meshes. Parses the command line and the scene, runs it, maps failures to exit codes:
// 0 success, 2 bad input, 3 a step that did not converge, 1 anything else.
#include <ritr/scene/parameters.h>
#include <ritr/time/simulation.h>

#include <tbb/global_control.h>

#include <iostream>
#include <memory>
#include <string>

namespace
{
  void print_usage(std::ostream &out)
  {
    out << "usage: ritr SCENE.prm          run a scene (outputs go to its 'output directory')\n"
           "       ritr --print-parameters  every parameter with its documentation and default\n"
           "       ritr --help\n"
           "exit codes: 0 done, 2 bad input, 3 a step did not converge\n";
  }

  template <int dim>
  void run(const ritr::Scene &scene)
  {
    ritr::Simulation<dim> simulation(scene);
    std::cout << "ritr: " << scene.parameter_file << ": " << dim << "D " << scene.mode << ", "
              << simulation.mesh().n_nodes() << " vertices, " << simulation.mesh().n_cells() << " cells, "
              << scene.n_steps() << " steps -> " << scene.output_directory << std::endl;
    simulation.run();
    std::cout << "ritr: done; results in " << scene.output_directory
              << " (solution.pvd, reference.pvd, log.csv, summary.json)" << std::endl;
  }
} // namespace

int main(int argc, char **argv)
{
  if (argc != 2)
    {
      print_usage(std::cerr);
      return 2;
    }
  const std::string argument = argv[1];
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
      std::unique_ptr<tbb::global_control> threads;
      if (scene.solver.threads > 0)
        threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                        scene.solver.threads);
      switch (scene.dimension)
        {
          case 1: run<1>(scene); break;
          case 2: run<2>(scene); break;
          default: run<3>(scene); break;
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
