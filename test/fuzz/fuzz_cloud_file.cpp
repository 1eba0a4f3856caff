/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 *
 * libFuzzer target: the pcl_holefill command's input path on arbitrary bytes.
 * The first byte picks the format (odd: PLY, 'x': text .xyz, other even: PCD;
 * the seeds of earlier runs keep their meaning); the rest is the file. Must never crash, hang or leak: a bad file is a one-line error.
 */
#include "cloud_assembly.h"
#include "cloud_file.h"

#include <pcl/console/print.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int
LLVMFuzzerTestOneInput (const std::uint8_t *data, std::size_t size)
{
  if (size < 1 || size > (1u << 20))
    return 0;
  pcl::console::setVerbosityLevel (pcl::console::L_ALWAYS);
  const std::string path = "/tmp/pcl_holefill_fuzz_" + std::to_string (::getpid ()) + ((data[0] & 1) ? ".ply" : (data[0] == 'x' ? ".xyz" : ".pcd"));
  {
    std::ofstream out (path, std::ios::binary);
    out.write (reinterpret_cast<const char *> (data + 1), static_cast<std::streamsize> (size - 1));
  }
  pcl::PCLPointCloud2 cloud;
  std::string error;
  if (pcl_holefill_tool::loadCloud (path, cloud, error))
  {
    pcl_holefill_tool::PreparedCloud prepared;
    if (cloud.width * cloud.height <= 20000)
      pcl_holefill_tool::prepareCloud (cloud, 1, prepared, error);
  }
  std::remove (path.c_str ());
  return 0;
}
