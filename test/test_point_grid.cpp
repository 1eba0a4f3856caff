/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/ordered_selection.h>
#include <pcl_holefill/detail/point_grid.h>
#include <pcl_holefill/voxel_hash_search.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>

using pcl_holefill::detail::PointGrid;

namespace
{
std::vector<Eigen::Vector3f>
randomPoints (std::size_t n, unsigned seed)
{
  std::mt19937 rng (seed);
  std::uniform_real_distribution<float> u (-1.f, 1.f);
  std::vector<Eigen::Vector3f> points;
  for (std::size_t i = 0; i < n; ++i)
    points.emplace_back (u (rng), u (rng), 0.1f * u (rng));
  return points;
}

std::vector<float>
bruteForceSqrDistances (const std::vector<Eigen::Vector3f> &points, const Eigen::Vector3f &q)
{
  std::vector<float> d;
  for (const auto &p : points)
    d.push_back ((p - q).squaredNorm ());
  std::sort (d.begin (), d.end ());
  return d;
}
}  // namespace

TEST (PointGrid, NearestKMatchesBruteForce)
{
  const auto points = randomPoints (3000, 1);
  PointGrid grid (PointGrid::suggestCellSize (points, 8));
  for (std::size_t i = 0; i < points.size (); ++i)
    grid.insert (points[i], static_cast<int> (i));
  std::vector<PointGrid::Neighbour> found;
  for (const Eigen::Vector3f &q : {Eigen::Vector3f (0, 0, 0), Eigen::Vector3f (0.9f, -0.9f, 0.f),
                                  Eigen::Vector3f (5.f, 5.f, 5.f)})
  {
    grid.nearestK (q, 12, found);
    const auto truth = bruteForceSqrDistances (points, q);
    ASSERT_EQ (found.size (), 12u);
    for (int k = 0; k < 12; ++k)
      EXPECT_FLOAT_EQ (found[k].sqr_distance, truth[k]);
  }
}

TEST (PointGrid, EveryPointsNearestKMatchBruteForceWithTiesBrokenById)
{
  // Random points, then a lattice (many equal distances) and duplicates
  // (distance 0 to another point): each point's k nearest, itself left out,
  // are the brute force's, ties going to the lower id, for 1 and 2 threads.
  auto points = randomPoints (2000, 4);
  for (int x = 0; x < 20; ++x)
    for (int y = 0; y < 20; ++y)
      points.emplace_back (2.f + 0.01f * x, 0.01f * y, 0.f);
  for (int d = 0; d < 50; ++d)
    points.push_back (points[static_cast<std::size_t> (37 * d)]);
  constexpr int k = 16;
  const auto less = [] (const PointGrid::Neighbour &a, const PointGrid::Neighbour &b) {
    return std::tie (a.sqr_distance, a.id) < std::tie (b.sqr_distance, b.id);
  };
  std::vector<std::vector<int>> truth (points.size ());
  for (std::size_t i = 0; i < points.size (); ++i)
  {
    std::vector<PointGrid::Neighbour> all;
    for (std::size_t j = 0; j < points.size (); ++j)
      if (j != i)
        all.push_back ({static_cast<int> (j), (points[j] - points[i]).squaredNorm ()});
    std::partial_sort (all.begin (), all.begin () + k, all.end (), less);
    for (int m = 0; m < k; ++m)
      truth[i].push_back (all[static_cast<std::size_t> (m)].id);
    std::sort (truth[i].begin (), truth[i].end ());
  }
  PointGrid grid (PointGrid::suggestCellSize (points, k));
  grid.build (points, nullptr, 1);
  for (const int threads : {1, 2})
  {
    std::vector<std::vector<int>> found (points.size ());
    grid.forEachNearestK (k, threads, [&] (int i, const PointGrid::Neighbour *neighbours, int count) {
      for (int m = 0; m < count; ++m)
        found[static_cast<std::size_t> (i)].push_back (neighbours[m].id);
      std::sort (found[static_cast<std::size_t> (i)].begin (), found[static_cast<std::size_t> (i)].end ());
    });
    std::size_t differing = 0;
    for (std::size_t i = 0; i < points.size (); ++i)
      differing += found[i] == truth[i] ? 0 : 1;
    EXPECT_EQ (differing, 0u) << threads << " threads";
  }
}

TEST (PointGrid, RadiusMatchesBruteForceAndGrows)
{
  auto points = randomPoints (2000, 2);
  PointGrid grid (0.05f);
  for (std::size_t i = 0; i < points.size (); ++i)
    grid.insert (points[i], static_cast<int> (i));
  // Points added later are found too.
  points.emplace_back (0.01f, 0.f, 0.f);
  grid.insert (points.back (), static_cast<int> (points.size () - 1));
  std::vector<PointGrid::Neighbour> found;
  grid.withinRadius (Eigen::Vector3f::Zero (), 0.17f, found);
  const auto truth = bruteForceSqrDistances (points, Eigen::Vector3f::Zero ());
  const auto inside = std::count_if (truth.begin (), truth.end (), [] (float d) { return d <= 0.17f * 0.17f; });
  EXPECT_EQ (static_cast<long> (found.size ()), inside);
  EXPECT_TRUE (std::any_of (found.begin (), found.end (),
                            [&] (const auto &n) { return n.id == static_cast<int> (points.size () - 1); }));
}

TEST (PointGrid, StrayPointsAndLargeBallsMatchBruteForce)
{
  // A surface and stray points far off it: a stray point's neighbours lie
  // beyond the rings nearestK walks, and a ball of the stray points' own
  // scale spans far more cells than the grid holds. Both take the
  // occupied-cell paths; the answers must stay exact.
  auto points = randomPoints (3000, 3);
  std::mt19937 rng (4);
  std::uniform_real_distribution<float> far (-40.f, 40.f);
  for (int i = 0; i < 20; ++i)
    points.emplace_back (far (rng), far (rng), far (rng));
  PointGrid grid (PointGrid::suggestCellSize (points, 8));
  grid.build (points);
  std::vector<PointGrid::Neighbour> found;
  for (std::size_t s = 3000; s < points.size (); ++s)
  {
    const auto truth = bruteForceSqrDistances (points, points[s]);
    grid.nearestK (points[s], 8, found);
    ASSERT_EQ (found.size (), 8u);
    for (int k = 0; k < 8; ++k)
      EXPECT_FLOAT_EQ (found[k].sqr_distance, truth[k]);
    for (const float radius : {3.f, 30.f, 200.f})
    {
      grid.withinRadius (points[s], radius, found);
      const auto inside = std::count_if (truth.begin (), truth.end (), [&] (float d) { return d <= radius * radius; });
      EXPECT_EQ (static_cast<long> (found.size ()), inside) << "radius " << radius;
    }
  }
}

TEST (PointGrid, IgnoresNonFiniteAndEmptyQueries)
{
  PointGrid grid (0.1f);
  grid.insert (Eigen::Vector3f (std::nanf (""), 0.f, 0.f), 0);
  EXPECT_EQ (grid.size (), 0u);
  std::vector<PointGrid::Neighbour> found;
  grid.nearestK (Eigen::Vector3f::Zero (), 3, found);
  EXPECT_TRUE (found.empty ());
  EXPECT_EQ (PointGrid::suggestCellSize ({}, 8), 0.f);
}

namespace
{
/** Z-order of two cells, by the dimension whose coordinates differ in the
  * highest bit (the comparison of interleaved bits, without interleaving). */
bool
mortonLess (const std::array<std::int64_t, 3> &a, const std::array<std::int64_t, 3> &b)
{
  int dimension = 0;
  std::uint64_t highest = 0;
  for (int d = 0; d < 3; ++d)
  {
    const std::uint64_t differ = static_cast<std::uint64_t> (a[d] ^ b[d]);
    // d wins over a lower dimension when its highest differing bit is at
    // least as high (x < y && x < (x ^ y): x's highest bit is lower than y's).
    const bool lower = differ < highest && differ < (differ ^ highest);
    if (differ != 0 && !lower)
    {
      dimension = d;
      highest = differ;
    }
  }
  return a[dimension] < b[dimension];
}
}  // namespace

TEST (PointGrid, SpatialOrderGoesCellByCellAlongTheZCurveThenByPosition)
{
  // Points on a wavy sheet around the origin (cell coordinates of both
  // signs), repeated positions, and NaN / infinite ones in between: more
  // than one sorting run's worth, so that 1 and 2 threads could differ.
  std::vector<Eigen::Vector3f> points = randomPoints (150000, 11);
  for (std::size_t i = 0; i < points.size (); ++i)
  {
    if (i % 997 == 0)
      points[i].x () = std::nanf ("");
    else if (i % 1009 == 0)
      points[i].z () = std::numeric_limits<float>::infinity ();
    else if (i % 101 == 0)
      points[i] = points[i - 1];
  }
  const float cell = 0.01f;
  const std::vector<int> order = PointGrid::spatialOrder (points, cell, 1);
  EXPECT_EQ (PointGrid::spatialOrder (points, cell, 2), order);
  EXPECT_EQ (PointGrid::spatialOrder (points, cell, 3), order);
  ASSERT_EQ (order.size (), points.size ());
  std::vector<int> sorted = order;
  std::sort (sorted.begin (), sorted.end ());
  for (std::size_t i = 0; i < sorted.size (); ++i)
    ASSERT_EQ (sorted[i], static_cast<int> (i));  // a permutation
  // The reference: cells in Z-order, then x, y, z, index; non-finite last, by index.
  // (The grid multiplies by the cell's inverse, as here: dividing moves a
  // few points on cell faces to the next cell.)
  const float inverse = 1.f / cell;
  const auto cellOf = [inverse] (const Eigen::Vector3f &p) {
    return std::array<std::int64_t, 3>{static_cast<std::int64_t> (std::floor (p.x () * inverse)) + (1 << 20),
                                       static_cast<std::int64_t> (std::floor (p.y () * inverse)) + (1 << 20),
                                       static_cast<std::int64_t> (std::floor (p.z () * inverse)) + (1 << 20)};
  };
  std::vector<int> expected (points.size ());
  for (std::size_t i = 0; i < expected.size (); ++i)
    expected[i] = static_cast<int> (i);
  std::stable_sort (expected.begin (), expected.end (), [&] (int a, int b) {
    const bool fa = points[a].allFinite (), fb = points[b].allFinite ();
    if (fa != fb)
      return fa;
    if (!fa)
      return a < b;
    const auto ca = cellOf (points[a]), cb = cellOf (points[b]);
    if (ca != cb)
      return mortonLess (ca, cb);
    const auto &p = points[a], &q = points[b];
    return std::make_tuple (p.x (), p.y (), p.z (), a) < std::make_tuple (q.x (), q.y (), q.z (), b);
  });
  EXPECT_EQ (order, expected);
}

TEST (PointGrid, SuggestedCellHoldsTheAskedNeighboursOnAPlane)
{
  // n uniformly random points on a unit square: a disc of the suggested
  // cell's radius should hold k of them (pi cell^2 n = k), up to the
  // coarse cells along the square's border, which overstate its area.
  for (const std::size_t n : {20000u, 200000u})
  {
    std::mt19937 rng (5);
    std::uniform_real_distribution<float> u (0.f, 1.f);
    std::vector<Eigen::Vector3f> points;
    for (std::size_t i = 0; i < n; ++i)
      points.emplace_back (u (rng), u (rng), 0.f);
    const float cell = PointGrid::suggestCellSize (points, 16);
    const float expected = std::sqrt (16.f / (3.14159265f * static_cast<float> (n)));
    EXPECT_NEAR (cell, expected, 0.1f * expected) << n << " points";
  }
}

TEST (VoxelHashSearch, IsAPclSearch)
{
  pcl::PointCloud<pcl::PointNormal>::Ptr cloud (new pcl::PointCloud<pcl::PointNormal>);
  for (const auto &p : randomPoints (500, 3))
  {
    pcl::PointNormal q;
    q.getVector3fMap () = p;
    cloud->push_back (q);
  }
  pcl::search::Search<pcl::PointNormal>::Ptr search (new pcl_holefill::VoxelHashSearch<pcl::PointNormal>);
  search->setInputCloud (cloud);
  pcl::Indices idx;
  std::vector<float> d2;
  ASSERT_EQ (search->nearestKSearch ((*cloud)[7], 1, idx, d2), 1);
  EXPECT_EQ (idx[0], 7);
  EXPECT_EQ (d2[0], 0.f);
}

TEST (SelectInOrder, KeepsWhatTheSerialFilterKeepsForAnyNumberOfThreads)
{
  // Runs kept and dropped of every length, an odd count that the blocks do
  // not divide, and none at all.
  for (const std::ptrdiff_t n : {std::ptrdiff_t (0), std::ptrdiff_t (1), std::ptrdiff_t (100003)})
  {
    const auto keep = [] (std::ptrdiff_t i) { return (i / 7) % 3 != 1 && i % 11 != 4; };
    const auto value = [] (std::ptrdiff_t i) { return static_cast<int> (3 * i + 1); };
    std::vector<int> expected;
    for (std::ptrdiff_t i = 0; i < n; ++i)
      if (keep (i))
        expected.push_back (value (i));
    for (const int threads : {1, 2, 3, 5})
    {
      std::vector<int> out = {42};  // replaced, not appended to
      pcl_holefill::detail::selectInOrder (n, threads, keep, value, out);
      EXPECT_EQ (out, expected) << n << " points, " << threads << " threads";
    }
  }
}
