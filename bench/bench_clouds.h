/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include "shapes.h"

#include <pcl/features/normal_3d_omp.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <random>

namespace bench
{
/** \brief \a count balls of radius \a radius centred on the unit-cube
  * sphere, at least 3 radii apart: the holes of the large benchmark clouds. */
inline std::vector<pcl_holefill::shapes::Ball>
sphereHoles (std::size_t count, double radius, unsigned seed)
{
  std::mt19937 rng (seed);
  std::normal_distribution<double> gauss;
  std::vector<pcl_holefill::shapes::Ball> balls;
  for (int attempt = 0; attempt < 10000 && balls.size () < count; ++attempt)
  {
    const Eigen::Vector3d d (gauss (rng), gauss (rng), gauss (rng));
    const Eigen::Vector3d c = Eigen::Vector3d::Constant (0.5) + 0.5 * d.normalized ();
    if (std::all_of (balls.begin (), balls.end (), [&] (const auto &b) { return (b.centre - c).norm () > 3 * radius; }))
      balls.push_back ({c, radius});
  }
  return balls;
}

/** \brief The benchmark cloud: a sphere of \a points samples with 10 holes. */
inline pcl_holefill::shapes::CutCloud
sphereWithTenHoles (std::size_t points)
{
  return pcl_holefill::shapes::cutHoles (pcl_holefill::shapes::sphere ().sample (points), sphereHoles (10, 0.06, 3));
}

using Cloud = pcl_holefill::shapes::Cloud;

/** Median wall time of \a runs calls. */
inline double
seconds (const std::function<void ()> &work, int runs)
{
  std::vector<double> times;
  for (int i = 0; i < runs; ++i)
  {
    const auto start = std::chrono::steady_clock::now ();
    work ();
    times.push_back (std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ());
  }
  std::sort (times.begin (), times.end ());
  return times[times.size () / 2];
}

/** PCL NormalEstimationOMP (k = 16) on \a cloud: the yardstick of every bench table. */
inline double
pclNormals (const Cloud::Ptr &cloud, int threads)
{
  pcl::NormalEstimationOMP<pcl::PointNormal, pcl::Normal> estimation (threads);
  estimation.setInputCloud (cloud);
  estimation.setSearchMethod (pcl::search::KdTree<pcl::PointNormal>::Ptr (new pcl::search::KdTree<pcl::PointNormal>));
  estimation.setKSearch (16);
  pcl::PointCloud<pcl::Normal> normals;
  return seconds ([&] { estimation.compute (normals); }, 1);
}

}  // namespace bench
