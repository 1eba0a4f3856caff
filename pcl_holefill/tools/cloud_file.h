/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/PCLPointCloud2.h>

#include <string>

namespace pcl_holefill_tool
{
/** \brief "pcd", "ply" or "text" (.xyz, .pts, .txt) from a file name (case-insensitive), or "" for anything else. */
std::string
cloudFormat (const std::string &path);

/** \brief "unknown file type of 'PATH' (expected ...)": the one message for a
  * file whose format cloudFormat() does not know. */
std::string
unknownFormatMessage (const std::string &path);

/** \brief Reads a PCD or PLY file with all its fields (cloud_reader.h). On
  * failure returns false and puts a one-line reason in \a error; never
  * throws, never crashes on a malformed file. */
bool
loadCloud (const std::string &path, pcl::PCLPointCloud2 &cloud, std::string &error);

/** \brief Writes binary PCD or PLY by the file's extension. */
bool
saveCloud (const std::string &path, const pcl::PCLPointCloud2 &cloud, std::string &error);

}  // namespace pcl_holefill_tool
