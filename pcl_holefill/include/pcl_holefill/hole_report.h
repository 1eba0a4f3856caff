/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <cstddef>

namespace pcl_holefill
{
/** \brief Why the contraction of a hole stopped. */
enum class Termination
{
  kNotStarted,     //!< nothing could be done (too few usable boundary points, bad setup)
  kControlRatio,   //!< kept control points / boundary points fell under the ratio (the paper's rule)
  kNoNewBoundary,  //!< the new boundary had fewer than 3 points
  kDiverging,      //!< the boundary grew past 1.5 times its first length: stopped, not closed
  kPassLimit       //!< the pass bound was reached
};

/** \brief A short name for reports: "ratio", "no_new_boundary", ... */
const char *
toString (Termination termination);

/** \brief What HoleFilling did to one hole. */
struct HoleReport
{
  std::size_t boundary_points = 0;     //!< |B'| of the first pass
  unsigned passes = 0;                 //!< contraction passes run
  std::size_t points_added = 0;        //!< filled points in the output
  std::size_t first_output_index = 0;  //!< where they start in the output cloud
  Termination termination = Termination::kNotStarted;
  bool closed = false;                 //!< stopped by the paper's rule with the fronts met
  float diameter = 0.f;                //!< of the boundary loop
  float spacing = 0.f;                 //!< mean input spacing around the rim
  float equilibrium_distance = 0.f;    //!< d_eq used
  float radius = 0.f;                  //!< r of the first pass
  float noise = 0.f;                   //!< RMS distance of the rim's neighbours to their fitted plane
  bool first_order = false;            //!< the first-order extension was used (off on noisy rims)
};

}  // namespace pcl_holefill
