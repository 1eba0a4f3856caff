/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include "render.h"

#include <pcl_holefill/hole_report.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <vector>

namespace pcl_holefill_tool
{
/** \brief Colours of the pictures: input grey, filled points orange, the rim
  * of a closed hole blue, the rim of a hole left open red. */
struct HoleColours
{
  static Eigen::Vector3f input () { return {0.78f, 0.78f, 0.8f}; }
  static Eigen::Vector3f fill () { return {1.f, 0.55f, 0.1f}; }
  static Eigen::Vector3f closedRim () { return {0.1f, 0.35f, 0.95f}; }
  static Eigen::Vector3f openRim () { return {0.9f, 0.05f, 0.05f}; }
};

/** \brief The picture of -png: the whole result from two opposite sides, each
  * hole's rim marked (blue: closed, red: left open), filled points orange;
  * below, one close-up per hole (the first kMaxCloseUps of \a reports), seen
  * from outside the surface (along the mean normal of its rim) and cropped
  * to the hole and a margin around it. \a output: the filter's output, the
  * \a input_points input points first. */
Image
holePicture (const pcl::PointCloud<pcl::PointNormal> &output, std::size_t input_points,
             const std::vector<pcl_holefill::HoleReport> &reports);

/** \brief At most this many close-ups (a scan with hundreds of holes gets an overview). */
constexpr std::size_t kMaxCloseUps = 8;

}  // namespace pcl_holefill_tool
