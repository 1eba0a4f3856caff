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
/** \brief The filter as constructed: the one source of the command's defaults. */
inline const pcl_holefill::HoleFilling<pcl::PointNormal> &
filterDefaults ()
{
  static const pcl_holefill::HoleFilling<pcl::PointNormal> defaults;
  return defaults;
}

/** \brief Everything the command line can say, with the library's defaults. */
struct Options
{
  std::string input, output;
  float radius = filterDefaults ().getRadius ();
  float sigma_n = filterDefaults ().getSigmaN ();
  float sigma_r = filterDefaults ().getSigmaR ();
  float sigma_d = filterDefaults ().getSigmaD ();
  float shrink = filterDefaults ().getRadiusShrinkFactor ();
  float ratio = filterDefaults ().getTerminationRatio ();
  float spacing = filterDefaults ().getSpacingFactor ();
  int max_passes = filterDefaults ().getMaxPasses ();
  bool zero_order = !filterDefaults ().getFirstOrder ();
  bool denoise = filterDefaults ().getDenoise ();
  float max_hole_size = filterDefaults ().getMaxHoleDiameter ();
  float min_hole_size = filterDefaults ().getMinHoleSize ();
  std::string holes_file, report_file, png_file, demo_dir;
  int threads = 0;
  bool quiet = false;
  bool verbose = false;
  bool detect_only = false;
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

/** \brief Writes the hole loops (is_hole) in the format readHoles reads. */
bool
writeHoles (const std::string &path, const std::vector<pcl_holefill::BoundaryLoop> &loops, std::string &error);

}  // namespace pcl_holefill_tool
