// The Newton system over the free unknowns keeps its pattern across triplet lists: whatever
// sequence of lists it is given (the same structure, a reordered one as after a contact-set
// change, one with a new entry, one whose pattern shrank), its matrix and right-hand side
// equal, bit for bit, those of a system built afresh from that list alone.
#include <ritr/solver/reduced_system.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace ritr;

namespace
{
  // A symmetric list over n unknowns: every pair (i, j) of `pairs` as two mirrored triplets,
  // plus the diagonal, with values from `seed`.
  Triplets symmetric_list(const int n, const std::vector<std::pair<int, int>> &pairs, const unsigned seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    Triplets                               list;
    for (int i = 0; i < n; ++i)
      list.emplace_back(i, i, 4 + u(rng));
    for (const auto &[i, j] : pairs)
      {
        const double v = u(rng);
        list.emplace_back(i, j, v);
        list.emplace_back(j, i, v);
      }
    return list;
  }

  void expect_as_fresh(const ReducedSystem &kept, const Eigen::VectorXd &kept_rhs, const Triplets &list,
                       const std::vector<int> &free_index, const int n_free, const Eigen::VectorXd &step,
                       const Eigen::VectorXd &minus_g)
  {
    ReducedSystem   fresh;
    Eigen::VectorXd rhs = minus_g;
    fresh.assemble(list, free_index, n_free, step, rhs);
    const auto &a = kept.matrix(), &b = fresh.matrix();
    ASSERT_EQ(a.nonZeros(), b.nonZeros());
    EXPECT_TRUE(std::equal(b.outerIndexPtr(), b.outerIndexPtr() + b.outerSize() + 1, a.outerIndexPtr()));
    EXPECT_TRUE(std::equal(b.innerIndexPtr(), b.innerIndexPtr() + b.nonZeros(), a.innerIndexPtr()));
    EXPECT_TRUE(std::equal(b.valuePtr(), b.valuePtr() + b.nonZeros(), a.valuePtr()));
    EXPECT_TRUE(kept_rhs == rhs);
  }
} // namespace

TEST(ReducedSystem, KeptPatternGivesTheFreshSystem)
{
  const int n = 12;
  // Unknowns 3 and 7 prescribed: the others are free, numbered in order.
  std::vector<int> free_index(n);
  int              n_free = 0;
  for (int i = 0; i < n; ++i)
    free_index[i] = i == 3 || i == 7 ? -1 : n_free++;
  Eigen::VectorXd step = Eigen::VectorXd::Zero(n), minus_g = Eigen::VectorXd::LinSpaced(n_free, 1, 2);
  step[3] = 0.25, step[7] = -0.5;

  const std::vector<std::pair<int, int>> chain{{0, 1}, {1, 2}, {2, 3}, {3, 4}, {5, 6}, {6, 7}, {8, 9}, {10, 11}};
  std::vector<std::pair<int, int>>       contact{{0, 5}, {2, 9}, {4, 7}};
  std::vector<Triplets>                  lists;
  {
    auto pairs = chain;
    pairs.insert(pairs.end(), contact.begin(), contact.end());
    lists.push_back(symmetric_list(n, pairs, 1));  // the first list
    lists.push_back(symmetric_list(n, pairs, 2));  // same structure, new values
    std::reverse(contact.begin(), contact.end());  // same pattern, contact triplets reordered
    pairs = chain;
    pairs.insert(pairs.end(), contact.begin(), contact.end());
    lists.push_back(symmetric_list(n, pairs, 3));
    pairs.emplace_back(1, 11);  // a new contact entry: the pattern grows
    lists.push_back(symmetric_list(n, pairs, 4));
    pairs.emplace_back(0, 5);  // a duplicate of an existing entry: summed in list order
    lists.push_back(symmetric_list(n, pairs, 5));
    lists.push_back(symmetric_list(n, chain, 6));  // contact gone: the pattern shrinks
    auto shorter = chain;
    shorter.emplace_back(0, 5);
    lists.push_back(symmetric_list(n, shorter, 7));  // a longer list after a short one
  }
  ReducedSystem kept;
  for (std::size_t k = 0; k < lists.size(); ++k)
    {
      SCOPED_TRACE("list " + std::to_string(k));
      Eigen::VectorXd rhs = minus_g;
      kept.assemble(lists[k], free_index, n_free, step, rhs);
      expect_as_fresh(kept, rhs, lists[k], free_index, n_free, step, minus_g);
    }

  // Another set of free unknowns: the pattern follows it.
  free_index[7] = n_free++;
  Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(n_free, 1, 2);
  kept.assemble(lists[0], free_index, n_free, step, rhs);
  expect_as_fresh(kept, rhs, lists[0], free_index, n_free, step, Eigen::VectorXd::LinSpaced(n_free, 1, 2));
}
