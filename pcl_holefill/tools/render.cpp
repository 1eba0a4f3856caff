/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "render.h"

#include <pcl_holefill/detail/point_grid.h>

#include <Eigen/Geometry>

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace pcl_holefill_tool
{
namespace
{
/** The part of the view plane (coordinates along \a right and \a up) to
  * show: what holds all but 0.5 % of the points on each side, widened by
  * 2 %. A few stray points far away would otherwise shrink the object to a
  * dot in an empty frame. */
void
viewWindow (const std::vector<Eigen::Vector3f> &positions, const Eigen::Vector3f &right, const Eigen::Vector3f &up,
            Eigen::Vector2f &lo, Eigen::Vector2f &hi)
{
  constexpr double kOutlierShare = 0.005;
  for (int axis = 0; axis < 2; ++axis)
  {
    std::vector<float> values;
    values.reserve (positions.size ());
    for (const auto &p : positions)
      values.push_back (p.dot (axis == 0 ? right : up));
    const auto skip = static_cast<std::size_t> (kOutlierShare * values.size ());
    std::nth_element (values.begin (), values.begin () + skip, values.end ());
    const float low = values[skip];
    std::nth_element (values.begin (), values.end () - 1 - skip, values.end ());
    const float high = values[values.size () - 1 - skip];
    lo[axis] = low - 0.02f * (high - low);
    hi[axis] = high + 0.02f * (high - low);
  }
}
}  // namespace

Image
renderSplats (const std::vector<Splat> &splats, const Eigen::Vector3f &view_direction, int size)
{
  Image image (size, size, 255);
  std::vector<Eigen::Vector3f> positions;
  for (const auto &s : splats)
    if (s.position.allFinite () && s.normal.allFinite ())
      positions.push_back (s.position);
  if (positions.empty () || size < 8)
    return image;
  // Camera frame: forward along the view direction, up as close to +z as possible.
  const Eigen::Vector3f forward = view_direction.normalized ();
  Eigen::Vector3f up = Eigen::Vector3f::UnitZ () - forward.dot (Eigen::Vector3f::UnitZ ()) * forward;
  if (up.norm () < 1e-3f)
    up = Eigen::Vector3f::UnitY () - forward.dot (Eigen::Vector3f::UnitY ()) * forward;
  up.normalize ();
  const Eigen::Vector3f right = forward.cross (up);
  Eigen::Vector2f lo, hi;
  viewWindow (positions, right, up, lo, hi);
  const float extent = std::max ((hi - lo).maxCoeff (), 1e-9f);
  const float scale = 0.9f * size / extent;  // pixels per unit, 5 % margin
  const Eigen::Vector2f offset = 0.5f * (lo + hi);
  // Splat radius: the mean spacing, a little more so that surfaces close.
  pcl_holefill::detail::PointGrid grid (pcl_holefill::detail::PointGrid::suggestCellSize (positions, 4));
  grid.build (positions);
  double spacing = 0.0;
  std::size_t counted = 0;
  std::vector<pcl_holefill::detail::PointGrid::Neighbour> near;
  for (std::size_t i = 0; i < positions.size (); i += 1 + positions.size () / 2000)
  {
    grid.nearestK (positions[i], 2, near);
    if (near.size () == 2)
    {
      spacing += std::sqrt (near[1].sqr_distance);
      ++counted;
    }
  }
  const float radius_px = std::max (1.f, 1.0f * static_cast<float> (counted ? spacing / counted : 0.0) * scale);
  const Eigen::Vector3f light = (-forward + 0.5f * up - 0.4f * right).normalized ();
  std::vector<float> depth (static_cast<std::size_t> (size) * size, std::numeric_limits<float>::max ());
  for (const auto &s : splats)
  {
    if (!s.position.allFinite () || !s.normal.allFinite ())
      continue;
    const float px = (s.position.dot (right) - offset.x ()) * scale + 0.5f * size;
    const float py = 0.5f * size - (s.position.dot (up) - offset.y ()) * scale;
    if (!(px > -radius_px - 1.f && px < size + radius_px + 1.f && py > -radius_px - 1.f && py < size + radius_px + 1.f))
      continue;  // out of the window (a stray point): also keeps the casts below in range
    const float z = s.position.dot (forward);
    const Eigen::Vector3f n = s.normal.normalized ();
    const float shade = 0.3f + 0.7f * std::abs (n.dot (light));
    const int r = static_cast<int> (std::ceil (radius_px));
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx)
      {
        if (dx * dx + dy * dy > radius_px * radius_px)
          continue;
        const int x = static_cast<int> (px) + dx, y = static_cast<int> (py) + dy;
        if (x < 0 || y < 0 || x >= size || y >= size)
          continue;
        float &d = depth[static_cast<std::size_t> (y) * size + x];
        if (z >= d)
          continue;
        d = z;
        for (int c = 0; c < 3; ++c)
          image.rgb[3 * (static_cast<std::size_t> (y) * size + x) + c] =
              static_cast<std::uint8_t> (std::clamp (255.f * shade * s.colour[c], 0.f, 255.f));
      }
  }
  return image;
}

Image
sideBySide (const std::vector<Image> &images)
{
  int width = 0, height = 0;
  for (const auto &im : images)
  {
    width += im.width;
    height = std::max (height, im.height);
  }
  Image out (width, height, 255);
  int x0 = 0;
  for (const auto &im : images)
  {
    for (int y = 0; y < im.height; ++y)
      std::copy (im.rgb.begin () + 3 * y * im.width, im.rgb.begin () + 3 * (y + 1) * im.width,
                 out.rgb.begin () + 3 * (y * width + x0));
    x0 += im.width;
  }
  return out;
}

Image
aboveEachOther (const std::vector<Image> &images)
{
  int width = 0, height = 0;
  for (const auto &im : images)
  {
    width = std::max (width, im.width);
    height += im.height;
  }
  Image out (width, height, 255);
  int y0 = 0;
  for (const auto &im : images)
  {
    for (int y = 0; y < im.height; ++y)
      std::copy (im.rgb.begin () + 3 * y * im.width, im.rgb.begin () + 3 * (y + 1) * im.width,
                 out.rgb.begin () + 3 * ((y0 + y) * width));
    y0 += im.height;
  }
  return out;
}

bool
savePng (const Image &image, const std::string &path, std::string &error)
{
  if (image.width <= 0 || image.height <= 0)
  {
    error = "empty image";
    return false;
  }
  FILE *file = std::fopen (path.c_str (), "wb");
  if (!file)
  {
    error = "cannot write '" + path + "'";
    return false;
  }
  png_structp png = png_create_write_struct (PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct (png) : nullptr;
  if (!png || !info || setjmp (png_jmpbuf (png)))
  {
    png_destroy_write_struct (&png, &info);
    std::fclose (file);
    error = "libpng failed to write '" + path + "'";
    return false;
  }
  png_init_io (png, file);
  png_set_IHDR (png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info (png, info);
  for (int y = 0; y < image.height; ++y)
    png_write_row (png, const_cast<png_bytep> (image.rgb.data () + 3 * static_cast<std::size_t> (y) * image.width));
  png_write_end (png, nullptr);
  png_destroy_write_struct (&png, &info);
  std::fclose (file);
  return true;
}

Eigen::Vector3f
heatColour (float value)
{
  const float t = std::clamp (value, 0.f, 1.f);
  // blue -> cyan -> yellow -> red
  if (t < 1.f / 3.f)
    return {0.f, 3.f * t, 1.f};
  if (t < 2.f / 3.f)
    return {3.f * (t - 1.f / 3.f), 1.f, 1.f - 3.f * (t - 1.f / 3.f)};
  return {1.f, 1.f - 3.f * (t - 2.f / 3.f), 0.f};
}

}  // namespace pcl_holefill_tool
