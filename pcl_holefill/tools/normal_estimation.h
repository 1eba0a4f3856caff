/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace pcl_holefill_tool
{
/** \brief Normals for a cloud that has none, as the command and the Python
  * module give them: PCL NormalEstimationOMP (k = 16 nearest neighbours),
  * then consistently oriented (pcl_holefill::orientNormalsConsistently).
  * Non-finite points get NaN normals. */
void
estimateOrientedNormals (pcl::PointCloud<pcl::PointNormal> &cloud, unsigned int threads);

}  // namespace pcl_holefill_tool
