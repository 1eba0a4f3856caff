/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/normal_refit.h>
#include <pcl_holefill/detail/rim_side_planes.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace pcl_holefill::detail
{
namespace
{
// Rim points on either side of a window's centre: a plane needs a stretch
// of rim that bends within it (an L along a face's border).
constexpr int kSideWindow = 6;
// The mean |n . m| of the points on a side plane stays under this: their
// normals lie along it (0.33 on fandisk's face); a flat hole's rim has 1,
// the rim of a cap cut by a ball of 0.6 radii 0.8.
constexpr float kMaxSideAlong = 0.5f;
// The mean of the unit normals on a side plane is at least this long when
// they agree (fandisk's face: one face's normals; a plate's end: two faces'
// opposite ones, near 0).
constexpr float kMinTurnAgreement = 0.5f;
// The rim reaches this many window extents below a side plane: the taken
// face lies across the hole (fandisk's: 12 h deep, a window 3-5 h long).
// The rim of a box's missing lid lies in the lid's plane all round, up to a
// pitch below it where the last row of samples stops short or noise moves
// it, and was taken for a side (0.1 % noise: 9 pitches off).
constexpr float kMinSideDepth = 1.f;

/** The longest distance between the window's ends and its centre point. */
float
windowExtent (const std::vector<Eigen::Vector3f> &positions, int centre)
{
  const auto n = static_cast<int> (positions.size ());
  const Eigen::Vector3f &c = positions[centre];
  return std::max ((positions[(centre - kSideWindow + n) % n] - c).norm (),
                   (positions[(centre + kSideWindow) % n] - c).norm ());
}

/** The plane of the window of rim points around \a centre, if they lie in
  * one and span it. */
bool
windowPlane (const std::vector<Eigen::Vector3f> &positions, int centre, float tolerance, Eigen::Vector3f &point,
             Eigen::Vector3f &normal)
{
  const auto n = static_cast<int> (positions.size ());
  std::array<Eigen::Vector3f, 2 * kSideWindow + 1> window;
  for (int j = -kSideWindow; j <= kSideWindow; ++j)
    window[j + kSideWindow] = positions[(centre + j + n) % n];
  const PlaneFit plane = fitPlane (window.data (), static_cast<int> (window.size ()));
  point = plane.centroid;
  normal = plane.normal;
  // In the plane, and wider across the stretch than the tolerance: a
  // straight stretch lies in every plane through it.
  const float sqr = tolerance * tolerance;
  return plane.residual <= sqr && plane.spread >= 4.f * sqr;
}
}  // namespace

std::vector<RimSidePlane>
findRimSidePlanes (const std::vector<Eigen::Vector3f> &positions, const std::vector<Eigen::Vector3f> &normals,
                   float tolerance)
{
  std::vector<RimSidePlane> planes;
  const auto n = static_cast<int> (positions.size ());
  if (n < 4 * kSideWindow || normals.size () != positions.size () || !(tolerance > 0.f))
    return planes;
  for (int k = 0; k < n; k += kSideWindow)
  {
    RimSidePlane plane;
    if (!windowPlane (positions, k, tolerance, plane.point, plane.normal))
      continue;
    int above = 0, below = 0;
    float along = 0.f, deepest = 0.f;
    Eigen::Vector3f mean_normal = Eigen::Vector3f::Zero ();
    for (int q = 0; q < n; ++q)
    {
      const float height = (positions[q] - plane.point).dot (plane.normal);
      deepest = std::max (deepest, std::abs (height));
      if (height > tolerance)
        ++above;
      else if (height < -tolerance)
        ++below;
      else
      {
        plane.on.push_back (q);
        along += std::abs (normals[q].dot (plane.normal));
        mean_normal += normals[q];
      }
    }
    if ((above > 0) == (below > 0))
      continue;  // the rim on both sides, or all of it in the plane
    if (above > 0)
      plane.normal = -plane.normal;
    const auto on = static_cast<int> (plane.on.size ());
    if (on < 3 * kSideWindow || above + below < on || along > kMaxSideAlong * static_cast<float> (on) ||
        !(deepest >= kMinSideDepth * windowExtent (positions, k)))
      continue;
    plane.turns_rim = (mean_normal / static_cast<float> (on)).norm () >= kMinTurnAgreement;
    planes.push_back (std::move (plane));
  }
  return planes;
}

}  // namespace pcl_holefill::detail
