/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/hole_filling.h>

#include <pcl/point_types.h>

#include <string>
#include <vector>

namespace pcl_holefill_tool
{
/** \brief Everything the command line can say, with the library's defaults. */
struct Options
{
  std::string input, output;
  float radius = 0.f;
  float sigma_n = 0.1f;
  float sigma_r = 0.f;
  float sigma_d = 0.f;
  float shrink = 1.f;
  float ratio = 0.3f;
  float spacing = 1.5f;
  int max_passes = 200;
  bool zero_order = false;
  bool denoise = false;
  float max_hole_size = 0.f;
  float min_hole_size = 6.f;
  std::string holes_file, report_file, png_file, demo_dir;
  int threads = 0;
  bool quiet = false;
  bool help = false;
};

/** \brief Parses argv. False with a one-line reason for an unknown option, a
  * missing or malformed value, or a value out of range. */
bool
parseOptions (int argc, char **argv, Options &options, std::string &error);

/** \brief The -h text: every option with its default and unit. */
std::string
usage (const char *program);

/** \brief Sets the filter's parameters from the options. */
void
configure (const Options &options, pcl_holefill::HoleFilling<pcl::PointNormal> &filler);

/** \brief Reads loops from a text file: one loop per line, point indices
  * separated by spaces (a line starting with '#' is a comment). */
bool
readHoles (const std::string &path, std::size_t cloud_size, std::vector<pcl_holefill::BoundaryLoop> &holes,
           std::string &error);

}  // namespace pcl_holefill_tool
