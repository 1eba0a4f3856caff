/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/boundary_loop.h>
#include <pcl_holefill/hole_report.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pcl_holefill_tool
{
/** \brief The per-hole reports as a JSON document; centres in the file's
  * frame (\a origin: where the fill's local frame lies in it). */
std::string
reportJson (const std::string &input, std::size_t input_points, const std::vector<pcl_holefill::HoleReport> &reports,
            const Eigen::Vector3d &origin = Eigen::Vector3d::Zero ());

/** \brief What detection measured of the whole cloud. */
struct DetectionSummary
{
  float sampling_evenness = 0.f;  //!< HoleBoundaryEstimation::getSamplingEvenness
  float min_hole_size = 0.f;      //!< HoleBoundaryEstimation::getMinHoleSizeUsed (pitches)
};

/** \brief Every loop detection found (holes and borders) as a JSON document:
  * hole or border, closed, diameter, length, spacing, pitch and the indices,
  * after the min hole size applied and the sampling's evenness. */
std::string
loopsJson (const std::string &input, std::size_t input_points, const std::vector<pcl_holefill::BoundaryLoop> &loops,
           const DetectionSummary &summary);

}  // namespace pcl_holefill_tool
