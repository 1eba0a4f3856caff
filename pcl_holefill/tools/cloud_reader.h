/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/PCLPointCloud2.h>

#include <string>

namespace pcl_holefill_tool
{
/** \brief Reads a PCD file (ascii, binary or binary_compressed, version 0.7)
  * with every field. Checks the header and the data length before touching
  * the data, so a malformed file is a one-line error, never a crash: PCL
  * 1.13's own reader crashes on some (found by fuzzing, see test/fuzz). */
bool
readPcd (const std::string &path, pcl::PCLPointCloud2 &cloud, std::string &error);

/** \brief Reads the vertex element of a PLY file (ascii or binary, either
  * byte order), which must come first. Properties keep their names (nx, ny,
  * nz become normal_x, normal_y, normal_z; uchar red, green, blue become a
  * packed rgb as in PCL) and are stored as 32-bit floats. Same guarantees as
  * readPcd(). */
bool
readPly (const std::string &path, pcl::PCLPointCloud2 &cloud, std::string &error);

}  // namespace pcl_holefill_tool
