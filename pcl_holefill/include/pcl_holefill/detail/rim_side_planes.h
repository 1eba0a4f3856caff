/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl_holefill::detail
{
/** \brief A plane that a stretch of the rim runs in, with the rest of the
  * rim on one side: a face of the part that the hole took, seen from its
  * border only.
  *
  * A CAD mesh's vertices sample a flat face on its boundary edges only, and
  * PCA gives those the normal of the face beside it (the denser one). A
  * hole that takes most of such a face leaves rim points all in its plane
  * whose normals lie along the plane: the fill continued the face beside it
  * past the edge, out of the part (fandisk's vertices, estimated normals:
  * 10.4 spacings off, 3.5 past the cut ball), and no tangent plane of the
  * rim held it. */
struct RimSidePlane
{
  Eigen::Vector3f point = Eigen::Vector3f::Zero ();
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ ();  //!< unit, pointing away from the rim
  std::vector<int> on;                                  //!< the rim points within the tolerance of it
  /** Do the normals of the points on it agree (their mean at least
    * kMinTurnAgreement long)? Then they are the face beside's, and take the
    * plane's normal for the fill: their fronts run down the taken face. At a
    * thin plate's end the points on the end's plane are both faces', with
    * opposite normals, and keep them. */
  bool turns_rim = false;
};

/** \brief The side planes of the rim \a positions (in loop order, the loop
  * closed) with unit \a normals: a window of kSideWindow points on either
  * side of every kSideWindow-th point that lies in a plane (variance along
  * its normal within \a tolerance squared) and spans it (a standard
  * deviation of twice \a tolerance at least along its narrower direction
  * within the plane), where at least
  * 3 kSideWindow rim points lie within \a tolerance of that plane and
  * every other one below it, and the normals of those on it lie along it
  * (the mean |n . m| at most kMaxSideAlong: a flat hole's rim, or a cap's,
  * has its normals across its plane). More rim points must lie below it than
  * on it: the rim of a hole around a steep apex is a ring in one plane, within
  * the tolerance at 0.1 % noise, with normals along it (the corpus's pyramid:
  * 100 -> 63 % covered when taken for a side); and the rim must reach
  * farther below it than the window is long (kMinSideDepth): a box's
  * missing lid leaves a rim in the lid's plane, a pitch deep at most. A rim
  * without points off the plane (a loop around a rod) gives none. */
std::vector<RimSidePlane>
findRimSidePlanes (const std::vector<Eigen::Vector3f> &positions, const std::vector<Eigen::Vector3f> &normals,
                   float tolerance);

}  // namespace pcl_holefill::detail
