/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/stray_points.h>

#include <pcl_holefill/detail/boundary_point_test.h>
#include <pcl_holefill/detail/point_grid.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_holefill::detail
{
namespace
{
constexpr int kStrayNeighbours = 8;
// A stray's nearest neighbour is farther than this many pitches of its neighbours.
constexpr float kStrayPitches = 2.f;
// ... or its second nearest this many more (isStrayPoint: a pair of strays).
constexpr float kPairMargin = 0.5f;
}  // namespace

bool
isStrayPoint (float nearest, float second, float *around, int count, float pitches)
{
  if (count == 0 || !std::isfinite (nearest))
    return false;
  std::nth_element (around, around + count / 2, around + count);
  const float pitch = around[count / 2];
  return nearest > pitches * pitch || (std::isfinite (second) && second > (pitches + kPairMargin) * pitch);
}

std::vector<char>
markStrayPoints (const std::vector<Eigen::Vector3f> &positions, int threads)
{
  const std::size_t n = positions.size ();
  std::vector<char> stray (n, 0);
  if (n <= static_cast<std::size_t> (kStrayNeighbours))
    return stray;
  PointGrid grid (PointGrid::suggestCellSize (positions, kStrayNeighbours));
  grid.build (positions, nullptr, threads);
  std::vector<NearestTwo> nearest (n);
  std::vector<float> pitch (n, 0.f);
  std::vector<int> neighbours (n * kStrayNeighbours, -1);
  grid.forEachNearestK (kStrayNeighbours, threads, [&] (int i, const PointGrid::Neighbour *found, int count) {
    float farthest = 0.f;
    for (int k = 0; k < count; ++k)
    {
      neighbours[static_cast<std::size_t> (i) * kStrayNeighbours + k] = found[k].id;
      nearest[i].add (found[k].sqr_distance);
      farthest = std::max (farthest, found[k].sqr_distance);
    }
    pitch[i] = samplingPitch (farthest, count, 0.f);
  });
#pragma omp parallel for num_threads(std::max (threads, 1)) schedule(static)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (n); ++i)
  {
    float around[kStrayNeighbours];
    int count = 0;
    for (int k = 0; k < kStrayNeighbours; ++k)
    {
      const int j = neighbours[static_cast<std::size_t> (i) * kStrayNeighbours + k];
      if (j >= 0)
        around[count++] = pitch[j];
    }
    stray[i] = isStrayPoint (std::sqrt (nearest[i].nearest), std::sqrt (nearest[i].second), around, count,
                             kStrayPitches)
                   ? 1
                   : 0;
  }
  return stray;
}
}  // namespace pcl_holefill::detail
