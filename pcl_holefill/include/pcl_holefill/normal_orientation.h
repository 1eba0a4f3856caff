/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/point_cloud.h>

namespace pcl_holefill
{
/** \brief Flips normals so that neighbours agree (the estimated normals of
  * PCL's NormalEstimation have an arbitrary sign per point, and the filler
  * needs one side of the surface to be "out").
  *
  * A best-first walk over the k nearest neighbours, from the point highest
  * along z in each connected part, flips each newly reached normal to agree
  * with the points reached before it, following the most reliable links
  * first. Then each part as a whole is turned outward if it is closed (its
  * normals point away from its centroid, or, for a thin part such as a
  * plate or a bowl's shell, the volume they enclose is positive), else
  * upward (+z).
  * Agreement is the normals' dot product plus a sharp-edge term: across a
  * convex edge each point lies below the other's tangent plane, across a
  * concave one above it, so two faces meeting at a right angle (dot 0) still
  * orient each other. Linear in the cloud with a kNN per point.
  * Points with no usable normal are left alone. Returns how many were flipped. */
template <typename PointT> std::size_t
orientNormalsConsistently (pcl::PointCloud<PointT> &cloud, int k = 12);

/** \brief The share of neighbour pairs (k nearest, on up to \a samples
  * points spread over the cloud) whose normals point opposite ways (cosine
  * under -0.5): about 0 for an oriented cloud, about 0.5 for random signs. */
template <typename PointT> float
flippedNeighbourShare (const pcl::PointCloud<PointT> &cloud, int k = 8, std::size_t samples = 2000);

}  // namespace pcl_holefill

#ifdef PCL_NO_PRECOMPILE
#include <pcl_holefill/impl/normal_orientation.hpp>
#endif
