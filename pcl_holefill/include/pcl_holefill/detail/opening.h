/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl_holefill::detail
{
/** \brief Openings: holes whose rim is a crease all round.
  *
  * At the end of a tube, or where a box lost a whole face (the underside of
  * a scanned object, an opening of a mechanical part), the surface left
  * meets the missing part along a crease that runs round the whole rim: the
  * rim's normals lie across the surface that the loop spans, not along it.
  * The paper's contraction direction (n x t) then points along the walls,
  * out of the loop, and the fronts carry the walls on past the rim (a box
  * without its lid, random samples: walls grown 0.97 below it). Nothing in
  * the rim's normals knows the missing face: the loop does. Its vector area
  * gives the face's axis, and the face meets the walls on the convex side
  * (the walls' normals point away from the loop's inside when the normals
  * point out of the solid, towards it when they point in).
  */

/** \brief The share of \a filled positions that lie on walls past the
  * loop through \a loop_positions: farther from the loop's plane (through
  * its centroid, across its axis: vectorArea) than half the rim's mean
  * distance R from the axis, and still at least kWallRadius R from the
  * axis. A fill that closes in on its loop (a face, a cap, a pyramid's
  * apex) has nothing far past the rim that is not also near the axis. */
float
shareAlongWalls (const std::vector<Eigen::Vector3f> &loop_positions, const std::vector<Eigen::Vector3f> &filled);

/** \brief The mean |n . a| of the unit \a normals against the axis a of the
  * loop through \a loop_positions (vectorArea): 1 on a face the loop lies
  * in, ~0 on walls parallel to the axis; 1 when the loop spans nothing. */
float
alignmentWithLoop (const std::vector<Eigen::Vector3f> &loop_positions, const std::vector<Eigen::Vector3f> &normals);

/** \brief The normal of the face that closes an opening, oriented like the
  * walls' normals (outwards when theirs point out of the solid): the loop's
  * axis, turned away from \a walls_centroid (the mean of the points around
  * the rim) and then flipped when the walls' normals face the loop's inside.
  * Zero when the loop spans nothing. */
Eigen::Vector3f
openingNormal (const std::vector<Eigen::Vector3f> &positions, const std::vector<Eigen::Vector3f> &normals,
               const Eigen::Vector3f &walls_centroid);

/** \brief RMS distance of \a positions from their mean along the unit \a direction. */
float
depthAlong (const std::vector<Eigen::Vector3f> &positions, const Eigen::Vector3f &direction);

/** \brief The \a quantile (0-1) of \a positions' heights along the unit \a direction. */
float
quantileAlong (const std::vector<Eigen::Vector3f> &positions, const Eigen::Vector3f &direction, float quantile);

}  // namespace pcl_holefill::detail
