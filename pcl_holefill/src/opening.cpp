/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/loop_tracing.h>
#include <pcl_holefill/detail/opening.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace pcl_holefill::detail
{
namespace
{
// Past the rim: farther from the loop's plane than this share of the rim's
// mean distance from the axis; on a wall: at least this share of it from
// the axis (a square rim's sides lie at 0.88 of its mean).
constexpr float kWallHeight = 0.5f;
constexpr float kWallRadius = 0.85f;

Eigen::Vector3f
loopAxis (const std::vector<Eigen::Vector3f> &positions)
{
  const Eigen::Vector3f area = vectorArea (positions);
  return area.norm () > 0.f ? Eigen::Vector3f (area.normalized ()) : Eigen::Vector3f::Zero ();
}

Eigen::Vector3f
centroidOf (const std::vector<Eigen::Vector3f> &positions)
{
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero ();
  for (const auto &p : positions)
    centroid += p;
  return positions.empty () ? centroid : Eigen::Vector3f (centroid / static_cast<float> (positions.size ()));
}
}  // namespace

float
shareAlongWalls (const std::vector<Eigen::Vector3f> &loop_positions, const std::vector<Eigen::Vector3f> &filled)
{
  const Eigen::Vector3f axis = loopAxis (loop_positions);
  if (axis.isZero () || filled.empty ())
    return 0.f;
  const Eigen::Vector3f centroid = centroidOf (loop_positions);
  const auto fromAxis = [&] (const Eigen::Vector3f &p) {
    const Eigen::Vector3f d = p - centroid;
    return (d - d.dot (axis) * axis).norm ();
  };
  float rim_radius = 0.f;
  for (const auto &p : loop_positions)
    rim_radius += fromAxis (p);
  rim_radius /= static_cast<float> (loop_positions.size ());
  std::size_t on_walls = 0;
  for (const auto &p : filled)
    if (std::abs ((p - centroid).dot (axis)) > kWallHeight * rim_radius && fromAxis (p) >= kWallRadius * rim_radius)
      ++on_walls;
  return static_cast<float> (on_walls) / static_cast<float> (filled.size ());
}

float
alignmentWithLoop (const std::vector<Eigen::Vector3f> &loop_positions, const std::vector<Eigen::Vector3f> &normals)
{
  const Eigen::Vector3f axis = loopAxis (loop_positions);
  if (axis.isZero () || normals.empty ())
    return 1.f;
  float sum = 0.f;
  for (const auto &n : normals)
    sum += std::abs (n.dot (axis));
  return sum / static_cast<float> (normals.size ());
}

Eigen::Vector3f
openingNormal (const std::vector<Eigen::Vector3f> &positions, const std::vector<Eigen::Vector3f> &normals,
               const Eigen::Vector3f &walls_centroid)
{
  const Eigen::Vector3f axis = loopAxis (positions);
  if (axis.isZero ())
    return axis;
  const Eigen::Vector3f centroid = centroidOf (positions);
  const Eigen::Vector3f away = (walls_centroid - centroid).dot (axis) > 0.f ? Eigen::Vector3f (-axis) : axis;
  // Do the walls' normals face the loop's inside (seen across the axis)?
  float facing = 0.f;
  for (std::size_t i = 0; i < positions.size () && i < normals.size (); ++i)
  {
    Eigen::Vector3f inside = centroid - positions[i];
    inside -= inside.dot (axis) * axis;
    if (inside.norm () > 0.f)
      facing += normals[i].dot (inside.normalized ());
  }
  return facing > 0.f ? Eigen::Vector3f (-away) : away;
}

float
depthAlong (const std::vector<Eigen::Vector3f> &positions, const Eigen::Vector3f &direction)
{
  if (positions.empty ())
    return 0.f;
  const float mean = centroidOf (positions).dot (direction);
  float sum = 0.f;
  for (const auto &p : positions)
    sum += (p.dot (direction) - mean) * (p.dot (direction) - mean);
  return std::sqrt (sum / static_cast<float> (positions.size ()));
}

float
quantileAlong (const std::vector<Eigen::Vector3f> &positions, const Eigen::Vector3f &direction, float quantile)
{
  if (positions.empty ())
    return 0.f;
  std::vector<float> heights;
  for (const auto &p : positions)
    heights.push_back (p.dot (direction));
  const auto k = static_cast<std::size_t> (std::clamp (quantile, 0.f, 1.f) * static_cast<float> (heights.size () - 1));
  std::nth_element (heights.begin (), heights.begin () + static_cast<std::ptrdiff_t> (k), heights.end ());
  return heights[k];
}

}  // namespace pcl_holefill::detail
