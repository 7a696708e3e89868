// Solver/newton log: newton.csv holds one row per Newton iteration, also for a step that
// fails. On the 80 m/s bar the rows show what the solver does near convergence: steps whose
// predicted decrease is below the energy's round-off are judged by the gradient norm, and
// every step judged on the energy lowers it once the prescribed motion is complete.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <regex>
#include <string>

#include "run_ritr.h"

using namespace ritr::test_support;

namespace
{
  const std::string log_on = "subsection Solver\n  set newton log = true\nend\n";

  std::size_t summary_count(const std::string &directory, const std::string &key)
  {
    const std::string summary = read_file(directory + "/summary.json");
    const std::size_t at      = summary.find("\"" + key + "\": ");
    return at == std::string::npos ? 0 : std::stoul(summary.substr(at + key.size() + 4));
  }

  // The coarse deep punch (two load steps) with Newton's log on and the given
  // `Solver/hessian projection`, run once per projection; returns its output directory.
  std::string punch_run(const std::string &projection)
  {
    static std::map<std::string, std::string> done;
    if (const auto it = done.find(projection); it != done.end())
      return it->second;
    const std::string directory = "output/newton_log/punch_" + projection;
    const RunResult   r         = run_ritr(scene_variant(
      "deep_punch_2d", projection, directory,
      "subsection Solver\n  set newton log = true\n  set hessian projection = " + projection + "\nend\n"));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(read_csv(directory + "/log.csv").rows.size(), 2u);
    return done[projection] = directory;
  }
} // namespace

// summary.json splits the final energy by term, and the terms add up to it (statics: the
// potential has no inertia, and without r-adaptivity no measure barrier).
TEST(NewtonLog, SummarySplitsTheFinalEnergyByTerm)
{
  const std::string summary = read_file(punch_run("trust-region") + "/summary.json");
  std::smatch       total, split;
  ASSERT_TRUE(std::regex_search(summary, total, std::regex("\"final_energy\": ([^,\n]*)")));
  ASSERT_TRUE(std::regex_search(summary, split, std::regex("\"final_energy_terms\": \\{([^}]*)\\}")));
  std::map<std::string, double> terms;
  const std::string             entries = split[1];
  const std::regex              entry("\"([a-z ]+)\": ([^,]+)");
  for (auto it = std::sregex_iterator(entries.begin(), entries.end(), entry); it != std::sregex_iterator(); ++it)
    terms[(*it)[1]] = std::stod((*it)[2]);
  ASSERT_EQ(terms.size(), 3u) << split[1];
  EXPECT_GT(terms.at("elasticity"), 0.0);
  EXPECT_GT(terms.at("contact barrier"), 0.0);  // the punch presses on the block
  double sum = 0;
  for (const auto &[name, value] : terms)
    sum += value;
  EXPECT_NEAR(sum, std::stod(total[1]), 1e-12 * std::abs(sum));
}

TEST(NewtonLog, OneRowPerIterationOnTheFastBar)
{
  const std::string directory = "output/newton_log/bar";
  const RunResult   r         = run_ritr(scene_variant("bar_impact_fine_2d", "log", directory, log_on));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const CsvTable log = read_csv(directory + "/newton.csv");
  EXPECT_EQ(log.rows.size(), summary_count(directory, "total_newton_iterations"));
  ASSERT_GT(log.rows.size(), 30u);
  const auto change = log.column("energy_change"), moving = log.column("prescribed_moving"),
             by_gradient = log.column("judged_by_gradient"), kappa = log.column("barrier_stiffness");
  ASSERT_LT(kappa, log.header.size());
  unsigned int judged_by_gradient = 0;
  for (const auto &row : log.rows)
    {
      ASSERT_EQ(row.size(), log.header.size());
      EXPECT_GT(row[kappa], 0.0);
      if (row[by_gradient] == 1)
        ++judged_by_gradient;
      else if (row[moving] == 0)
        {
          EXPECT_LE(row[change], 0.0) << "step " << row[0] << ", iteration " << row[2];
        }
    }
  EXPECT_GT(judged_by_gradient, 0u);
}

TEST(NewtonLog, FailedStepKeepsItsIterations)
{
  const std::string directory = "output/newton_log/failed";
  const RunResult   r         = run_ritr(scene_variant("bar_impact_fine_2d", "failed", directory,
                                                 "subsection Solver\n  set newton log = true\n"
                                                 "  set max iterations = 3\nend\n"));
  ASSERT_EQ(r.exit_code, 3) << r.output;
  const CsvTable log = read_csv(directory + "/newton.csv");
  ASSERT_EQ(log.rows.size(), 3u);
  for (unsigned int i = 0; i < 3; ++i)
    {
      EXPECT_EQ(log.rows[i][log.column("step")], 1.0);
      EXPECT_EQ(log.rows[i][log.column("iteration")], double(i));
    }
}

// Solver/hessian projection = never: the exact Hessian (shifted where indefinite) reaches the
// same states as projected Newton on the bar, in no more iterations, and logs its shifts.
TEST(NewtonLog, ExactHessianReachesTheProjectedStates)
{
  const std::string projected_dir = "output/newton_log/projected", exact_dir = "output/newton_log/exact";
  const RunResult   projected     = run_ritr(scene_variant(
    "bar_impact_fine_2d", "projected", projected_dir,
    "subsection Solver\n  set newton log = true\n  set hessian projection = always\nend\n"));
  const RunResult   exact         = run_ritr(scene_variant(
    "bar_impact_fine_2d", "exact", exact_dir,
    "subsection Solver\n  set newton log = true\n  set hessian projection = never\nend\n"));
  ASSERT_EQ(projected.exit_code, 0) << projected.output;
  ASSERT_EQ(exact.exit_code, 0) << exact.output;
  const CsvTable a = read_csv(projected_dir + "/log.csv"), b = read_csv(exact_dir + "/log.csv");
  ASSERT_EQ(a.rows.size(), b.rows.size());
  const auto energy = a.column("energy");
  for (std::size_t s = 0; s < a.rows.size(); ++s)
    EXPECT_NEAR(b.rows[s][energy], a.rows[s][energy], 1e-6 * std::abs(a.rows[s][energy])) << "step " << s + 1;
  EXPECT_LE(summary_count(exact_dir, "total_newton_iterations"), summary_count(projected_dir, "total_newton_iterations"));
  const CsvTable log   = read_csv(exact_dir + "/newton.csv");
  const auto     shift = log.column("hessian_shift");
  ASSERT_LT(shift, log.header.size());
  for (const auto &row : log.rows)
    EXPECT_GE(row[shift], 0.0);
}

// The adaptive projection: on the coarse deep punch projected Newton crawls under the punch's
// corners (101 and 86 iterations for the two load steps); the adaptive solve switches to the
// exact Hessian there and reaches the same equilibria in fewer iterations.
TEST(NewtonLog, AdaptiveProjectionFinishesTheCrawl)
{
  const std::string projected_dir = punch_run("always"), adaptive_dir = punch_run("adaptive");
  const CsvTable    a = read_csv(projected_dir + "/log.csv"), b = read_csv(adaptive_dir + "/log.csv");
  ASSERT_EQ(a.rows.size(), 2u);
  ASSERT_EQ(b.rows.size(), 2u);
  const auto energy = a.column("energy"), iterations = a.column("inner_newton_iterations");
  for (std::size_t s = 0; s < 2; ++s)
    {
      EXPECT_NEAR(b.rows[s][energy], a.rows[s][energy], 1e-9 * std::abs(a.rows[s][energy])) << "step " << s + 1;
      EXPECT_LT(b.rows[s][iterations], 0.8 * a.rows[s][iterations]) << "step " << s + 1;
    }
  const CsvTable log = read_csv(adaptive_dir + "/newton.csv");
  const auto     exact = log.column("exact_hessian"), shift = log.column("hessian_shift");
  unsigned int   exact_steps = 0;
  for (const auto &row : log.rows)
    {
      exact_steps += row[exact] == 1;
      if (row[exact] == 0)
        {
          EXPECT_EQ(row[shift], 0.0);  // a projected Hessian factorizes without a shift here
        }
    }
  EXPECT_GT(exact_steps, 10u);
  EXPECT_LT(exact_steps, log.rows.size());
}

// The trust region on the exact Hessian, preconditioned by the projected one (the default):
// on the same punch it ends no higher than the projected solve (lower where it follows
// negative curvature past the projected solve's equilibrium under a corner), in fewer
// iterations; every step after the punch has arrived is a trust-region step (a radius, CG
// iterations, an accepted decrease, no shift), and the steps while it moves are projected
// line-search steps.
TEST(NewtonLog, TrustRegionEndsNoHigherThanProjectedNewton)
{
  const std::string projected_dir = punch_run("always"), region_dir = punch_run("trust-region");
  const CsvTable    a = read_csv(projected_dir + "/log.csv"), b = read_csv(region_dir + "/log.csv");
  ASSERT_EQ(a.rows.size(), 2u);
  ASSERT_EQ(b.rows.size(), 2u);
  const auto energy = a.column("energy"), iterations = a.column("inner_newton_iterations");
  for (std::size_t s = 0; s < 2; ++s)
    {
      EXPECT_LE(b.rows[s][energy], a.rows[s][energy] + 1e-9 * std::abs(a.rows[s][energy])) << "step " << s + 1;
      EXPECT_LT(b.rows[s][iterations], a.rows[s][iterations]) << "step " << s + 1;
    }
  const CsvTable log    = read_csv(region_dir + "/newton.csv");
  const auto     radius = log.column("trust_radius"), cg = log.column("cg_iterations"),
             moving = log.column("prescribed_moving"), change = log.column("energy_change"),
             exact = log.column("exact_hessian"), value = log.column("energy");
  ASSERT_LT(cg, log.header.size());
  unsigned int region_steps = 0;
  for (const auto &row : log.rows)
    if (row[moving] == 0)
      {
        ++region_steps;
        EXPECT_GT(row[radius], 0.0);
        EXPECT_GE(row[cg], 1.0);
        EXPECT_EQ(row[exact], 1.0);
        EXPECT_LE(row[change], 1e-12 * std::abs(row[value]));  // a decrease, up to round-off
      }
    else
      {
        EXPECT_EQ(row[radius], 0.0);  // a projected line-search step
      }
  EXPECT_GT(region_steps, 20u);
}
