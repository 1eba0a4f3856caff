/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/detail/point_grid.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_holefill::detail
{
/** \brief Smallest hole (sampling pitches) on a uniformly random sampling,
  * whose gaps are the widest of any sampler: an empty disc of 6 pitches less
  * the rim's raggedness is found by chance about 0.1 times per million
  * points (doc/parameters.md, "Telling holes from sampling gaps"). */
constexpr float kRandomSamplingMinHoleSize = 6.f;

/** \brief Smallest hole (sampling pitches) on an even sampling (Poisson-disk,
  * jittered grid, voxel grid): these leave every point of the surface within
  * about a pitch of a sample, so the disc tested (radius 4 / 2 - 0.5 = 1.5
  * pitches) is never empty by chance. */
constexpr float kEvenSamplingMinHoleSize = 4.f;

/** \brief The sampling's evenness (lower quartile of the nearest neighbour's
  * distance in the tangent plane, in pitches) up to which the sampling counts
  * as random, and from which it counts as even; in between the min hole size
  * goes linearly from one to the other. Measured on 20,000-point samples of
  * a cube, clean and at 0.5 % noise, exact and PCA normals: uniformly random
  * 0.30, scan lines (3-5 times denser along a line) 0.39-0.41, jittered grid
  * 0.59-0.63, Poisson-disk 0.72-0.78, voxel grid 0.78-0.83. The lower
  * quartile, not the median: a cloud part random, part even is judged by its
  * random part until that is under a quarter of it. */
constexpr float kRandomEvenness = 0.45f;
constexpr float kEvenEvenness = 0.55f;

/** \brief The evenness is measured at every this many points: on 13,000
  * to 20,000 samples of five samplers the lower quartile of 1 in 8 was
  * within 0.011 of all points' (thresholds 0.1 apart), and measuring all
  * cost 7 % of the detection of 900,000 random samples. */
constexpr std::size_t kEvennessStride = 8;

/** \brief Distance to the nearest of \a count neighbours \a ids (into
  * \a positions) in the tangent plane of \a point, \a unit_normal: the
  * sampling's spacing, without the noise along the normal. Neighbours at the
  * point's own position are skipped (a repeated point says nothing of the
  * spacing); 0 if none is left. */
float
tangentialNearest (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal, const Eigen::Vector3f *positions,
                   const int *ids, int count);

/** \brief The lower quartile of the positive \a values (0 if none): the
  * evenness of a sampling from each point's tangentialNearest over its
  * pitch. Reorders \a values. */
float
lowerQuartileOfPositive (std::vector<float> &values);

/** \brief The min hole size (pitches) for a sampling of this \a evenness:
  * kRandomSamplingMinHoleSize up to kRandomEvenness, kEvenSamplingMinHoleSize
  * from kEvenEvenness, linear in between. */
float
minHoleSizeForEvenness (float evenness);

/** \brief A region's evenness is measured within this many of its own
  * pitches: about 56 points are measured within 12 pitches (one in
  * kEvennessStride of some 450), and their lower quartile moves by about 0.03
  * between draws of one sampling (the thresholds are 0.1 apart, the
  * samplers' evenness 0.3).*/
constexpr float kRegionEvennessRadius = 12.f;

/** \brief Fewer measured points than this within the radius (a small
  * cloud, a narrow part) leave the region's evenness unknown: the whole
  * cloud's is used. */
constexpr int kMinRegionEvennessSamples = 16;

/** \brief How evenly the cloud is sampled around a place: the lower quartile
  * of the evenness measured within kRegionEvennessRadius pitches of it, each
  * measured point weighted by the area it stands for (its pitch squared).
  *
  * Why per region: merged scans and partly thinned clouds are sampled evenly
  * in one part and randomly in another. A min hole size chosen from the whole
  * cloud's evenness (4 pitches where most of it is even) reported the random
  * part's gaps (up to about 5 pitches) as holes. Why weighted by area: beside
  * a part 4 times denser, the measured points are mostly the dense part's,
  * and a count would judge the sparse part's rim by its neighbour. */
class RegionEvenness
{
public:
  /** \brief Keeps the positive \a evenness_of[s], measured at
    * \a positions[s * \a stride] whose pitch is \a pitch_of[s * \a stride]. */
  void
  build (const std::vector<Eigen::Vector3f> &positions, const std::vector<float> &pitch_of,
         const std::vector<float> &evenness_of, std::size_t stride, int threads);

  /** \brief The evenness around \a position, where the sampling pitch is
    * \a pitch; 0 when fewer than kMinRegionEvennessSamples were measured
    * there. */
  float
  around (const Eigen::Vector3f &position, float pitch) const;

private:
  PointGrid grid_;
  std::vector<float> values_;  //!< the evenness of the grid's point i
  std::vector<float> areas_;   //!< the area it stands for (its pitch squared)
};
}  // namespace pcl_holefill::detail
