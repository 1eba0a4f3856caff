/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/PCLPointCloud2.h>

#include <string>

namespace pcl_holefill_tool
{
/** \brief Writes \a cloud as a binary PCD file (version 0.7, every field,
  * gaps between fields as '_' padding, as PCL's PCDWriter writes them).
  * False, with a one-line reason in \a error, if the file cannot be written.
  *
  * The command writes its files itself, as it reads them (cloud_reader.h):
  * PCL's io library brings 75 shared libraries (VTK, OpenNI, ...) whose
  * symbols the dynamic loader resolved for 0.1 s at every start, longer
  * than the whole fill of a 20,000-point cloud. */
bool
writePcd (const std::string &path, const pcl::PCLPointCloud2 &cloud, std::string &error);

/** \brief Writes the points of \a cloud as the vertex element of a binary
  * PLY file in the machine's byte order: each field a property of its type,
  * normal_x, normal_y, normal_z as nx, ny, nz, a packed rgb (or rgba) as
  * uchar red, green, blue (and alpha), a field of several values as a
  * list, '_' padding and the types PLY lacks (64-bit integers, bool) left
  * out. The names readPly () gives back. */
bool
writePly (const std::string &path, const pcl::PCLPointCloud2 &cloud, std::string &error);

}  // namespace pcl_holefill_tool
