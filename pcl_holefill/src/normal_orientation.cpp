/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/instantiation.h>
#include <pcl_holefill/normal_orientation.h>
#include <pcl_holefill/point_grid.h>
#include <pcl_holefill/point_validity.h>

#include <cmath>
#include <queue>

namespace pcl_holefill
{
template <typename PointT> std::size_t
orientNormalsConsistently (pcl::PointCloud<PointT> &cloud, int k)
{
  std::vector<Eigen::Vector3f> positions;
  std::vector<int> usable;
  for (std::size_t i = 0; i < cloud.size (); ++i)
    if (isOrientedPoint (cloud[i]))
    {
      usable.push_back (static_cast<int> (i));
      positions.push_back (cloud[i].getVector3fMap ());
    }
  if (usable.empty ())
    return 0;
  PointGrid grid (PointGrid::suggestCellSize (positions, k));
  for (std::size_t i = 0; i < positions.size (); ++i)
    grid.insert (positions[i], static_cast<int> (i));
  auto normal = [&] (int local) { return cloud[usable[local]].getNormalVector3fMap (); };

  std::vector<char> reached (usable.size (), 0);
  // Seeds in order of decreasing z: each unreached one starts a new part.
  std::vector<int> seeds (usable.size ());
  for (std::size_t i = 0; i < seeds.size (); ++i)
    seeds[i] = static_cast<int> (i);
  std::sort (seeds.begin (), seeds.end (), [&] (int a, int b) { return positions[a].z () > positions[b].z (); });
  std::size_t flipped = 0;
  std::vector<PointGrid::Neighbour> near;
  using Link = std::pair<float, std::pair<int, int>>;  // (agreement, (from, to)), best first
  for (const int seed : seeds)
  {
    if (reached[seed])
      continue;
    reached[seed] = 1;
    if (normal (seed).z () < 0.f)
    {
      normal (seed) = -normal (seed);
      ++flipped;
    }
    std::priority_queue<Link> links;
    auto push_links = [&] (int from) {
      grid.nearestK (positions[from], k + 1, near);
      for (const auto &n : near)
        if (!reached[n.id])
          links.push ({std::abs (normal (from).normalized ().dot (normal (n.id).normalized ())), {from, n.id}});
    };
    push_links (seed);
    while (!links.empty ())  // every point is reached once and pushes at most k links
    {
      const auto [from, to] = links.top ().second;
      links.pop ();
      if (reached[to])
        continue;
      reached[to] = 1;
      if (normal (from).dot (normal (to)) < 0.f)
      {
        normal (to) = -normal (to);
        ++flipped;
      }
      push_links (to);
    }
  }
  return flipped;
}

#define PCL_INSTANTIATE_orientNormalsConsistently(T) \
  template std::size_t orientNormalsConsistently<T> (pcl::PointCloud<T> &, int);
PCL_HOLEFILL_INSTANTIATE (orientNormalsConsistently)

}  // namespace pcl_holefill
