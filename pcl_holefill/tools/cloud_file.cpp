/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "cloud_file.h"

#include "file_check.h"

#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <algorithm>
#include <cctype>
#include <fstream>

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
  return ext == "pcd" || ext == "ply" ? ext : "";
}

bool
loadCloud (const std::string &path, pcl::PCLPointCloud2 &cloud, std::string &error)
{
  const std::string format = cloudFormat (path);
  if (format.empty ())
  {
    error = "unknown file type of '" + path + "' (expected .pcd or .ply)";
    return false;
  }
  if (!std::ifstream (path).good ())
  {
    error = "cannot read '" + path + "'";
    return false;
  }
  if (!checkCloudFile (path, format, error))
    return false;
  // PCL's readers print their own complaints; this tool prints one line of its own.
  const auto verbosity = pcl::console::getVerbosityLevel ();
  pcl::console::setVerbosityLevel (pcl::console::L_ALWAYS);
  int status = -1;
  try
  {
    status = format == "pcd" ? pcl::io::loadPCDFile (path, cloud) : pcl::io::loadPLYFile (path, cloud);
  }
  catch (const std::exception &e)
  {
    status = -1;
  }
  pcl::console::setVerbosityLevel (verbosity);
  if (status < 0)
  {
    error = "'" + path + "' is not a readable " + format + " point cloud";
    return false;
  }
  if (cloud.data.size () != static_cast<std::size_t> (cloud.row_step) * cloud.height ||
      cloud.row_step != cloud.point_step * cloud.width)
  {
    error = "'" + path + "' is malformed (its point count does not match its data)";
    return false;
  }
  return true;
}

bool
saveCloud (const std::string &path, const pcl::PCLPointCloud2 &cloud, std::string &error)
{
  const std::string format = cloudFormat (path);
  int status = -1;
  if (format == "pcd")
    status = pcl::io::savePCDFile (path, cloud, Eigen::Vector4f::Zero (), Eigen::Quaternionf::Identity (), true);
  else if (format == "ply")
    status = pcl::io::savePLYFile (path, cloud, Eigen::Vector4f::Zero (), Eigen::Quaternionf::Identity (), true);
  else
  {
    error = "unknown file type of '" + path + "' (expected .pcd or .ply)";
    return false;
  }
  if (status < 0)
  {
    error = "cannot write '" + path + "'";
    return false;
  }
  return true;
}

}  // namespace pcl_holefill_tool
