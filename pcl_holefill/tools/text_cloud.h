/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/PCLPointCloud2.h>

#include <string>

namespace pcl_holefill_tool
{
/** \brief Reads a plain-text cloud (.xyz, .pts, .txt): one point per line,
  * numbers separated by spaces, tabs or commas; empty lines and lines
  * starting with '#' or '//' are skipped, and so is a leading line holding
  * one whole number (the point count of .pts files). Every point line has
  * the same number of columns, at least 3: x y z first. Three columns that
  * hold unit vectors on (nearly) every line, right after x y z or last,
  * become normal_x, normal_y, normal_z; every other column becomes a float
  * field "column_K" (K its 1-based position), carried to the output. A
  * malformed line is a one-line error naming it, never a crash. */
bool
readText (const std::string &path, pcl::PCLPointCloud2 &cloud, std::string &error);

/** \brief Writes \a cloud as text, a point per line: x y z, the normals if
  * any, every other field, then curvature and filled if present (9
  * significant digits: a float32 read back is the same float). */
bool
writeText (const std::string &path, const pcl::PCLPointCloud2 &cloud, std::string &error);

}  // namespace pcl_holefill_tool
