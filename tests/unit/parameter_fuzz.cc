// Mutation fuzz of the scene reader: mutants of a valid scene (bytes flipped, inserted and
// deleted, values swapped for hostile ones, lines duplicated, dropped, swapped or cut) are
// read and validated as `ritr` does before it runs. Each must be accepted or rejected with
// an InputError of one printable line naming the file; any other exception, a crash or a
// hang fails. RITR_FUZZ_SEED and RITR_FUZZ_MUTANTS change the (fixed) sample;
// RITR_FUZZ_VERBOSE=1 prints every rejection.
#include <ritr/scene/parameters.h>
#include <ritr/time/simulation.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "run_ritr.h"

using namespace ritr;
using namespace ritr::test_support;

namespace
{
  const char *base_scene = R"(set dimension = 2
set time step = 0.01
set end time = 0.02
set output directory = output/parameter_fuzz/out
subsection Body 0
  set shape = rectangle
  set lower = 0, 0
  set upper = 1, 0.2
  set subdivisions = 4, 1
  set translation = 0, 0.01
  set initial velocity = 0; -t - y
end
subsection Body 1
  set enabled = true
  set shape = disk
  set center = 0.5, 0.6
  set radius = 0.2
  set shape refinements = 0
  set material id = 1
end
subsection Material 1
  set youngs modulus = 1e4
end
subsection Gravity
  set acceleration = 0, -9.81
  set load factor = 1 + t
end
subsection Dirichlet 0
  set enabled = true
  set region = 0.05 - x
  set displacement = 0; 0.1 * t
end
subsection Obstacle 0
  set type = plane
  set point = 0, 0
  set normal = 0, 1
  set size = 4
  set translation = 0; 0
  set rotation angle = 0.1 * t
end
subsection Contact
  set dhat = 1e-3
  set friction coefficient = 0.2
end
subsection Adaptivity
  set enabled = false
end
)";

  std::string repeated(const std::string &s, const unsigned int n)
  {
    std::string r;
    for (unsigned int i = 0; i < n; ++i)
      r += s;
    return r;
  }

  const std::vector<std::string> hostile_values = {
    "", "0", "-1", "1", "3", "1e308", "-1e308", "1e-308", "1e-320", "nan", "inf", "1e999", "-0", "0x10",
    "1e5abc", "0,0", "0,0,0,0", "1,", ",", ";", "0;0", "0;0;0", "x", "t", "sqrt(-1)", "1/0", "log(0)",
    "((", "true", "false", "file", "disk", "ball", "box", "interval", "spikes", "punch", "static",
    "adaptive", "full", "geometric", "\\", "#", "\t", std::string("\0", 1), "\xff\xfe", repeated("9", 400),
    repeated("(", 3000), repeated("x", 30000)};
  const std::vector<std::string> hostile_lines = {
    "end", "subsection Body 2", "subsection Contact", "set enabled = true", "set dimension = 3",
    "set dimension = 1", "set mode = static", "subsection Adaptivity\nset enabled = true\nend"};

  class Mutator
  {
  public:
    explicit Mutator(const unsigned int seed) : random_(seed) {}

    std::string mutant(std::string text)
    {
      for (unsigned int n = 1 + below(3); n > 0; --n)
        mutate(text);
      return text;
    }

  private:
    std::size_t below(const std::size_t n) { return n == 0 ? 0 : random_() % n; }

    std::vector<std::string> lines(const std::string &text)
    {
      std::vector<std::string> r;
      std::stringstream        ss(text);
      for (std::string line; std::getline(ss, line);)
        r.push_back(line);
      return r;
    }
    std::string joined(const std::vector<std::string> &lines)
    {
      std::string r;
      for (const auto &line : lines)
        r += line + "\n";
      return r;
    }

    void mutate(std::string &text)
    {
      const std::size_t at   = below(text.size() + 1);
      const char        byte = static_cast<char>(below(256));
      auto              all  = lines(text);
      switch (below(9))
        {
          case 0: if (at < text.size()) text[at] = byte; break;
          case 1: text.insert(at, 1, byte); break;
          case 2: text.erase(at, 1 + below(10)); break;
          case 3:
            {
              // A value swapped for a hostile one.
              auto &line = all[below(all.size())];
              if (line.find('=') != std::string::npos)
                line = line.substr(0, line.find('=') + 2) + hostile_values[below(hostile_values.size())];
              text = joined(all);
              break;
            }
          case 4: all.insert(all.begin() + below(all.size()), all[below(all.size())]); text = joined(all); break;
          case 5: all.erase(all.begin() + below(all.size())); text = joined(all); break;
          case 6: std::swap(all[below(all.size())], all[below(all.size())]); text = joined(all); break;
          case 7: text.resize(at); break;
          default:
            all.insert(all.begin() + below(all.size()), hostile_lines[below(hostile_lines.size())]);
            text = joined(all);
        }
    }

    std::mt19937 random_;
  };

  // What ritr does before it runs: read the scene, build and check everything.
  void validate(const std::string &file)
  {
    const Scene scene = read_scene(file);
    switch (scene.dimension)
      {
        case 1: Simulation<1>{scene}; break;
        case 2: Simulation<2>{scene}; break;
        default: Simulation<3>{scene}; break;
      }
  }

  unsigned int from_environment(const char *name, const unsigned int otherwise)
  {
    const char *value = std::getenv(name);
    return value ? std::stoul(value) : otherwise;
  }
} // namespace

TEST(ParameterFuzz, MutantsAreAcceptedOrRejectedWithOneLine)
{
  const std::string folder = "output/parameter_fuzz", file = folder + "/mutant.prm";
  std::filesystem::create_directories(folder);
  write_file(file, base_scene);
  ASSERT_NO_THROW(validate(file)) << "the base scene must be valid";

  const unsigned int seed = from_environment("RITR_FUZZ_SEED", 1), n = from_environment("RITR_FUZZ_MUTANTS", 500);
  Mutator            mutator(seed);
  unsigned int       rejected = 0;
  const bool         verbose  = from_environment("RITR_FUZZ_VERBOSE", 0) > 0;
  for (unsigned int i = 0; i < n; ++i)
    {
      const std::string text = mutator.mutant(base_scene);
      write_file(file, text);
      const std::string kept = folder + "/failed-" + std::to_string(seed) + "-" + std::to_string(i) + ".prm";
      try
        {
          validate(file);
        }
      catch (const InputError &e)
        {
          ++rejected;
          const std::string message = e.what();
          const bool printable = std::none_of(message.begin(), message.end(),
                                              [](const char c) { return static_cast<unsigned char>(c) < 0x20; });
          const bool one_line = message.rfind(file, 0) == 0 && printable && message.size() < 600;
          if (verbose)
            std::cout << message << '\n';
          EXPECT_TRUE(one_line) << "mutant " << i << " (kept as " << kept << "): " << message;
          if (!one_line)
            write_file(kept, text);
        }
      catch (const std::exception &e)
        {
          write_file(kept, text);
          ADD_FAILURE() << "mutant " << i << " (kept as " << kept << "): not an InputError: " << e.what();
        }
    }
  // Most mutants break something; a fuzz that rejects nothing tests nothing.
  EXPECT_GT(rejected, n / 4);
  std::cout << rejected << " of " << n << " mutants rejected (seed " << seed << ")\n";
}
