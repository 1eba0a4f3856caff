/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/normal_orientation.h>
#include <pcl_holefill/point_grid.h>
#include <pcl_holefill/point_validity.h>

#include <algorithm>
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

  // How much two oriented points agree: the normals' dot product, plus, for
  // points across a sharp edge (dot near 0), whether each lies on the same
  // side of the other's tangent plane (both below on a convex edge, both
  // above on a concave one). Positive: consistent; negative: one is flipped.
  auto agreement = [&] (int a, int b) {
    const Eigen::Vector3f na = normal (a).normalized (), nb = normal (b).normalized ();
    const Eigen::Vector3f d = positions[b] - positions[a];
    const float length = d.norm ();
    const float side = length > 0.f ? (d.dot (na) / length) * (-d.dot (nb) / length) : 0.f;
    return na.dot (nb) + 2.f * side;
  };
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
          links.push ({std::abs (agreement (from, n.id)), {from, n.id}});
    };
    push_links (seed);
    while (!links.empty ())  // every point is reached once and pushes at most k links
    {
      const auto [from, to] = links.top ().second;
      links.pop ();
      if (reached[to])
        continue;
      reached[to] = 1;
      if (agreement (from, to) < 0.f)
      {
        normal (to) = -normal (to);
        ++flipped;
      }
      push_links (to);
    }
  }
  return flipped;
}

template <typename PointT> float
flippedNeighbourShare (const pcl::PointCloud<PointT> &cloud, const pcl::search::Search<PointT> &search, int k,
                       std::size_t samples)
{
  if (cloud.empty () || samples == 0)
    return 0.f;
  std::size_t pairs = 0, flipped = 0;
  pcl::Indices found;
  std::vector<float> sqr_distances;
  const std::size_t stride = std::max<std::size_t> (1, cloud.size () / samples);
  for (std::size_t i = 0; i < cloud.size (); i += stride)
  {
    if (!isOrientedPoint (cloud[i]))
      continue;
    const Eigen::Vector3f n = cloud[i].getNormalVector3fMap ().normalized ();
    search.nearestKSearch (cloud[i], k + 1, found, sqr_distances);
    for (const auto j : found)
      if (j != static_cast<int> (i) && isOrientedPoint (cloud[j]))
      {
        ++pairs;
        flipped += n.dot (cloud[j].getNormalVector3fMap ().normalized ()) < -0.5f;
      }
  }
  return pairs ? static_cast<float> (flipped) / pairs : 0.f;
}

template <typename PointT> float
flippedNeighbourShare (const pcl::PointCloud<PointT> &cloud, int k, std::size_t samples)
{
  // An even subsample of at most 25 x samples points is enough to see
  // orientation, and keeps this check small next to the cloud.
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
  const std::size_t keep_every = std::max<std::size_t> (1, cloud.size () / (25 * std::max<std::size_t> (samples, 1)));
  for (std::size_t i = 0; i < cloud.size (); i += keep_every)
    if (isOrientedPoint (cloud[i]))
    {
      positions.push_back (cloud[i].getVector3fMap ());
      normals.push_back (cloud[i].getNormalVector3fMap ().normalized ());
    }
  if (positions.size () < 2 || samples == 0)
    return 0.f;
  PointGrid grid (PointGrid::suggestCellSize (positions, k));
  grid.build (positions);
  std::vector<PointGrid::Neighbour> near;
  std::size_t pairs = 0, flipped = 0;
  const std::size_t stride = std::max<std::size_t> (1, positions.size () / samples);
  for (std::size_t i = 0; i < positions.size (); i += stride)
  {
    grid.nearestK (positions[i], k + 1, near);
    for (const auto &n : near)
      if (n.id != static_cast<int> (i))
      {
        ++pairs;
        flipped += normals[i].dot (normals[n.id]) < -0.5f;
      }
  }
  return pairs ? static_cast<float> (flipped) / pairs : 0.f;
}

}  // namespace pcl_holefill

#define PCL_INSTANTIATE_flippedNeighbourShare(T) \
  template float pcl_holefill::flippedNeighbourShare<T> (const pcl::PointCloud<T> &, int, std::size_t); \
  template float pcl_holefill::flippedNeighbourShare<T> (const pcl::PointCloud<T> &, \
                                                         const pcl::search::Search<T> &, int, std::size_t);
#define PCL_INSTANTIATE_orientNormalsConsistently(T) \
  template std::size_t pcl_holefill::orientNormalsConsistently<T> (pcl::PointCloud<T> &, int);
