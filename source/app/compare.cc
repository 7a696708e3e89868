// ritr-compare: compares the solution series of two ritr runs (deformed-boundary Hausdorff
// distance, energies, centroid distance per shared frame time) and prints the result as JSON.
// Exit codes: 0 done, 2 bad input (one line naming the file), 1 anything else.
#include <ritr/common/input_error.h>
#include <ritr/compare/run_comparison.h>

#include <exception>
#include <iostream>
#include <string>

namespace
{
  void print_usage(std::ostream &out)
  {
    out << "usage: ritr-compare RUN_A RUN_B   compare two ritr output directories; JSON on stdout\n"
           "       ritr-compare --help\n"
           "exit codes: 0 done, 2 bad input\n";
  }
} // namespace

int main(int argc, char **argv)
{
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h"))
    {
      print_usage(std::cout);
      return 0;
    }
  if (argc != 3)
    {
      print_usage(std::cerr);
      return 2;
    }
  try
    {
      ritr::compare::write_json(std::cout, ritr::compare::compare_runs(argv[1], argv[2]));
      return 0;
    }
  catch (const ritr::InputError &e)
    {
      std::cerr << "ritr-compare: " << e.what() << std::endl;
      return 2;
    }
  catch (const std::exception &e)
    {
      std::cerr << "ritr-compare: " << e.what() << std::endl;
      return 1;
    }
}
