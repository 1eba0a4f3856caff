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
  * A breadth-first walk over the k nearest neighbours, from the point highest
  * along z in each connected part (its normal is made to point up, i.e. out
  * of a closed object), flips each newly reached normal to agree with the
  * point it was reached from, visiting the most reliable links (the most
  * parallel normals) first. Linear in the cloud with a kNN per point.
  * Points with no usable normal are left alone. Returns how many were flipped. */
template <typename PointT> std::size_t
orientNormalsConsistently (pcl::PointCloud<PointT> &cloud, int k = 12);

}  // namespace pcl_holefill
