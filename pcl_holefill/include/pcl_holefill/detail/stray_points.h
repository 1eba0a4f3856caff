/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl_holefill::detail
{
/** \brief Is a point whose nearest neighbour lies at \a nearest a stray,
  * given the sampling pitches (samplingPitch) at its \a count neighbours,
  * \a around (reordered)? It is when that neighbour is farther than
  * \a pitches times their median pitch.
  *
  * A scanner's stray return (a mixed pixel, a reflection) lies off the
  * surface: its nearest neighbour is at least as far as its offset, while
  * the points around it keep the sampling's pitch. Strays in the middle of a
  * hole, or on its rim (they see the hole's side empty too), were points of
  * the surface to the fill, which grew through them at their offset: with
  * 0.5 % of the points moved 1-4 pitches off, 15 of 108 clean corpus cases
  * had max errors of 1.3-4.2 pitches. On uniformly random samples of a plane
  * (the closest neighbours of any sampler), 0 to 4 of 50,000 points of the
  * surface pass the test; strays pass from about 2 pitches off. The pitch
  * of the neighbours, not the cloud's, keeps the sparse parts of a cloud of
  * varying density. */
bool
isStrayPoint (float nearest, float *around, int count, float pitches);

/** \brief Marks (1) the stray points among \a positions (isStrayPoint, over
  * the 8 nearest neighbours). The same marks for any \a threads. */
std::vector<char>
markStrayPoints (const std::vector<Eigen::Vector3f> &positions, int threads);
}  // namespace pcl_holefill::detail
