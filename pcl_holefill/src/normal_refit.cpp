/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/normal_refit.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <vector>

namespace pcl_holefill::detail
{
namespace
{
// A refit needs the best plane to hold this many neighbours more than the
// point's own plane ...
constexpr int kMinGain = 3;
// ... or this many when the own plane holds the point alone and the best
// one lies a crease away: a normal square to no neighbour, between two
// faces, belongs to neither. Where a hole left a point at a convex edge 15
// neighbours within 6 h, its PCA normal pointed 55 degrees from both
// faces, 2 of them lay on a face's plane, and with a sharp sigma_n the fill
// took that normal for a face of its own: a flat sheet grew from the edge
// 0.11 (12 h) into a bored cube. (A lone normal on a curved face, tilted by
// its one-sided neighbourhood, is a few degrees from the best plane's, and
// keeps the stricter rule.)
constexpr int kMinGainOverLoneNormal = 2;
// ... and this many times as many: a plane that wins by a few points on a
// curved patch is a tilt the curvature allows, not a crease.
constexpr float kMinGainRatio = 1.2f;
// The plane's neighbours must span a surface, not lie along a line (the
// ratio of the middle to the largest eigenvalue of their scatter).
constexpr float kMinSpread = 1e-3f;
// A quadric fit's neighbour is an outlier when its residual exceeds this many
// median absolute residuals (as standard deviations of Gaussian noise) ...
constexpr float kOutlierResidualMads = 4.f;
constexpr float kMadToSigma = 1.4826f;

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
  const bool lone_between_faces = own <= 1 && (best_normal - unit_normal).norm () > kCreaseNormalDifference;
  const int gain = lone_between_faces ? kMinGainOverLoneNormal : kMinGain;
  if (best < own + gain || static_cast<float> (best) < kMinGainRatio * static_cast<float> (own))
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

namespace
{
constexpr int kQuadricCoefficients = 6;
using QuadricCoefficients = Eigen::Matrix<float, kQuadricCoefficients, 1>;
using QuadricMatrix = Eigen::Matrix<float, kQuadricCoefficients, kQuadricCoefficients>;
using QuadricSolver = Eigen::LDLT<QuadricMatrix>;

/** The terms of the height field at the tangent coordinates (s, t). */
QuadricCoefficients
quadricTerms (float s, float t)
{
  QuadricCoefficients row;
  row << 1.f, s, t, s * s, s * t, t * t;
  return row;
}

/** The normal equations of the height field h(s, t) over the positions that
  * \a use marks (all when empty), coordinates over \a reach, solved; false
  * when ill-posed. */
bool
fitHeightField (const Eigen::Vector3f &point, const Eigen::Vector3f &normal, const Eigen::Vector3f &u,
                const Eigen::Vector3f &v, const Eigen::Vector3f *positions, int count, float reach,
                const std::vector<char> &use, QuadricSolver &solver, QuadricCoefficients &c)
{
  // Twice the coefficients at least, and a well-posed fit (smallest over
  // largest pivot of the normal equations, coordinates scaled to the reach).
  constexpr int kMinNeighbours = 2 * kQuadricCoefficients;
  constexpr float kMinConditioning = 1e-5f;
  QuadricMatrix lhs = QuadricMatrix::Zero ();
  QuadricCoefficients rhs = QuadricCoefficients::Zero ();
  int used = 0;
  for (int k = 0; k < count; ++k)
  {
    if (!use.empty () && !use[k])
      continue;
    const Eigen::Vector3f d = positions[k] - point;
    const QuadricCoefficients row = quadricTerms (d.dot (u) / reach, d.dot (v) / reach);
    lhs += row * row.transpose ();
    rhs += row * d.dot (normal);
    ++used;
  }
  if (used < kMinNeighbours)
    return false;
  solver.compute (lhs);
  const auto pivots = solver.vectorD ().cwiseAbs ();
  if (solver.info () != Eigen::Success || !(pivots.minCoeff () > kMinConditioning * pivots.maxCoeff ()))
    return false;
  c = solver.solve (rhs);
  return c.allFinite ();
}

/** Marks in \a use the positions that the field fitted without them would
  * pass within the allowance; returns how many it left out. The residual
  * of a fit that held the point is not enough: a lone point on one side of
  * a one-sided neighbourhood pulls the quadric through itself (its
  * leverage h is near 1), so each residual is divided by 1 - h, which
  * makes it the residual of the fit without that point. */
int
keepNearField (const Eigen::Vector3f &point, const Eigen::Vector3f &normal, const Eigen::Vector3f &u,
               const Eigen::Vector3f &v, const Eigen::Vector3f *positions, int count, float reach,
               const QuadricSolver &solver, const QuadricCoefficients &c, float min_allowance, std::vector<char> &use)
{
  constexpr float kMinShareLeft = 1e-2f;  // of a residual's leverage, against 0 / 0
  std::vector<float> residual (count);
  for (int k = 0; k < count; ++k)
  {
    const Eigen::Vector3f d = positions[k] - point;
    const QuadricCoefficients row = quadricTerms (d.dot (u) / reach, d.dot (v) / reach);
    const float leverage = row.dot (solver.solve (row));
    residual[k] = std::abs (d.dot (normal) - row.dot (c)) / std::max (1.f - leverage, kMinShareLeft);
  }
  std::vector<float> sorted (residual);
  const auto middle = sorted.begin () + count / 2;
  std::nth_element (sorted.begin (), middle, sorted.end ());
  const float allowance = std::max (min_allowance, kOutlierResidualMads * kMadToSigma * *middle);
  use.assign (count, 1);
  int left_out = 0;
  for (int k = 0; k < count; ++k)
    if (!(residual[k] <= allowance))
    {
      use[k] = 0;
      ++left_out;
    }
  return left_out;
}
}  // namespace

Eigen::Vector3f
quadricNormal (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal, const Eigen::Vector3f *positions,
               int count, float outlier_allowance)
{
  const Eigen::Vector3f u = unit_normal.unitOrthogonal (), v = unit_normal.cross (u);
  float reach = 0.f;
  for (int k = 0; k < count; ++k)
    reach = std::max (reach, (positions[k] - point).norm ());
  if (!(reach > 0.f))
    return unit_normal;
  std::vector<char> use;
  QuadricSolver solver;
  QuadricCoefficients c;
  if (!fitHeightField (point, unit_normal, u, v, positions, count, reach, use, solver, c))
    return unit_normal;
  // One least-squares fit follows a stray point: a single outlier four
  // pitches off the surface among 30 neighbours tilted a rim normal by 12
  // degrees, and the rim's tangent plane then cut the fill of a sphere cap
  // short. Those far from the first fit are left out of a second.
  if (outlier_allowance > 0.f &&
      keepNearField (point, unit_normal, u, v, positions, count, reach, solver, c, outlier_allowance, use) > 0 &&
      !fitHeightField (point, unit_normal, u, v, positions, count, reach, use, solver, c))
    return unit_normal;
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
  plane.spread = std::max (solver.eigenvalues () (1), 0.f) / static_cast<float> (count);
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
