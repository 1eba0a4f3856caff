/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/detail/ordered_selection.h>

#include <pcl/point_cloud.h>
#include <pcl/types.h>

#include <cmath>

namespace pcl_holefill::detail
{
/** \brief True for a point with finite coordinates and a finite normal that is
  * not (nearly) zero: the only points the method can use. */
template <typename PointT> inline bool
isOrientedPoint (const PointT &p)
{
  if (!std::isfinite (p.x) || !std::isfinite (p.y) || !std::isfinite (p.z))
    return false;
  const float n2 = p.normal_x * p.normal_x + p.normal_y * p.normal_y + p.normal_z * p.normal_z;
  return std::isfinite (n2) && n2 > 1e-12f;
}

/** \brief The entries of \a indices that are oriented points, in their
  * order (tested by \a threads threads); returns how many were skipped. */
template <typename PointT> inline std::size_t
keepOrientedPoints (const pcl::PointCloud<PointT> &cloud, const pcl::Indices &indices, pcl::Indices &kept,
                    int threads = 1)
{
  const auto oriented = [&] (std::ptrdiff_t i) { return isOrientedPoint (cloud[indices[i]]); };
  const auto index = [&] (std::ptrdiff_t i) { return indices[i]; };
  selectInOrder (static_cast<std::ptrdiff_t> (indices.size ()), threads, oriented, index, kept);
  return indices.size () - kept.size ();
}

/** \brief True when every index addresses a point of a cloud of \a size
  * points (PCL's own initCompute does not check). */
inline bool
indicesInRange (const pcl::Indices &indices, std::size_t size)
{
  for (const auto i : indices)
    if (i < 0 || static_cast<std::size_t> (i) >= size)
      return false;
  return true;
}

}  // namespace pcl_holefill::detail
