/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/boundary_loop.h>
#include <pcl_holefill/hole_report.h>

#include <pcl/PCLPointCloud2.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <string>

namespace pcl_holefill_tool
{
/** \brief A file's cloud as the library sees it, next to the file's own fields. */
struct PreparedCloud
{
  pcl::PCLPointCloud2 fields;                              //!< every field of the file (+ normals if estimated)
  pcl::PointCloud<pcl::PointNormal>::Ptr points;           //!< xyz (minus origin) and normals, same order
  /** The local frame: points = the file's positions - origin, the centre
    * of their bounding box when the cloud lies farther from (0, 0, 0) than
    * its size, else zero. */
  Eigen::Vector3d origin = Eigen::Vector3d::Zero ();
  bool normals_estimated = false;                          //!< points carry estimated normals
  bool normals_unusable = false;                           //!< the file had normals, mostly zero or not finite
  int normal_neighbours = 0;                               //!< k of the estimated normals (0: not estimated)
  std::size_t finite_points = 0;
};

/** \brief Checks the file's fields, takes its normals or estimates them
  * (estimateOrientedNormals: PCL NormalEstimationOMP, k = 16 or more on
  * noisy clouds, then consistently oriented). The file's rows become
  * prepared.fields: pass the cloud with std::move where it is not needed
  * after (a copy of a large cloud's rows costs a serial pass). */
bool
prepareCloud (pcl::PCLPointCloud2 file_cloud, unsigned int threads, PreparedCloud &prepared,
              std::string &error);

/** \brief The output file: the input rows unchanged, then one row per filled
  * point (its other fields copied from the nearest input point), and a
  * field "filled" (1 for filled points, 0 for the input). \a filtered is the
  * filter's output: the input points, then the fill; \a reports its reports
  * (where each hole's filled points are, to search the input near them);
  * \a threads search side by side (0: all cores). */
bool
assembleOutput (const PreparedCloud &prepared, const pcl::PointCloud<pcl::PointNormal> &filtered,
                const std::vector<pcl_holefill::HoleReport> &reports, unsigned int threads,
                pcl::PCLPointCloud2 &output, std::string &error);

/** \brief The output of -detect_only: the input rows unchanged, with a field
  * "hole_id" (int32): the hole's number (in the order of \a loops, holes
  * only) for the points of its rim, -1 for every other point. */
bool
assembleDetection (const PreparedCloud &prepared, const std::vector<pcl_holefill::BoundaryLoop> &loops,
                   unsigned int threads, pcl::PCLPointCloud2 &output, std::string &error);

}  // namespace pcl_holefill_tool
