/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl_holefill::detail
{
/** \brief Normals further apart than this (|n_q - n_p|, ~30 degrees) are
  * on two sides of a crease: PCA normals turn 45 degrees towards a 90 degree
  * edge, while the normals of close neighbours on a smooth surface differ by
  * its curvature only (3 degrees over 3 pitches of a sphere 50 pitches wide). */
constexpr float kCreaseNormalDifference = 0.5f;

/** \brief A normal blended across a crease, refitted to the face its point
  * lies on.
  *
  * Normals estimated by PCA over k neighbours (PCL NormalEstimation, what a
  * cloud without normals gets) turn gradually across every sharp edge: within
  * ~2 pitches of it they point between the two faces, 20-35 degrees off. The
  * fill continues the rim's normals, so a blended rim rounds the edge off and
  * the rounding grows pass by pass (random samples of a cube, a corner hole:
  * up to 0.11, 6 pitches, off the cube).
  *
  * The test: the plane through \a point normal to each neighbour's normal
  * (and to the point's own) counts the neighbours lying within \a tolerance
  * of it. On one face of a crease, a normal of that face, taken from a
  * neighbour farther from the edge, has every point of the face on its plane;
  * a blended normal has only those close to the point. When the best plane
  * holds clearly more neighbours than the point's own (3 more, or 2 when
  * the point lies alone on its own plane and the best is a crease away,
  * and 1.2 times as many), the normal is refitted by PCA to that plane's
  * neighbours and returned in \a refitted, on the side of the old one. Exact normals,
  * and estimated normals away from creases, already hold the most
  * neighbours: false, nothing changes. Only near a crease (a neighbour's
  * normal kCreaseNormalDifference away): on smooth parts a plane tilted
  * along the surface can hold more neighbours within the tolerance than the
  * tangent plane, and refitted there, the exact normals of a sphere went 3
  * degrees off (max error 0 -> 0.009) and noisy ones more.
  *
  * \a positions and \a unit_normals hold the \a count neighbours (the point
  * itself may be among them). */
bool
refitCreaseNormal (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal,
                   const Eigen::Vector3f *positions, const Eigen::Vector3f *unit_normals, int count,
                   float tolerance, Eigen::Vector3f &refitted);

/** \brief The normal of the quadric height field through \a point that fits
  * its \a count neighbours best (a "jet" of order 2 over the point's tangent
  * plane), or \a unit_normal when they do not span the surface.
  *
  * A rim point's neighbours all lie on one side of it, away from the hole.
  * On a curved surface the plane that PCA fits to them is their chord, not
  * the tangent at the point: its normal leans away from the hole (about a
  * degree on a sphere 40 pitches in radius, random samples, k = 16), and
  * the fill, which continues the rim's normals and their change, climbs
  * accordingly (a cap 32 pitches across came out 0.014, 1.1 pitches, too
  * high). The quadric takes the curvature out; its gradient at the point
  * is the tilt to remove. \a positions and the point are expected on one
  * smooth piece (no crease among them).
  *
  * With \a outlier_allowance > 0 (cloud units), neighbours farther from the
  * fitted surface than both that and 4 robust standard deviations of the
  * residuals are left out and the quadric is fitted again. */
Eigen::Vector3f
quadricNormal (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal, const Eigen::Vector3f *positions,
               int count, float outlier_allowance = 0.f);

/** \brief A plane fitted by PCA: its unit normal (on either side), the
  * centroid it passes through, and the variance of the points along the
  * normal (zero on a noise-free plane; the noise variance plus what a crease
  * or the curvature adds otherwise). */
struct PlaneFit
{
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ ();
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero ();
  float residual = 0.f;
  float spread = 0.f;  //!< the variance along the plane's narrower direction within it
};

/** \brief The PCA plane of \a count positions (at least one). */
PlaneFit
fitPlane (const Eigen::Vector3f *positions, int count);

/** \brief How rough a normal field is: the median, over the points marked in
  * \a use, of the angle (radians) between a point's normal and the mean of
  * the normals of its marked neighbours (\a neighbours[i]). Exact normals of
  * a smooth surface measure what its curvature turns them by between
  * neighbours; PCA normals of noisy points add their noise. 0 without any
  * marked point. */
float
normalRoughness (const std::vector<Eigen::Vector3f> &unit_normals, const std::vector<std::vector<int>> &neighbours,
                 const std::vector<char> &use);

}  // namespace pcl_holefill::detail
