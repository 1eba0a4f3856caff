/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "normal_estimation.h"

#include <pcl_holefill/normal_orientation.h>

#include <pcl/common/io.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/search/kdtree.h>

#include <cmath>

namespace pcl_holefill_tool
{
namespace
{
// Neighbours of the PCA normal: what PCL's tools and most users take.
constexpr int kNormalNeighbours = 16;
}  // namespace

void
estimateOrientedNormals (pcl::PointCloud<pcl::PointNormal> &cloud, unsigned int threads)
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr xyz (new pcl::PointCloud<pcl::PointXYZ>);
  pcl::copyPointCloud (cloud, *xyz);
  xyz->is_dense = true;
  for (const auto &p : *xyz)
    xyz->is_dense = xyz->is_dense && std::isfinite (p.x) && std::isfinite (p.y) && std::isfinite (p.z);
  pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> estimation (threads);
  estimation.setInputCloud (xyz);
  estimation.setSearchMethod (pcl::search::KdTree<pcl::PointXYZ>::Ptr (new pcl::search::KdTree<pcl::PointXYZ>));
  estimation.setKSearch (kNormalNeighbours);
  pcl::PointCloud<pcl::Normal> normals;
  estimation.compute (normals);
  for (std::size_t i = 0; i < normals.size (); ++i)
    cloud[i].getNormalVector3fMap () = normals[i].getNormalVector3fMap ();
  pcl_holefill::orientNormalsConsistently (cloud);
}

}  // namespace pcl_holefill_tool
