/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/hole_filling_parameters.h>

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace pcl_holefill::detail
{
/** \brief The two Gaussians of the paper's equations (1) and (7): g1 over the
  * distance between points (std sigma_d, cloud units) and g2 over the
  * difference of unit normals |n_p - n_ref| (std sigma_n, no unit; |n_p -
  * n_ref| runs from 0 to 2, so sigma_n = 0.1 all but ignores a neighbour whose
  * normal turns by more than ~15 degrees). sigma_n = kSup switches g2 off. */
struct BilateralKernel
{
  float sigma_d = 1.f;
  float sigma_n = kSup;

  float
  spatial (float sqr_distance) const;

  float
  normal (float sqr_normal_difference) const;
};

/** \brief Positions and unit normals of the points around a query. */
struct Neighbourhood
{
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
  std::vector<int> indices;  //!< in the searched cloud, when gathered by a search (else empty)

  void
  clear ()
  {
    positions.clear ();
    normals.clear ();
    indices.clear ();
  }
  std::size_t
  size () const { return positions.size (); }
};

/** \brief What the neighbours say about the surface at a candidate position. */
struct SurfaceEstimate
{
  bool valid = false;
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ ();  //!< unit
  Eigen::Vector3f axis_u = Eigen::Vector3f::UnitX ();  //!< tangent basis, unit
  Eigen::Vector3f axis_v = Eigen::Vector3f::UnitY ();
  /** Shape operator in (axis_u, axis_v): d(normal)/d(tangent step). Zero
    * unless the first-order propagation is on. */
  Eigen::Matrix2f shape = Eigen::Matrix2f::Zero ();
  float weight_sum = 0.f;  //!< K(b) of equation (2)
};

/** \brief Equations (1)-(2): the normal at \a position as the g1*g2-weighted
  * mean of the neighbours' normals, g2 measured against \a reference_normal
  * (the nearest former-boundary point's normal).
  *
  * With \a first_order, the same weights fit a linear normal field
  * n(p) = a + J (p - position) instead of a constant one, and the normal is
  * its value at \a position: the zero-order mean reproduces the rim's normal
  * unchanged, so a patch built from it is developable (a cone on a sphere,
  * the paper's Fig. 1(e)); the linear field carries the rim's curvature on
  * (exact for a sphere), while on the planes of a sharp feature J vanishes
  * and the result is the paper's. J's tangent part is returned as the shape
  * operator. Invalid when no neighbour has weight. */
SurfaceEstimate
propagateNormal (const Neighbourhood &neighbours, const Eigen::Vector3f &position,
                 const Eigen::Vector3f &reference_normal, const BilateralKernel &kernel, bool first_order);

/** \brief Equation (7): the g1*g2-weighted mean offset of the neighbours from
  * the tangent plane at \a position (g2 against the estimate's own normal),
  * each corrected by the height the estimate's shape operator predicts for
  * it (zero for the paper's zero-order estimate). Equation (8) then moves
  * the candidate by normal * offset. Returns 0 when no neighbour has weight. */
float
positionOffset (const Neighbourhood &neighbours, const Eigen::Vector3f &position,
                const SurfaceEstimate &estimate, const BilateralKernel &kernel);

}  // namespace pcl_holefill::detail
