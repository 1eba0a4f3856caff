/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <string>

namespace pcl_holefill_tool
{
/** \brief Checks a PCD or PLY file's header, and that the file is long
  * enough for the points it announces, before PCL's reader sees it: PCL 1.13
  * crashes on some malformed files (a header without fields, counts that the
  * data does not hold). True when the file looks readable; otherwise false
  * with a one-line reason. Reads at most the first 64 KiB of header. */
bool
checkCloudFile (const std::string &path, const std::string &format, std::string &error);

}  // namespace pcl_holefill_tool
