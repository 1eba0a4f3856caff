/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/sampling_evenness.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_holefill::detail
{
float
tangentialNearest (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal, const Eigen::Vector3f *positions,
                   const int *ids, int count)
{
  float nearest = std::numeric_limits<float>::infinity ();
  for (int j = 0; j < count; ++j)
  {
    const Eigen::Vector3f offset = positions[ids[j]] - point;
    const float sqr_distance = offset.squaredNorm ();
    const float along = offset.dot (unit_normal);
    if (sqr_distance > 0.f)
      nearest = std::min (nearest, std::max (sqr_distance - along * along, 0.f));
  }
  return std::isfinite (nearest) ? std::sqrt (nearest) : 0.f;
}

float
lowerQuartileOfPositive (std::vector<float> &values)
{
  const auto end = std::partition (values.begin (), values.end (), [] (float v) { return v > 0.f; });
  const std::size_t n = static_cast<std::size_t> (end - values.begin ());
  if (n == 0)
    return 0.f;
  const auto quartile = values.begin () + static_cast<std::ptrdiff_t> (n / 4);
  std::nth_element (values.begin (), quartile, end);
  return *quartile;
}

float
minHoleSizeForEvenness (float evenness)
{
  const float t = std::clamp ((evenness - kRandomEvenness) / (kEvenEvenness - kRandomEvenness), 0.f, 1.f);
  return kRandomSamplingMinHoleSize + t * (kEvenSamplingMinHoleSize - kRandomSamplingMinHoleSize);
}
}  // namespace pcl_holefill::detail
