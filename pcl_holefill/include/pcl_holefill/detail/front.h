/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_holefill::detail
{
/** \brief One point of a hole boundary that the filler moves inwards. */
struct FrontVertex
{
  Eigen::Vector3f position;
  Eigen::Vector3f normal;  //!< unit
};

/** \brief An ordered piece of hole boundary: the whole loop at first, pieces
  * of it once parts have met (the paper's Fig. 11). */
struct FrontChain
{
  std::vector<FrontVertex> vertices;
  bool closed = false;
  /** Sampled by a contraction pass, d_eq apart; false for a rim of input
    * points or the boundary of an opening, whose spacing is the input's. */
  bool sampled = false;
};

/** \brief The whole boundary of one hole in one pass (B' or B in the paper). */
using Front = std::vector<FrontChain>;

/** \brief Counts of one contraction pass, for the termination rule and the report. */
struct ContractionStats
{
  std::size_t former_boundary_points = 0;  //!< |B'|
  std::size_t kept_control_points = 0;     //!< control points that survived
  std::size_t repelled = 0;                //!< candidates discarded by the elastic force (fronts met)
  std::size_t too_close = 0;               //!< candidates on top of existing surface (hole closed there)
  std::size_t rejected_by_constraint = 0;  //!< overshooting candidates (section 4.4)
  std::size_t unsupported = 0;             //!< no weighted neighbour
  std::size_t outside_bound = 0;           //!< outside the hole's bounding ball
  std::size_t beyond_rim = 0;              //!< not enclosed by the hole's rim
  std::size_t samples = 0;                 //!< points of the new boundary B
};

/** \brief Number of vertices over all chains. */
inline std::size_t
frontSize (const Front &front)
{
  std::size_t n = 0;
  for (const auto &chain : front)
    n += chain.vertices.size ();
  return n;
}

/** \brief Total polyline length over all chains. */
float
frontLength (const Front &front);

}  // namespace pcl_holefill::detail
