/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/types.h>

#include <vector>

namespace pcl_holefill
{
/** \brief One rim of missing surface, as found by HoleBoundaryEstimation or
  * given by the user. */
struct BoundaryLoop
{
  /** Indices into the input cloud; consecutive entries are neighbours along the rim. */
  pcl::Indices indices;
  /** The last point links back to the first. */
  bool closed = false;
  /** A hole to fill (true) or the outer border of an open surface (false). */
  bool is_hole = false;
  /** Length of the polyline through the indices. */
  float length = 0.f;
  /** Mean distance from a rim point to its nearest input neighbour. */
  float mean_spacing = 0.f;
  /** Sampling pitch around the rim: sqrt(surface area per point), from the
    * density of the k nearest neighbours; 0 when not measured. */
  float pitch = 0.f;
  /** Largest distance between two rim points: the hole's size. */
  float diameter = 0.f;
};

}  // namespace pcl_holefill
