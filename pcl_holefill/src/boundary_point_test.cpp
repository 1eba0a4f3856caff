/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/boundary_point_test.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace pcl_holefill
{
Eigen::Vector3f
unfoldIntoTangentPlane (const Eigen::Vector3f &offset, const Eigen::Vector3f &unit_normal,
                        const Eigen::Vector3f &neighbour_normal)
{
  const float height = offset.dot (unit_normal);
  Eigen::Vector3f unfolded = offset - height * unit_normal;
  // The tangent part of the neighbour's normal points towards the edge on a
  // convex edge and away from it on a concave one; -height has the matching sign.
  const Eigen::Vector3f tilt = neighbour_normal - neighbour_normal.dot (unit_normal) * unit_normal;
  const float tilt_norm = tilt.norm ();
  if (tilt_norm > 0.2f)
    unfolded -= height * tilt / tilt_norm;
  return unfolded;
}

AngularGap
largestAngularGap (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal,
                   const std::vector<Eigen::Vector3f> &neighbours,
                   const std::vector<Eigen::Vector3f> &neighbour_normals)
{
  AngularGap gap;
  const Eigen::Vector3f u = unit_normal.unitOrthogonal ();
  const Eigen::Vector3f v = unit_normal.cross (u);
  float angles[64];
  Eigen::Vector3f unfolded[64];
  const std::size_t count_in = std::min<std::size_t> (neighbours.size (), 64);
  float reach = 0.f;
  for (std::size_t i = 0; i < count_in; ++i)
  {
    unfolded[i] = unfoldIntoTangentPlane (neighbours[i] - point, unit_normal, neighbour_normals[i]);
    reach = std::max (reach, unfolded[i].norm ());
  }
  int count = 0;
  for (std::size_t i = 0; i < count_in; ++i)
  {
    const float a = unfolded[i].dot (u), b = unfolded[i].dot (v);
    if (std::hypot (a, b) <= 1e-3f * reach)
      continue;
    angles[count++] = std::atan2 (b, a);
  }
  if (count == 0)
  {
    gap.angle = static_cast<float> (2.0 * M_PI);
    gap.direction = u;
    return gap;
  }
  std::sort (angles, angles + count);
  // The wrap-around gap first, then each consecutive pair.
  float widest = angles[0] + static_cast<float> (2.0 * M_PI) - angles[count - 1];
  float start = angles[count - 1];
  for (int i = 1; i < count; ++i)
    if (angles[i] - angles[i - 1] > widest)
    {
      widest = angles[i] - angles[i - 1];
      start = angles[i - 1];
    }
  const float middle = start + 0.5f * widest;
  gap.angle = widest;
  gap.direction = (std::cos (middle) * u + std::sin (middle) * v).normalized ();
  return gap;
}

}  // namespace pcl_holefill
