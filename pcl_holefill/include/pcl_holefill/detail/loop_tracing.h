/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace pcl_holefill::detail
{
/** \brief The boundary points of one connected rim, in walking order. */
struct TracedLoop
{
  std::vector<int> members;  //!< indices into the arrays given to traceBoundaryLoops
  bool closed = false;
};

/** \brief Chains flagged boundary points into ordered loops.
  *
  * Two points are linked when closer than the longer of their
  * \a link_distances (one per point: where a cloud is sampled more sparsely,
  * its rim points lie farther apart); each connected set is walked along its
  * tangent (normal x gap direction, so the missing surface stays on one
  * side), always to the nearest unvisited point ahead. Points a row behind
  * the walk are absorbed, so a rim two points deep gives one loop; a gap
  * shorter than the link is jumped; spurs, which the walk never needs, are
  * left out. Sets with fewer than \a min_points are dropped. Every loop runs
  * a bounded number of steps (the size of its set). */
std::vector<TracedLoop>
traceBoundaryLoops (const std::vector<Eigen::Vector3f> &positions,
                    const std::vector<Eigen::Vector3f> &normals,
                    const std::vector<Eigen::Vector3f> &gap_directions,
                    const std::vector<float> &link_distances, int min_points);

/** \brief traceBoundaryLoops with one \a link_distance for every point. */
inline std::vector<TracedLoop>
traceBoundaryLoops (const std::vector<Eigen::Vector3f> &positions,
                    const std::vector<Eigen::Vector3f> &normals,
                    const std::vector<Eigen::Vector3f> &gap_directions, float link_distance,
                    int min_points)
{
  return traceBoundaryLoops (positions, normals, gap_directions,
                             std::vector<float> (positions.size (), link_distance), min_points);
}

/** \brief The paper's section 3.3: between consecutive \a feature points
  * (indices of a cloud), recursively insert the cloud point nearest to each
  * segment's midpoint until no new point appears. At most \a max_points in
  * the result. \a position_of maps an index to its position and
  * \a nearest_index a midpoint and the segment's two ends to the nearest
  * cloud index on the ends' surface (or -1). */
std::vector<int>
refineByMidpoints (const std::vector<int> &features, bool closed,
                   const std::function<Eigen::Vector3f (int)> &position_of,
                   const std::function<int (const Eigen::Vector3f &, int, int)> &nearest_index,
                   std::size_t max_points);

/** \brief True when the missing surface lies inside the loop (a hole), false
  * when it lies outside (the outer border of an open surface): the gap
  * directions, their parts across the surface the loop spans, point towards
  * the loop's centroid for a hole, away from it for a border, and along the
  * walls (neither) at an opening, which is a hole (detail/opening.h). */
bool
gapsPointInside (const std::vector<Eigen::Vector3f> &loop_positions,
                 const std::vector<Eigen::Vector3f> &loop_gap_directions);

/** \brief The loop's vector area, 1/2 sum of (p_i - c) x (p_i+1 - c) about
  * its centroid c: its direction is the axis of the surface the loop spans,
  * whatever the normals of its points (zero for a loop that spans nothing). */
Eigen::Vector3f
vectorArea (const std::vector<Eigen::Vector3f> &loop_positions);

/** \brief Largest distance between two loop points (exact up to 2000 points,
  * on an even subsample beyond). */
float
loopDiameter (const std::vector<Eigen::Vector3f> &loop_positions);

/** \brief Length of the polyline, closed or not. */
float
loopLength (const std::vector<Eigen::Vector3f> &loop_positions, bool closed);

}  // namespace pcl_holefill::detail
