/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_holefill_tool
{
/** \brief An RGB picture, row by row. */
struct Image
{
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;

  Image (int w = 0, int h = 0, std::uint8_t grey = 255) : width (w), height (h), rgb (3 * w * h, grey) {}
};

/** \brief A point to draw: where, which way it faces, which colour (0..1). */
struct Splat
{
  Eigen::Vector3f position;
  Eigen::Vector3f normal;
  Eigen::Vector3f colour;
};

/** \brief Headless software rendering of oriented points as shaded splats:
  * an orthographic view along \a view_direction (towards the cloud), lit
  * from the viewer's upper left, two-sided Lambert shading, a z-buffer, splat
  * size from the points' spacing. No display or GPU needed. */
Image
renderSplats (const std::vector<Splat> &splats, const Eigen::Vector3f &view_direction, int size);

/** \brief Images side by side (heights may differ; the tallest sets the height). */
Image
sideBySide (const std::vector<Image> &images);

/** \brief Images one above the other (the widest sets the width). */
Image
aboveEachOther (const std::vector<Image> &images);

/** \brief Writes a PNG with libpng. */
bool
savePng (const Image &image, const std::string &path, std::string &error);

/** \brief A blue-to-red colour for \a value in [0, 1] (clamped), for error maps. */
Eigen::Vector3f
heatColour (float value);

}  // namespace pcl_holefill_tool
