// Broad phase (AABB tree) against brute force, active-set construction and minimum
// distance against all-pairs evaluation.
#include <ritr/contact/broad_phase.h>
#include <ritr/contact/constraints.h>

#include "contact_test_support.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <chrono>
#include <set>
#include <tuple>

using namespace ritr::contact;
using namespace ritr::contact::test_support;

const std::mt19937::result_type ritr::contact::test_support::rng_seed = 7;

namespace
{
  // Random scenes of small primitives scattered in a box (some of them obstacles).
  Scene<1> random_scene_1d(const int n)
  {
    Scene<1> s;
    for (int i = 0; i < n; ++i)
      s.add_vertex(random_vector<1>(), uniform(0, 1) < 0.2);
    return s;
  }

  Scene<2> random_scene_2d(const int n_polygons)
  {
    Scene<2> s;
    for (int p = 0; p < n_polygons; ++p)
      {
        const Vec<2> c        = random_vector<2>();
        const bool   obstacle = uniform(0, 1) < 0.2;
        const int    n        = 3 + p % 3;
        const int    first    = s.surface.n_vertices;
        for (int i = 0; i < n; ++i)
          s.add_vertex(c + 0.15 * random_vector<2>(), obstacle);
        for (int i = 0; i < n; ++i)
          s.surface.edges.push_back({{first + i, first + (i + 1) % n}});
      }
    return s;
  }

  Scene<3> random_scene_3d(const int n_tets)
  {
    Scene<3> s;
    for (int t = 0; t < n_tets; ++t)
      {
        const Vec<3> c        = random_vector<3>();
        const bool   obstacle = uniform(0, 1) < 0.2;
        const int    first    = s.surface.n_vertices;
        for (int i = 0; i < 4; ++i)
          s.add_vertex(c + 0.25 * random_vector<3>(), obstacle);
        const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
        for (const auto &fa : f)
          s.surface.faces.push_back({{first + fa[0], first + fa[1], first + fa[2]}});
      }
    s.surface.edges = edges_of_faces(s.surface.faces);
    return s;
  }

  // Candidate in a canonical form for set comparisons (symmetric kinds sorted).
  std::tuple<int, int, int> canonical(const Candidate &c)
  {
    if (c.kind == ContactKind::vertex_vertex || c.kind == ContactKind::edge_edge)
      return {static_cast<int>(c.kind), std::min(c.first, c.second), std::max(c.first, c.second)};
    return {static_cast<int>(c.kind), c.first, c.second};
  }

  // Every admissible pair, enumerated naively.
  template <int dim>
  std::vector<Candidate> all_pairs(const CollisionSurface<dim> &s)
  {
    std::vector<Candidate> out;
    const auto             obs = [&](const int v) { return s.vertex_is_obstacle(v); };
    if constexpr (dim == 1)
      {
        for (int a = 0; a < s.n_vertices; ++a)
          for (int b = a + 1; b < s.n_vertices; ++b)
            if (!(obs(a) && obs(b)))
              out.push_back({ContactKind::vertex_vertex, a, b});
      }
    else if constexpr (dim == 2)
      {
        for (int v = 0; v < s.n_vertices; ++v)
          for (int e = 0; e < static_cast<int>(s.edges.size()); ++e)
            if (v != s.edges[e][0] && v != s.edges[e][1] && !(obs(v) && s.edge_is_obstacle(e)))
              out.push_back({ContactKind::point_edge, v, e});
      }
    else
      {
        for (int v = 0; v < s.n_vertices; ++v)
          for (int f = 0; f < static_cast<int>(s.faces.size()); ++f)
            {
              const auto &fa = s.faces[f];
              if (v != fa[0] && v != fa[1] && v != fa[2] && !(obs(v) && s.face_is_obstacle(f)))
                out.push_back({ContactKind::point_triangle, v, f});
            }
        const int ne = static_cast<int>(s.edges.size());
        for (int a = 0; a < ne; ++a)
          for (int b = a + 1; b < ne; ++b)
            {
              const auto &ea = s.edges[a], &eb = s.edges[b];
              if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1])
                continue;
              if (!(s.edge_is_obstacle(a) && s.edge_is_obstacle(b)))
                out.push_back({ContactKind::edge_edge, a, b});
            }
      }
    return out;
  }

  template <int dim>
  double pair_distance_sqr(const CollisionSurface<dim> &s, const Eigen::MatrixXd &V,
                           const Candidate &c)
  {
    std::array<int, 4> v;
    const int          n = stencil_vertices<dim>(s, c, v);
    StencilVector<dim> x = StencilVector<dim>::Zero();
    for (int i = 0; i < n; ++i)
      x.template segment<dim>(i * dim) = V.row(v[i]).transpose();
    return distance_sqr<dim>(c.kind, x);
  }

  template <int dim>
  ritr::Aabb<dim> pair_box(const CollisionSurface<dim> &s, const Eigen::MatrixXd &V0,
                     const Eigen::MatrixXd &V1, const Candidate &c, const int side, const double r)
  {
    std::array<int, 4> v;
    const int          n = stencil_vertices<dim>(s, c, v);
    // Side 0: the first primitive (point or edge a), side 1: the other one.
    const int n_first = c.kind == ContactKind::edge_edge ? 2 : 1;
    ritr::Aabb<dim> box;
    for (int i = side == 0 ? 0 : n_first; i < (side == 0 ? n_first : n); ++i)
      {
        ritr::Aabb<dim> b;
        b.min = V0.row(v[i]).transpose().cwiseMin(V1.row(v[i]).transpose());
        b.max = V0.row(v[i]).transpose().cwiseMax(V1.row(v[i]).transpose());
        box.extend(b);
      }
    box.inflate(r);
    return box;
  }

  template <int dim>
  void check_candidates_valid(const CollisionSurface<dim> &s, const std::vector<Candidate> &cs)
  {
    EXPECT_TRUE(std::is_sorted(cs.begin(), cs.end()));
    EXPECT_TRUE(std::adjacent_find(cs.begin(), cs.end()) == cs.end());
    std::set<std::tuple<int, int, int>> admissible;
    for (const auto &c : all_pairs<dim>(s))
      admissible.insert(canonical(c));
    for (const auto &c : cs)
      {
        EXPECT_TRUE(admissible.count(canonical(c))) << "inadmissible candidate";
        // For symmetric kinds a body primitive comes first (it owns the weight).
        if (c.kind == ContactKind::vertex_vertex)
          EXPECT_TRUE(!s.vertex_is_obstacle(c.first) || s.vertex_is_obstacle(c.second));
        if (c.kind == ContactKind::edge_edge)
          EXPECT_TRUE(!s.edge_is_obstacle(c.first) || s.edge_is_obstacle(c.second));
      }
  }

  template <int dim>
  void check_static_broad_phase(const Scene<dim> &scene, const double r)
  {
    const auto &s  = scene.surface;
    const auto  V  = scene.V();
    const auto  cs = find_candidates<dim>(s, V, r);
    check_candidates_valid<dim>(s, cs);

    // Exactly the pairs whose inflated boxes overlap...
    std::set<std::tuple<int, int, int>> boxes_bf, found, near_bf, near_found;
    for (const auto &c : all_pairs<dim>(s))
      {
        if (pair_box<dim>(s, V, V, c, 0, 0.5 * r).overlaps(pair_box<dim>(s, V, V, c, 1, 0.5 * r)))
          boxes_bf.insert(canonical(c));
        if (pair_distance_sqr<dim>(s, V, c) < r * r)
          near_bf.insert(canonical(c));
      }
    for (const auto &c : cs)
      {
        found.insert(canonical(c));
        if (pair_distance_sqr<dim>(s, V, c) < r * r)
          near_found.insert(canonical(c));
      }
    EXPECT_EQ(found, boxes_bf);
    // ...and after filtering by exact distance, exactly the brute-force near pairs.
    EXPECT_EQ(near_found, near_bf);
    EXPECT_GT(near_bf.size(), 0u);
  }
} // namespace

TEST(BroadPhase, AabbTreeQueriesMatchBruteForce)
{
  std::vector<ritr::Aabb<3>> boxes(500);
  for (auto &b : boxes)
    {
      b.min = random_vector<3>();
      b.max = b.min + 0.1 * (random_vector<3>().array() + 1.0).matrix();
    }
  const ritr::AabbTree<3> tree(boxes);
  for (int q = 0; q < 100; ++q)
    {
      ritr::Aabb<3> query;
      query.min = random_vector<3>();
      query.max = query.min + 0.3 * (random_vector<3>().array() + 1.0).matrix();
      std::set<int> found, expected;
      tree.for_each_overlap(query, [&](const int i) { EXPECT_TRUE(found.insert(i).second); });
      for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
        if (boxes[i].overlaps(query))
          expected.insert(i);
      EXPECT_EQ(found, expected);
    }
}

TEST(BroadPhase, StaticCandidatesMatchBruteForce1D)
{
  for (int trial = 0; trial < 5; ++trial)
    check_static_broad_phase<1>(random_scene_1d(200), 0.01);
}

TEST(BroadPhase, StaticCandidatesMatchBruteForce2D)
{
  for (int trial = 0; trial < 5; ++trial)
    check_static_broad_phase<2>(random_scene_2d(60), 0.05);
}

TEST(BroadPhase, StaticCandidatesMatchBruteForce3D)
{
  for (int trial = 0; trial < 3; ++trial)
    check_static_broad_phase<3>(random_scene_3d(40), 0.08);
}

template <int dim>
void check_swept_broad_phase(const Scene<dim> &scene, const double r)
{
  const auto     &s  = scene.surface;
  const auto      V0 = scene.V();
  Eigen::MatrixXd V1 = V0;
  for (int i = 0; i < V1.rows(); ++i)
    V1.row(i) += 0.2 * random_vector<dim>().transpose();
  const auto cs = find_candidates<dim>(s, V0, V1, r);
  check_candidates_valid<dim>(s, cs);
  std::set<std::tuple<int, int, int>> expected, found;
  for (const auto &c : all_pairs<dim>(s))
    if (pair_box<dim>(s, V0, V1, c, 0, 0.5 * r).overlaps(pair_box<dim>(s, V0, V1, c, 1, 0.5 * r)))
      expected.insert(canonical(c));
  for (const auto &c : cs)
    found.insert(canonical(c));
  EXPECT_EQ(found, expected);

  // Sampled along the trajectories, every pair closer than r is a candidate.
  for (const auto &c : all_pairs<dim>(s))
    for (double t = 0; t <= 1.0; t += 0.125)
      if (pair_distance_sqr<dim>(s, (1 - t) * V0 + t * V1, c) < r * r)
        EXPECT_TRUE(found.count(canonical(c)));
}

TEST(BroadPhase, SweptCandidatesMatchBruteForce)
{
  for (int trial = 0; trial < 3; ++trial)
    {
      check_swept_broad_phase<1>(random_scene_1d(100), 0.01);
      check_swept_broad_phase<2>(random_scene_2d(30), 0.02);
      check_swept_broad_phase<3>(random_scene_3d(20), 0.02);
    }
}

template <int dim>
void check_build_constraints(const Scene<dim> &scene, const double dhat)
{
  const auto &s  = scene.surface;
  const auto  V  = scene.V();
  const auto  cs = build_constraints<dim>(s, V, V, dhat);
  std::set<std::tuple<int, int, int>> expected, found;
  for (const auto &c : all_pairs<dim>(s))
    if (pair_distance_sqr<dim>(s, V, c) < dhat * dhat)
      expected.insert(canonical(c));
  for (const auto &c : cs)
    {
      found.insert(canonical(Candidate{c.kind, c.first, c.second}));
      EXPECT_NEAR(c.distance_sqr, constraint_distance_sqr<dim>(c, V), 1e-15);
      EXPECT_LT(c.distance_sqr, dhat * dhat);
      EXPECT_EQ(c.n_vertices, n_stencil_vertices(c.kind));
    }
  EXPECT_EQ(found, expected);
  EXPECT_GT(found.size(), 0u);
  EXPECT_NEAR(minimum_distance<dim>(cs, V), minimum_distance<dim>(s, V), 1e-15);
}

TEST(Constraints, BuildMatchesBruteForce)
{
  for (int trial = 0; trial < 3; ++trial)
    {
      check_build_constraints<1>(random_scene_1d(200), 0.01);
      check_build_constraints<2>(random_scene_2d(60), 0.05);
      check_build_constraints<3>(random_scene_3d(40), 0.08);
    }
}

template <int dim>
double brute_force_min_distance(const Scene<dim> &scene)
{
  const auto V = scene.V();
  double     d = std::numeric_limits<double>::infinity();
  for (const auto &c : all_pairs<dim>(scene.surface))
    d = std::min(d, pair_distance_sqr<dim>(scene.surface, V, c));
  return std::sqrt(d);
}

TEST(MinimumDistance, MatchesBruteForce)
{
  for (int trial = 0; trial < 5; ++trial)
    {
      const auto s1 = random_scene_1d(50);
      EXPECT_DOUBLE_EQ(minimum_distance<1>(s1.surface, s1.V()), brute_force_min_distance<1>(s1));
      const auto s2 = random_scene_2d(20);
      EXPECT_DOUBLE_EQ(minimum_distance<2>(s2.surface, s2.V()), brute_force_min_distance<2>(s2));
      const auto s3 = random_scene_3d(10);
      EXPECT_DOUBLE_EQ(minimum_distance<3>(s3.surface, s3.V()), brute_force_min_distance<3>(s3));
    }
}

TEST(MinimumDistance, FarApartBodiesAndEmptyScenes)
{
  // Two tiny segments far apart (no self pairs): the search radius has to grow many times.
  Scene<2> s;
  for (const double x : {0.0, 1000.0})
    {
      const int a = s.add_vertex(Vec<2>(x, 0), false), b = s.add_vertex(Vec<2>(x + 1e-3, 0), false);
      s.surface.edges.push_back({{a, b}});
    }
  EXPECT_DOUBLE_EQ(minimum_distance<2>(s.surface, s.V()), brute_force_min_distance<2>(s));
  EXPECT_NEAR(minimum_distance<2>(s.surface, s.V()), 1000.0 - 1e-3, 1e-9);

  // A single triangle: only self pairs (vertex vs opposite edge).
  Scene<2> one;
  const int a = one.add_vertex(Vec<2>(0, 0), false), b = one.add_vertex(Vec<2>(1, 0), false),
            c = one.add_vertex(Vec<2>(0, 2), false);
  one.surface.edges = {{{a, b}}, {{b, c}}, {{c, a}}};
  EXPECT_NEAR(minimum_distance<2>(one.surface, one.V()), 2.0 / std::sqrt(5.0), 1e-14);

  // No admissible pair at all: +inf.
  Scene<2> segment;
  segment.add_vertex(Vec<2>(0, 0), false);
  segment.add_vertex(Vec<2>(1, 0), false);
  segment.surface.edges = {{{0, 1}}};
  EXPECT_TRUE(std::isinf(minimum_distance<2>(segment.surface, segment.V())));
  Scene<1> lonely;
  lonely.add_vertex(Vec<1>(0.5), false);
  EXPECT_TRUE(std::isinf(minimum_distance<1>(lonely.surface, lonely.V())));
  Scene<3> empty;
  EXPECT_TRUE(std::isinf(minimum_distance<3>(empty.surface, empty.V())));
  EXPECT_TRUE(std::isinf(minimum_distance<3>(std::vector<Constraint>{}, empty.V())));

  // 1D: two rods and a wall.
  Scene<1> rods;
  for (const double x : {0.0, 1.0, 1.25, 2.0})
    rods.add_vertex(Vec<1>(x), false);
  rods.add_vertex(Vec<1>(-0.1), true);
  EXPECT_NEAR(minimum_distance<1>(rods.surface, rods.V()), 0.1, 1e-15);
}

TEST(BroadPhase, LargeScenePerformance)
{
  // ~100K 2D vertices on a grid of small squares; just has to be fast and consistent.
  Scene<2>  s;
  const int m = 158;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      {
        const Vec<2> c(i * 1.0, j * 1.0);
        const int    first = s.surface.n_vertices;
        s.add_vertex(c + Vec<2>(0, 0), false);
        s.add_vertex(c + Vec<2>(0.99, 0), false);
        s.add_vertex(c + Vec<2>(0.99, 0.99), false);
        s.add_vertex(c + Vec<2>(0, 0.99), false);
        for (int k = 0; k < 4; ++k)
          s.surface.edges.push_back({{first + k, first + (k + 1) % 4}});
      }
  const auto V     = s.V();
  const auto start = std::chrono::steady_clock::now();
  const auto cs    = build_constraints<2>(s.surface, V, V, 0.02);
  const auto w     = ConstraintWeights{};
  const auto g     = barrier_gradient<2>(cs, V, 0.02, w);
  const auto H     = barrier_hessian<2>(cs, V, 0.02, w, true);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "[          ] " << s.surface.n_vertices << " vertices, " << cs.size()
            << " constraints, build + gradient + Hessian in " << seconds << " s\n";
  // Each square touches up to 8 neighbours across gaps of 0.01: corner-to-corner pairs
  // and corner-to-edge pairs; every constraint has distance 0.01 or 0.01*sqrt(2).
  EXPECT_GT(cs.size(), static_cast<std::size_t>(4 * (m - 1) * m));
  for (const auto &c : cs)
    EXPECT_GE(c.distance_sqr, 0.99e-4);
  EXPECT_TRUE(g.allFinite());
  EXPECT_GT(H.size(), 0u);
  EXPECT_LE(H.size(), cs.size() * 36);
}
