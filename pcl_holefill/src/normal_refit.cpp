/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/normal_refit.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace pcl_holefill::detail
{
namespace
{
// A refit needs the best plane to hold this many neighbours more than the
// point's own plane ...
constexpr int kMinGain = 3;
// ... and this many times as many: a plane that wins by a few points on a
// curved patch is a tilt the curvature allows, not a crease.
constexpr float kMinGainRatio = 1.2f;
// The plane's neighbours must span a surface, not lie along a line (the
// ratio of the middle to the largest eigenvalue of their scatter).
constexpr float kMinSpread = 1e-3f;

int
countOnPlane (const Eigen::Vector3f &point, const Eigen::Vector3f &normal, const Eigen::Vector3f *positions,
              int count, float tolerance)
{
  int on = 0;
  for (int k = 0; k < count; ++k)
    on += std::abs ((positions[k] - point).dot (normal)) <= tolerance ? 1 : 0;
  return on;
}
}  // namespace

bool
refitCreaseNormal (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal,
                   const Eigen::Vector3f *positions, const Eigen::Vector3f *unit_normals, int count,
                   float tolerance, Eigen::Vector3f &refitted)
{
  const bool near_crease = std::any_of (unit_normals, unit_normals + count, [&] (const Eigen::Vector3f &n) {
    return (n - unit_normal).norm () > kCreaseNormalDifference;
  });
  if (!near_crease)
    return false;
  const int own = countOnPlane (point, unit_normal, positions, count, tolerance);
  int best = own;
  Eigen::Vector3f best_normal = unit_normal;
  for (int k = 0; k < count; ++k)
  {
    const int on = countOnPlane (point, unit_normals[k], positions, count, tolerance);
    if (on > best)
    {
      best = on;
      best_normal = unit_normals[k];
    }
  }
  if (best < own + kMinGain || static_cast<float> (best) < kMinGainRatio * static_cast<float> (own))
    return false;
  // PCA over the best plane's neighbours: the face's normal, not the
  // neighbour's estimate of it.
  Eigen::Vector3f mean = Eigen::Vector3f::Zero ();
  int on = 0;
  for (int k = 0; k < count; ++k)
    if (std::abs ((positions[k] - point).dot (best_normal)) <= tolerance)
    {
      mean += positions[k];
      ++on;
    }
  mean /= static_cast<float> (on);
  Eigen::Matrix3f scatter = Eigen::Matrix3f::Zero ();
  for (int k = 0; k < count; ++k)
    if (std::abs ((positions[k] - point).dot (best_normal)) <= tolerance)
      scatter += (positions[k] - mean) * (positions[k] - mean).transpose ();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> solver (scatter);
  refitted = solver.eigenvalues () (1) > kMinSpread * solver.eigenvalues () (2) ? solver.eigenvectors ().col (0)
                                                                              : best_normal;
  if (refitted.dot (unit_normal) < 0.f)
    refitted = -refitted;
  return true;
}

Eigen::Vector3f
quadricNormal (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal, const Eigen::Vector3f *positions,
               int count)
{
  constexpr int kCoefficients = 6;
  // Twice the coefficients at least, and a well-posed fit (smallest over
  // largest pivot of the normal equations, coordinates scaled to the reach).
  constexpr int kMinNeighbours = 2 * kCoefficients;
  constexpr float kMinConditioning = 1e-5f;
  if (count < kMinNeighbours)
    return unit_normal;
  const Eigen::Vector3f u = unit_normal.unitOrthogonal (), v = unit_normal.cross (u);
  float reach = 0.f;
  for (int k = 0; k < count; ++k)
    reach = std::max (reach, (positions[k] - point).norm ());
  if (!(reach > 0.f))
    return unit_normal;
  Eigen::Matrix<float, kCoefficients, kCoefficients> lhs = Eigen::Matrix<float, kCoefficients, kCoefficients>::Zero ();
  Eigen::Matrix<float, kCoefficients, 1> rhs = Eigen::Matrix<float, kCoefficients, 1>::Zero ();
  for (int k = 0; k < count; ++k)
  {
    const Eigen::Vector3f d = positions[k] - point;
    const float s = d.dot (u) / reach, t = d.dot (v) / reach;
    Eigen::Matrix<float, kCoefficients, 1> row;
    row << 1.f, s, t, s * s, s * t, t * t;
    lhs += row * row.transpose ();
    rhs += row * d.dot (unit_normal);
  }
  const Eigen::LDLT<Eigen::Matrix<float, kCoefficients, kCoefficients>> solver (lhs);
  const auto pivots = solver.vectorD ().cwiseAbs ();
  if (solver.info () != Eigen::Success || !(pivots.minCoeff () > kMinConditioning * pivots.maxCoeff ()))
    return unit_normal;
  const Eigen::Matrix<float, kCoefficients, 1> c = solver.solve (rhs);
  // The height field's gradient at the point, per unit length.
  const Eigen::Vector3f refitted = unit_normal - (c[1] / reach) * u - (c[2] / reach) * v;
  return refitted.allFinite () ? refitted.normalized () : unit_normal;
}

PlaneFit
fitPlane (const Eigen::Vector3f *positions, int count)
{
  PlaneFit plane;
  if (count < 1)
    return plane;
  for (int k = 0; k < count; ++k)
    plane.centroid += positions[k];
  plane.centroid /= static_cast<float> (count);
  Eigen::Matrix3f scatter = Eigen::Matrix3f::Zero ();
  for (int k = 0; k < count; ++k)
    scatter += (positions[k] - plane.centroid) * (positions[k] - plane.centroid).transpose ();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> solver (scatter);
  plane.normal = solver.eigenvectors ().col (0);
  plane.residual = std::max (solver.eigenvalues () (0), 0.f) / static_cast<float> (count);
  return plane;
}

float
normalRoughness (const std::vector<Eigen::Vector3f> &unit_normals, const std::vector<std::vector<int>> &neighbours,
                 const std::vector<char> &use)
{
  std::vector<float> angles;
  for (std::size_t i = 0; i < unit_normals.size (); ++i)
  {
    if (!use[i])
      continue;
    Eigen::Vector3f sum = Eigen::Vector3f::Zero ();
    for (const auto q : neighbours[i])
      if (q >= 0 && static_cast<std::size_t> (q) < use.size () && use[q] && static_cast<std::size_t> (q) != i)
        sum += unit_normals[q];
    if (sum.squaredNorm () > 0.f)
      angles.push_back (std::acos (std::clamp (unit_normals[i].dot (sum.normalized ()), -1.f, 1.f)));
  }
  if (angles.empty ())
    return 0.f;
  const auto middle = angles.begin () + static_cast<std::ptrdiff_t> (angles.size () / 2);
  std::nth_element (angles.begin (), middle, angles.end ());
  return *middle;
}

}  // namespace pcl_holefill::detail
