/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl_holefill
{
/** \brief The widest empty sector around a point, seen in its tangent plane. */
struct AngularGap
{
  float angle = 0.f;                                    //!< radians, 0..2pi
  Eigen::Vector3f direction = Eigen::Vector3f::Zero (); //!< unit, tangent, bisects the gap
};

/** \brief Where a neighbour at \a offset from a point would lie in the
  * point's tangent plane if the surface between them were flattened. On a
  * smooth patch this is the plain projection; beyond a sharp edge (normals
  * more than ~12 degrees apart) the neighbour's height is laid out towards
  * the edge, so it keeps its true distance and lands beyond the edge instead
  * of being squeezed onto it. */
Eigen::Vector3f
unfoldIntoTangentPlane (const Eigen::Vector3f &offset, const Eigen::Vector3f &unit_normal,
                        const Eigen::Vector3f &neighbour_normal);

/** \brief The angular-gap boundary test (as PCL's BoundaryEstimation): the
  * neighbours are projected on the tangent plane of \a point and the largest
  * angle between consecutive ones is returned with its bisector, which points
  * into the missing surface.
  *
  * Where PCL projects every neighbour straight onto the tangent plane, this
  * test first unfolds neighbours that lie beyond a sharp edge (their normal
  * turns away by more than ~12 degrees) into the plane, as the surface would
  * lie if flattened: a plain projection squeezes the other face onto a thin
  * sliver next to the point and opens false gaps along every edge and corner
  * of a solid (PCL issue #5075). On smooth surfaces the two agree. Neighbours
  * that land on the point itself carry no direction and are ignored. At most
  * 64 neighbours are used. */
AngularGap
largestAngularGap (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal,
                   const std::vector<Eigen::Vector3f> &neighbours,
                   const std::vector<Eigen::Vector3f> &neighbour_normals);

}  // namespace pcl_holefill
