/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <limits>
#include <vector>

namespace pcl_holefill::detail
{
/** \brief The two smallest distinct (non-zero) squared distances among a
  * point's neighbours, infinite until seen: a repeated position says nothing
  * of the spacing. Feeds isStrayPoint (as distances). */
struct NearestTwo
{
  float nearest = std::numeric_limits<float>::infinity ();
  float second = std::numeric_limits<float>::infinity ();

  void
  add (float sqr_distance)
  {
    if (!(sqr_distance > 0.f))
      return;
    second = std::min (second, std::max (nearest, sqr_distance));
    nearest = std::min (nearest, sqr_distance);
  }
};

/** \brief Is a point whose nearest and second nearest neighbours lie at
  * \a nearest and \a second a stray, given the sampling pitches
  * (samplingPitch) at its \a count neighbours, \a around (reordered)? It is
  * when the nearest is farther than \a pitches times their median pitch, or
  * the second farther than that plus half a pitch (a pair of strays).
  *
  * A scanner's stray return (a mixed pixel, a reflection) lies off the
  * surface: its nearest neighbour is at least as far as its offset, while
  * the points around it keep the sampling's pitch. Strays in the middle of a
  * hole, or on its rim (they see the hole's side empty too), were points of
  * the surface to the fill, which grew through them at their offset: with
  * 0.5 % of the points moved 1-4 pitches off, 15 of 108 clean corpus cases
  * had max errors of 1.3-4.2 pitches. Two strays next to each other (one
  * case of those: two points of one scan line, 3.8 pitches inside a
  * cylinder) are each other's nearest neighbour; the second nearest is on
  * the surface again. On uniformly random samples of a plane (the closest
  * neighbours of any sampler), the nearest neighbour lies past 2 pitches for
  * 1 point in 290,000 (exp(-4 pi)) and the second for 1 in 21,000, past 2.5
  * pitches for 1 in 16 million: hence the half pitch more for the pair. The
  * pitch of the neighbours, not the cloud's, keeps the sparse parts of a
  * cloud of varying density. */
bool
isStrayPoint (float nearest, float second, float *around, int count, float pitches);

/** \brief Marks (1) the stray points among \a positions (isStrayPoint, over
  * the 8 nearest neighbours). The same marks for any \a threads. */
std::vector<char>
markStrayPoints (const std::vector<Eigen::Vector3f> &positions, int threads);
}  // namespace pcl_holefill::detail
