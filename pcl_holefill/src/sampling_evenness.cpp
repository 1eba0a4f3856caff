/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/sampling_evenness.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

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

void
RegionEvenness::build (const std::vector<Eigen::Vector3f> &positions, const std::vector<float> &pitch_of,
                       const std::vector<float> &evenness_of, std::size_t stride, int threads)
{
  std::vector<Eigen::Vector3f> measured;
  values_.clear ();
  areas_.clear ();
  float pitch_sum = 0.f;
  for (std::size_t s = 0; s < evenness_of.size () && s * stride < positions.size (); ++s)
    if (evenness_of[s] > 0.f)
    {
      const float pitch = pitch_of[s * stride];
      measured.push_back (positions[s * stride]);
      values_.push_back (evenness_of[s]);
      areas_.push_back (pitch * pitch);
      pitch_sum += pitch;
    }
  if (values_.size () < static_cast<std::size_t> (kMinRegionEvennessSamples))
  {
    values_.clear ();
    grid_.reset (1.f);
    return;
  }
  // Cells of the radius around a place of the mean pitch: a query reads its
  // own cell block.
  grid_.reset (kRegionEvennessRadius * pitch_sum / static_cast<float> (values_.size ()));
  grid_.build (measured, nullptr, threads);
}

float
RegionEvenness::around (const Eigen::Vector3f &position, float pitch) const
{
  if (values_.empty () || !(pitch > 0.f))
    return 0.f;
  thread_local std::vector<PointGrid::Neighbour> within;
  thread_local std::vector<std::pair<float, float>> weighted;
  grid_.withinRadius (position, kRegionEvennessRadius * pitch, within);
  if (within.size () < static_cast<std::size_t> (kMinRegionEvennessSamples))
    return 0.f;
  weighted.clear ();
  float total = 0.f;
  for (const auto &m : within)
  {
    const std::size_t i = static_cast<std::size_t> (m.id);
    weighted.emplace_back (values_[i], areas_[i]);
    total += areas_[i];
  }
  // Sorted by value, then area: the same quartile in whatever order the
  // grid returned them.
  std::sort (weighted.begin (), weighted.end ());
  float below = 0.f;
  for (const auto &[value, area] : weighted)
    if ((below += area) >= 0.25f * total)
      return value;
  return weighted.back ().first;
}
}  // namespace pcl_holefill::detail
