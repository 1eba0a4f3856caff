/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/detail/normal_propagation.h>
#include <pcl_holefill/detail/point_validity.h>
#include <pcl_holefill/detail/thread_count.h>

#include <pcl/console/print.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace pcl_holefill::detail
{
template <typename PointT> bool
NormalPropagation<PointT>::checkParameters (const char *caller) const
{
  const bool sigma_n_ok = kernel_.sigma_n > 0.f;  // kSup (infinity) passes, NaN fails
  if (!(radius_ > 0.f && std::isfinite (radius_)) || !(kernel_.sigma_d > 0.f && std::isfinite (kernel_.sigma_d)) ||
      !sigma_n_ok)
  {
    PCL_ERROR ("[pcl_holefill::%s] Invalid parameters: radius = %g and sigma_d = %g must be finite and > 0, "
               "sigma_n = %g must be > 0 (or kSup).\n", caller, radius_, kernel_.sigma_d, kernel_.sigma_n);
    return false;
  }
  if (!input_ || !search_)
  {
    PCL_ERROR ("[pcl_holefill::%s] An input cloud and a search method over it are required.\n", caller);
    return false;
  }
  return true;
}

template <typename PointT> void
NormalPropagation<PointT>::gatherNeighbourhood (const Eigen::Vector3f &position, Neighbourhood &neighbours,
                                                float radius) const
{
  neighbours.clear ();
  PointT query;
  query.getVector3fMap () = position;
  // Kept from call to call: allocating them was a tenth of the fill.
  thread_local pcl::Indices found;
  thread_local std::vector<float> sqr_distances;
  search_->radiusSearch (query, radius > 0.f ? radius : radius_, found, sqr_distances);
  for (const auto i : found)
  {
    const PointT &p = (*input_)[i];
    if (!isOrientedPoint (p))
      continue;
    neighbours.positions.push_back (p.getVector3fMap ());
    neighbours.normals.push_back (p.getNormalVector3fMap ().normalized ());
    neighbours.indices.push_back (i);
  }
}

template <typename PointT> void
NormalPropagation<PointT>::selectNeighbourhood (const Neighbourhood &wider, const Eigen::Vector3f &position,
                                                Neighbourhood &neighbours) const
{
  // The test and the order of the search (VoxelHashSearch: d2 <= r^2 in
  // float, sorted by d2), so that the estimates come out the same bit for bit.
  thread_local std::vector<std::pair<float, int>> inside;
  inside.clear ();
  const float sqr = radius_ * radius_;
  for (std::size_t i = 0; i < wider.size (); ++i)
  {
    const Eigen::Vector3f &p = wider.positions[i];
    const float dx = p.x () - position.x (), dy = p.y () - position.y (), dz = p.z () - position.z ();
    const float d2 = dx * dx + dy * dy + dz * dz;
    if (d2 <= sqr)
      inside.emplace_back (d2, static_cast<int> (i));
  }
  std::sort (inside.begin (), inside.end (), [] (const auto &a, const auto &b) { return a.first < b.first; });
  neighbours.clear ();
  for (const auto &[d2, i] : inside)
  {
    neighbours.positions.push_back (wider.positions[i]);
    neighbours.normals.push_back (wider.normals[i]);
    neighbours.indices.push_back (wider.indices[i]);
  }
}

template <typename PointT> SurfaceEstimate
NormalPropagation<PointT>::computeNormal (const Eigen::Vector3f &position,
                                          const Eigen::Vector3f &reference_normal) const
{
  Neighbourhood neighbours;
  gatherNeighbourhood (position, neighbours);
  return computeNormal (neighbours, position, reference_normal);
}

template <typename PointT> bool
NormalPropagation<PointT>::propagate (PointCloud &candidates, const std::vector<Eigen::Vector3f> &reference_normals)
{
  if (!checkParameters ("NormalPropagation::propagate"))
    return false;
  if (reference_normals.size () != candidates.size ())
  {
    PCL_ERROR ("[pcl_holefill::NormalPropagation::propagate] %zu candidates but %zu reference normals.\n",
               candidates.size (), reference_normals.size ());
    return false;
  }
#pragma omp parallel for num_threads(resolveThreadCount (threads_)) schedule(dynamic, 256)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (candidates.size ()); ++i)
  {
    const SurfaceEstimate e = computeNormal (candidates[i].getVector3fMap (), reference_normals[i]);
    candidates[i].getNormalVector3fMap () =
        e.valid ? e.normal : Eigen::Vector3f::Constant (std::numeric_limits<float>::quiet_NaN ());
  }
  return true;
}

}  // namespace pcl_holefill::detail

#define PCL_INSTANTIATE_NormalPropagation(T) template class pcl_holefill::detail::NormalPropagation<T>;
