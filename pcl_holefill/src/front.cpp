/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/front.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>

namespace pcl_holefill::detail
{
float
frontLength (const Front &front)
{
  float length = 0.f;
  for (const auto &chain : front)
  {
    const auto &v = chain.vertices;
    for (std::size_t i = 1; i < v.size (); ++i)
      length += (v[i].position - v[i - 1].position).norm ();
    if (chain.closed && v.size () > 2)
      length += (v.front ().position - v.back ().position).norm ();
  }
  return length;
}

namespace
{
constexpr int kRimSectors = 128;

// The "diamond angle" of (x, y), 0..4 for 0..2 pi: monotone in the angle,
// with one division instead of an atan2 (this runs for every rim point of
// every candidate).
float
diamondAngle (float x, float y)
{
  if (y >= 0.f)
    return x >= 0.f ? y / (x + y) : 1.f - x / (y - x);
  return x < 0.f ? 2.f - y / (-x - y) : 3.f + x / (x - y);
}

// The true angle of each sector boundary: the sectors are equal in diamond angle.
const std::array<float, kRimSectors + 1> &
sectorBoundaryAngles ()
{
  static const std::array<float, kRimSectors + 1> angles = [] {
    std::array<float, kRimSectors + 1> a{};
    for (int k = 0; k <= kRimSectors; ++k)
    {
      const float d = 4.f * static_cast<float> (k) / kRimSectors;
      const int quadrant = std::min (3, static_cast<int> (d));
      const float f = d - static_cast<float> (quadrant);
      a[k] = static_cast<float> (quadrant) * static_cast<float> (M_PI / 2.0) + std::atan2 (f, 1.f - f);
    }
    return a;
  }();
  return angles;
}
}  // namespace

float
rimGapAround (const Eigen::Vector3f &position, const Eigen::Vector3f &normal, const std::vector<Eigen::Vector3f> &rim)
{
  const Eigen::Vector3f n = normal.normalized ();
  const Eigen::Vector3f u = n.unitOrthogonal (), v = n.cross (u);
  std::array<bool, kRimSectors> seen{};
  bool any = false;
  for (const auto &q : rim)
  {
    const Eigen::Vector3f d = q - position;
    const float a = d.dot (u), b = d.dot (v);
    if (!(a * a + b * b > 1e-12f * d.squaredNorm ()))
      continue;  // on top of the point, or straight above it
    const int sector = static_cast<int> (diamondAngle (a, b) * (kRimSectors / 4.f));
    seen[std::clamp (sector, 0, kRimSectors - 1)] = true;
    any = true;
  }
  if (!any)
    return static_cast<float> (2.0 * M_PI);
  // The widest run of empty sectors, around the circle, as a true angle.
  const auto &angle = sectorBoundaryAngles ();
  float widest = 0.f;
  for (int start = 0; start < kRimSectors; ++start)
  {
    if (seen[start] || !seen[(start + kRimSectors - 1) % kRimSectors])
      continue;  // runs are measured from their first sector
    int end = start;
    while (!seen[end % kRimSectors])
      ++end;
    const float from = angle[start], to = end > kRimSectors ? angle[end - kRimSectors] + static_cast<float> (2.0 * M_PI)
                                                             : angle[end];
    widest = std::max (widest, to - from);
  }
  return widest;
}

}  // namespace pcl_holefill::detail
