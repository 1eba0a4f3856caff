/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <string>

namespace pcl_holefill_tool
{
/** \brief The built-in demo: a cube with a corner hole and a sphere with a cap
  * cut out, each filled with a sharp (sigma_n = 0.1) and a smooth (sup)
  * setting. Writes DIR/demo_<model>_<setting>.ply (input grey, filled points
  * orange), DIR/demo.png (before / sharp / smooth per model) and prints each
  * patch's error against the true surface. Returns the exit code. */
int
runDemo (const std::string &directory, bool quiet);

}  // namespace pcl_holefill_tool
