/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/PolygonMesh.h>
#include <pcl/conversions.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/surface/mls.h>
#include <pcl/surface/poisson.h>

#include <chrono>
#include <cmath>
#include <limits>

/** PCL's own ways to fill holes, the yardsticks of the benches (bench code only). */
namespace bench
{
/** \brief PCL MovingLeastSquares with VOXEL_GRID_DILATION (order 2, radius
  * 6 \a spacing, voxel 1.5 \a spacing), dilated enough steps to reach the
  * middle of a hole of \a hole_radius; \a seconds gets its time. */
inline pcl::PointCloud<pcl::PointNormal>
runMls (const pcl::PointCloud<pcl::PointNormal>::Ptr &input, double spacing, double hole_radius, double &seconds)
{
  pcl::PointCloud<pcl::PointNormal> output;
  pcl::MovingLeastSquares<pcl::PointNormal, pcl::PointNormal> mls;
  mls.setInputCloud (input);
  mls.setSearchMethod (pcl::search::KdTree<pcl::PointNormal>::Ptr (new pcl::search::KdTree<pcl::PointNormal>));
  mls.setSearchRadius (6.0 * spacing);
  mls.setPolynomialOrder (2);
  mls.setComputeNormals (true);
  mls.setUpsamplingMethod (pcl::MovingLeastSquares<pcl::PointNormal, pcl::PointNormal>::VOXEL_GRID_DILATION);
  mls.setDilationVoxelSize (static_cast<float> (1.5 * spacing));
  mls.setDilationIterations (static_cast<int> (std::ceil (hole_radius / (1.5 * spacing))) + 1);
  const auto start = std::chrono::steady_clock::now ();
  mls.process (output);
  seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
  return output;
}

/** \brief PCL Poisson at \a depth; its mesh's vertices as points (no normals). */
inline pcl::PointCloud<pcl::PointNormal>
runPoisson (const pcl::PointCloud<pcl::PointNormal>::Ptr &input, int depth, double &seconds)
{
  pcl::Poisson<pcl::PointNormal> poisson;
  poisson.setInputCloud (input);
  poisson.setDepth (depth);
  pcl::PolygonMesh mesh;
  const auto start = std::chrono::steady_clock::now ();
  poisson.reconstruct (mesh);
  seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
  pcl::PointCloud<pcl::PointXYZ> vertices;
  pcl::fromPCLPointCloud2 (mesh.cloud, vertices);
  pcl::PointCloud<pcl::PointNormal> output;
  for (const auto &v : vertices)
  {
    pcl::PointNormal p;
    p.getVector3fMap () = v.getVector3fMap ();
    p.normal_x = p.normal_y = p.normal_z = std::numeric_limits<float>::quiet_NaN ();
    output.push_back (p);
  }
  return output;
}
}  // namespace bench
