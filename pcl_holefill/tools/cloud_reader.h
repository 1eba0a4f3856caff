/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/PCLPointCloud2.h>

#include <cstdint>
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
  * byte order; other elements before or after it are read past).
  * Properties keep their names (nx, ny, nz become normal_x, normal_y,
  * normal_z; uchar red, green, blue become a packed rgb as in PCL) and their
  * types. Same guarantees as readPcd(). */
bool
readPly (const std::string &path, pcl::PCLPointCloud2 &cloud, std::string &error);

/** \brief \a value as the bytes of a field of PCL type \a datatype at \a out
  * (integers clamped to their range, NaN as 0); false for an unknown type. */
bool
storeFieldValue (double value, std::uint8_t datatype, std::uint8_t *out);

/** \brief The value of a field of PCL type \a datatype stored at \a at (NaN for an unknown type). */
double
fieldValue (const std::uint8_t *at, std::uint8_t datatype);

}  // namespace pcl_holefill_tool
