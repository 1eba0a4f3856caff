/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/local_surface.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace pcl_holefill::detail
{
namespace
{
// Below this total weight a neighbourhood says nothing.
constexpr float kMinWeight = 1e-6f;
// The slope of the linear normal field is fitted freely along the directions
// in which the neighbours spread, and taken as zero across a direction that
// holds less than kRowShare of their spread (a row of neighbours, e.g. along
// a crease: a slope fitted across it turned the normal by 100 per unit and
// threw an L-block's concave edge 0.036 off). kSlopeRidge only keeps the
// solve regular. A ridge on every direction would shrink each fitted
// curvature a little (0.2 % at 1e-3 of the spread), and the fill of a large
// hole, ring by ring, compounds that: 160 rings flattened a sphere cap by
// 0.023, a quarter of its depth.
constexpr float kSlopeRidge = 1e-6f;
constexpr float kRowShare = 0.01f;

/** The ridge for the tangent block of the normal-field fit's normal matrix
  * \a lhs (rows 1, 2 = tangent coordinates, row 0 = constant): none along a
  * principal direction of the neighbours' weighted spread that holds at
  * least kRowShare of the total, and one as large as the total across a
  * direction that holds less (a row of neighbours: the slope across it
  * cannot be measured, and is taken as zero, the paper's zero order). */
Eigen::Matrix2f
slopeRidge (const Eigen::Matrix3f &lhs)
{
  const float total = lhs (0, 0);
  const Eigen::Vector2f first = lhs.block<2, 1> (1, 0);
  const Eigen::Matrix2f covariance = lhs.bottomRightCorner<2, 2> () - first * first.transpose () / total;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2f> solver (covariance);
  const float spread = std::max (covariance.trace (), 0.f);
  Eigen::Vector2f ridge = Eigen::Vector2f::Constant (kSlopeRidge * spread);
  for (int k = 0; k < 2; ++k)
    if (solver.eigenvalues () (k) < kRowShare * spread)
      ridge (k) = spread;
  return solver.eigenvectors () * ridge.asDiagonal () * solver.eigenvectors ().transpose ();
}
}  // namespace

float
BilateralKernel::spatial (float sqr_distance) const
{
  return std::exp (-sqr_distance / (2.f * sigma_d * sigma_d));
}

float
BilateralKernel::normal (float sqr_normal_difference) const
{
  if (std::isinf (sigma_n))
    return 1.f;
  return std::exp (-sqr_normal_difference / (2.f * sigma_n * sigma_n));
}

SurfaceEstimate
propagateNormal (const Neighbourhood &neighbours, const Eigen::Vector3f &position,
                 const Eigen::Vector3f &reference_normal, const BilateralKernel &kernel, bool first_order)
{
  SurfaceEstimate estimate;
  const std::size_t n = neighbours.size ();
  std::vector<float> weights (n);
  Eigen::Vector3f mean = Eigen::Vector3f::Zero ();
  float total = 0.f;
  for (std::size_t i = 0; i < n; ++i)
  {
    weights[i] = kernel.spatial ((neighbours.positions[i] - position).squaredNorm ()) *
                 kernel.normal ((neighbours.normals[i] - reference_normal).squaredNorm ());
    mean += weights[i] * neighbours.normals[i];
    total += weights[i];
  }
  if (!(total > kMinWeight) || !(mean.norm () > kMinWeight))
    return estimate;
  estimate.valid = true;
  estimate.weight_sum = total;
  estimate.normal = mean.normalized ();  // equation (1); K(b) cancels in the normalisation
  estimate.axis_u = estimate.normal.unitOrthogonal ();
  estimate.axis_v = estimate.normal.cross (estimate.axis_u);
  if (!first_order)
    return estimate;

  // Weighted least squares of n_p ~ a + J u_p, u_p the tangent coordinates.
  Eigen::Matrix3f lhs = Eigen::Matrix3f::Zero ();
  Eigen::Matrix3f rhs = Eigen::Matrix3f::Zero ();
  for (std::size_t i = 0; i < n; ++i)
  {
    const Eigen::Vector3f d = neighbours.positions[i] - position;
    const Eigen::Vector3f row (1.f, d.dot (estimate.axis_u), d.dot (estimate.axis_v));
    lhs += weights[i] * row * row.transpose ();
    rhs += weights[i] * row * neighbours.normals[i].transpose ();
  }
  lhs.bottomRightCorner<2, 2> () += slopeRidge (lhs);
  const Eigen::Matrix3f solution = lhs.ldlt ().solve (rhs);
  if (!solution.allFinite ())
    return estimate;
  const Eigen::Vector3f at_position = solution.row (0).transpose ();
  if (!(at_position.norm () > kMinWeight) || at_position.dot (estimate.normal) <= 0.f)
    return estimate;
  estimate.normal = at_position.normalized ();
  estimate.axis_u = estimate.normal.unitOrthogonal ();
  estimate.axis_v = estimate.normal.cross (estimate.axis_u);
  // Rows 1 and 2 are dn/du and dn/dv in the old basis; re-express in the new one.
  Eigen::Matrix<float, 3, 2> slope;
  slope.col (0) = solution.row (1).transpose ();
  slope.col (1) = solution.row (2).transpose ();
  // Directional derivative along a tangent t: slope * (coordinates of t in the old basis).
  const Eigen::Vector3f old_u = mean.normalized ().unitOrthogonal ();
  const Eigen::Vector3f old_v = mean.normalized ().cross (old_u);
  Eigen::Matrix2f shape;
  for (int k = 0; k < 2; ++k)
  {
    const Eigen::Vector3f t = k == 0 ? estimate.axis_u : estimate.axis_v;
    const Eigen::Vector3f dn = slope * Eigen::Vector2f (t.dot (old_u), t.dot (old_v));
    shape (0, k) = dn.dot (estimate.axis_u);
    shape (1, k) = dn.dot (estimate.axis_v);
  }
  estimate.shape = 0.5f * (shape + shape.transpose ());
  return estimate;
}

float
positionOffset (const Neighbourhood &neighbours, const Eigen::Vector3f &position,
                const SurfaceEstimate &estimate, const BilateralKernel &kernel)
{
  float total = 0.f, weighted = 0.f;
  for (std::size_t i = 0; i < neighbours.size (); ++i)
  {
    const Eigen::Vector3f d = neighbours.positions[i] - position;
    const float w = kernel.spatial (d.squaredNorm ()) *
                    kernel.normal ((neighbours.normals[i] - estimate.normal).squaredNorm ());
    const Eigen::Vector2f u (d.dot (estimate.axis_u), d.dot (estimate.axis_v));
    // A curved surface falls away from its tangent plane by -u'Su/2: expect that, not zero.
    const float expected_height = -0.5f * u.dot (estimate.shape * u);
    weighted += w * (d.dot (estimate.normal) - expected_height);
    total += w;
  }
  return total > kMinWeight ? weighted / total : 0.f;
}

}  // namespace pcl_holefill::detail
