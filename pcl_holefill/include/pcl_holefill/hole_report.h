/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <Eigen/Core>
#include <pcl/types.h>

#include <cstddef>

namespace pcl_holefill
{
/** \brief Why the contraction of a hole stopped. */
enum class Termination
{
  kNotStarted,     //!< nothing could be done (too few usable boundary points, bad setup)
  kControlRatio,   //!< kept control points / boundary points fell under the ratio (the paper's rule)
  kNoNewBoundary,  //!< the new boundary had fewer than 4 points
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
  bool closed = false;                 //!< no empty disc of 2 d_eq touches the boundary where the fill stopped
  std::size_t open_points = 0;         //!< boundary points where the fill stopped that an empty disc touches
  float open_diameter = 0.f;           //!< largest distance between two of them: the size of what is left
  unsigned resumed = 0;                //!< times the fill was taken up again from what was left open
  std::size_t outside_bound = 0;       //!< samples stopped at the region the rim can span (a runaway front)
  std::size_t beyond_rim = 0;          //!< samples dropped because the hole's rim does not enclose them
  std::size_t refitted_normals = 0;    //!< input normals near the hole refitted for the fill (blended across a
                                       //!< crease, or tilted by the hole); the output keeps the input's
  float diameter = 0.f;                //!< of the boundary loop
  float spacing = 0.f;                 //!< h: mean nearest-neighbour distance of the rim points
  float pitch = 0.f;                   //!< sampling pitch around the rim, sqrt(area per point)
  float equilibrium_distance = 0.f;    //!< d_eq used
  float radius = 0.f;                  //!< r of the first pass
  float noise = 0.f;                   //!< the rim's noise: RMS height of its neighbours over their fitted quadric
  float normal_spread = 0.f;           //!< median |n_p - n_q| between close rim neighbours (curvature, normal noise)
  bool first_order = false;            //!< the first-order extension was used (off on noisy rims)
  bool across_opening = false;         //!< filled across an opening, its rim a crease all round (the fronts
                                       //!< ran off along the walls first: detail/opening.h)
  bool withdrawn = false;              //!< the patch stayed open yet covered more than a band along the rim
                                       //!< can: it grew past the hole and none of it was added
  float sigma_n = 0.f;                 //!< sigma_n used (chosen per hole when automatic; kSup = off)
  Eigen::Vector3f centre = Eigen::Vector3f::Zero ();  //!< centroid of the rim
  pcl::Indices boundary;               //!< the hole's boundary loop, in order: indices of the output's first
                                       //!< points (the input, or the points of setIndices)
};

}  // namespace pcl_holefill
