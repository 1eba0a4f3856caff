/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "cloud_file.h"

#include "cloud_reader.h"
#include "cloud_writer.h"
#include "text_cloud.h"

#include <algorithm>
#include <cctype>

namespace pcl_holefill_tool
{
std::string
cloudFormat (const std::string &path)
{
  const auto dot = path.find_last_of ('.');
  if (dot == std::string::npos)
    return "";
  std::string ext = path.substr (dot + 1);
  std::transform (ext.begin (), ext.end (), ext.begin (), [] (unsigned char c) { return std::tolower (c); });
  if (ext == "xyz" || ext == "pts" || ext == "txt")
    return "text";
  return ext == "pcd" || ext == "ply" ? ext : "";
}

std::string
unknownFormatMessage (const std::string &path)
{
  return "unknown file type of '" + path + "' (expected .pcd, .ply, .xyz, .pts or .txt)";
}

bool
loadCloud (const std::string &path, pcl::PCLPointCloud2 &cloud, std::string &error)
{
  const std::string format = cloudFormat (path);
  if (format.empty ())
  {
    error = unknownFormatMessage (path);
    return false;
  }
  try
  {
    if (format == "text")
      return readText (path, cloud, error);
    return format == "pcd" ? readPcd (path, cloud, error) : readPly (path, cloud, error);
  }
  catch (const std::exception &e)  // allocation failures on absurd sizes
  {
    error = "'" + path + "': " + e.what ();
    return false;
  }
}

bool
saveCloud (const std::string &path, const pcl::PCLPointCloud2 &cloud, std::string &error)
{
  const std::string format = cloudFormat (path);
  if (format == "pcd")
    return writePcd (path, cloud, error);
  if (format == "ply")
    return writePly (path, cloud, error);
  if (format == "text")
    return writeText (path, cloud, error);
  error = unknownFormatMessage (path);
  return false;
}

}  // namespace pcl_holefill_tool
