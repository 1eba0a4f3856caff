/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/detail/boundary_point_test.h>
#include <pcl_holefill/detail/elastic_sampler.h>
#include <pcl_holefill/detail/normal_propagation.hpp>
#include <pcl_holefill/detail/normal_refit.h>

#include <pcl/console/print.h>

#include <algorithm>
#include <cmath>

namespace pcl_holefill::detail
{
// A control candidate is repelled by a former boundary point closer than
// d_eq (eq. 5); the slack absorbs the small shift of the position optimisation.
constexpr float kRepulsionReach = 0.95f;
// Closer than this (in d_eq) to existing surface, a new point would duplicate it.
constexpr float kDuplicateReach = 0.5f;
// Consecutive control points or samples further apart than this (in d_eq)
// belong to different pieces of boundary: the front has met itself between them.
constexpr float kChainBreak = 3.f;
// ... unless the chain is a rim of input points (not yet sampled) and every
// candidate discarded between the two was stopped only by the chain's own
// vertices within this arc length (in d_eq) of its source: the rim of a
// randomly sampled cloud has gaps of 3 d_eq and clusters of points that
// repel their neighbours' candidates, and a cut there left a seam from the
// rim to the centre of a large hole. Such a gap is bridged up to kMaxBridge
// d_eq, between control points whose normals agree within kBridgeCosine;
// the samples along the bridge are placed and checked like any other.
// A sampled chain is d_eq apart: a gap in its control points is a meeting.
constexpr float kOwnChainArc = 3.f;
constexpr float kMaxBridge = 6.f;
constexpr float kBridgeCosine = 0.95f;
// ... and only on a rim whose neighbours' normals all agree within this
// (37 degrees): on a rim that crosses an edge of a part (a cube's corner, a
// bore's edge on PCA normals) a bridge, even along one face, changed where
// the fronts went (bored cube, random, PCA normals: covered 0.93 -> 0.89).
constexpr float kSmoothRimCosine = 0.8f;
// Half-width of the stencil that gives the boundary tangent.
constexpr int kTangentStencil = 2;
// cos 45 degrees: a reference point's normal within this of the constraint's
// facing direction (setConstraintFacing) faces the same way.
constexpr float kFacingCosine = 0.7071f;
// setSignTowardsFront: a front vertex this far (in d_eq) past a reference
// point's tangent plane grew on a face beyond that plane, not towards it.
// Nearer, the plane may be the one the front approaches: at the flat rim of
// a thin bowl, the inner wall's front rose 3.9 pitches above the rim when
// fronts 0.16-0.25 pitch past the wall's planes were let by (d_eq / 4 is
// 0.28 pitch: a margin this narrow, measured, not a proven bound).
constexpr float kFrontPastPlane = 0.25f;
// optimisePosition gathers the input within (1 + this) r once for its three
// estimates, again only when eq. (8) moved the candidate farther: at most
// 0.001 r on a clean sphere; on a cube at 0.5 % noise, 5 moves in 3,000
// went past 0.25 r (the largest 0.43 r).
constexpr float kGatherSlack = 0.25f;

/** Unit tangent of a chain at vertex i from the vertices kTangentStencil away. */
inline Eigen::Vector3f
chainTangent (const FrontChain &chain, int i)
{
  const int m = static_cast<int> (chain.vertices.size ());
  for (int reach = std::min (kTangentStencil, m - 1); reach >= 1; --reach)
  {
    const int a = chain.closed ? (i - reach + m) % m : std::max (0, i - reach);
    const int b = chain.closed ? (i + reach) % m : std::min (m - 1, i + reach);
    const Eigen::Vector3f t = chain.vertices[b].position - chain.vertices[a].position;
    if (t.norm () > 1e-9f)
      return t.normalized ();
  }
  return Eigen::Vector3f::Zero ();
}

template <typename PointT> void
ElasticSampler<PointT>::setInputCloud (const PointCloudConstPtr &cloud)
{
  input_ = cloud;
  points_before_front_ = cloud->size ();
  propagation_.setInputCloud (cloud);
  curvature_signs_.clear ();
}

template <typename PointT> void
ElasticSampler<PointT>::setSearchMethod (const SearchPtr &search)
{
  propagation_.setSearchMethod (search);
}

template <typename PointT> bool
ElasticSampler<PointT>::optimisePosition (Eigen::Vector3f &position, const Eigen::Vector3f &reference_normal,
                                          Eigen::Vector3f &normal, Neighbourhood &around) const
{
  // One search of a ball kGatherSlack wider serves the three estimates
  // while the candidate stays within the slack of where it was gathered
  // (it moves along its normal by a fraction of r): the searches were a
  // quarter of the fill's time.
  const float slack = kGatherSlack * propagation_.getRadius ();
  thread_local Neighbourhood wider;  // its buffers kept from call to call
  Eigen::Vector3f p = position, gathered_at = position;
  propagation_.gatherNeighbourhood (gathered_at, wider, propagation_.getRadius () + slack);
  const auto gatherAround = [&] (const Eigen::Vector3f &q) {
    if (!((q - gathered_at).norm () <= slack))
    {
      gathered_at = q;
      propagation_.gatherNeighbourhood (gathered_at, wider, propagation_.getRadius () + slack);
    }
    propagation_.selectNeighbourhood (wider, q, around);
  };
  // Two rounds of "normal, then offset along it" (the paper: enough in practice).
  for (int round = 0; round < 2; ++round)
  {
    gatherAround (p);
    const SurfaceEstimate e = propagation_.computeNormal (around, p, reference_normal);
    if (!e.valid)
      return false;
    p += e.normal * positionOffset (around, p, e, propagation_.kernel ());  // eq. (8)
  }
  gatherAround (p);
  const SurfaceEstimate e = propagation_.computeNormal (around, p, reference_normal);
  if (!e.valid || !p.allFinite ())
    return false;
  position = p;
  normal = e.normal;
  return true;
}

template <typename PointT> int
ElasticSampler<PointT>::curvatureSign (int index) const
{
  // Filled before each pass for every point there is; threads of one pass
  // may compute the same sign at once and store the same value (atomic
  // accesses keep that well defined).
  signed char *cached = &curvature_signs_[index];
  const signed char known = __atomic_load_n (cached, __ATOMIC_RELAXED);
  if (known != 2)
    return known;
  const auto sign = static_cast<signed char> (signOfMeanHeight (index, nullptr));
  __atomic_store_n (cached, sign, __ATOMIC_RELAXED);
  return sign;
}

template <typename PointT> int
ElasticSampler<PointT>::signOfMeanHeight (int index, const Eigen::Vector3f *towards) const
{
  const PointT &q = (*input_)[index];
  const Eigen::Vector3f centre = q.getVector3fMap ();
  const Eigen::Vector3f normal = q.getNormalVector3fMap ().normalized ();
  const Eigen::Vector3f side = towards ? Eigen::Vector3f (*towards - centre) : Eigen::Vector3f::Zero ();
  thread_local Neighbourhood neighbours;  // its buffers kept from call to call
  propagation_.gatherNeighbourhood (centre, neighbours, constraintReach ());
  float total = 0.f, offset = 0.f;
  for (std::size_t i = 0; i < neighbours.size (); ++i)
  {
    const Eigen::Vector3f d = neighbours.positions[i] - centre;
    if (towards && !(d.dot (side) > 0.f))
      continue;
    const float w = propagation_.kernel ().spatial (d.squaredNorm ());
    offset += w * d.dot (normal);
    total += w;
  }
  const float mean = total > 0.f ? offset / total : 0.f;
  return mean < -sign_tolerance_ ? 1 : (mean > sign_tolerance_ ? -1 : 0);
}

template <typename PointT> bool
ElasticSampler<PointT>::boundsAnotherFace (int index, const Eigen::Vector3f &q, const Eigen::Vector3f &normal,
                                           const Eigen::Vector3f &origin, int sign) const
{
  // Heights are taken on the side the label bounds (sign +-1), as in breaksCombinationConstraint.
  const bool origin_past =
      static_cast<float> (sign) * (origin - q).dot (normal) > kFrontPastPlane * equilibrium_distance_;
  // Only asked of a point that would reject (rare): its neighbourhood is
  // gathered again, not cached.
  return origin_past && signOfMeanHeight (index, &origin) != sign;
}

template <typename PointT> float
ElasticSampler<PointT>::ownFaceSlope (int index, const Eigen::Vector3f &q, const Eigen::Vector3f &normal,
                                      const Eigen::Vector3f &towards) const
{
  // Only asked of a point that would reject (rare): not cached.
  Neighbourhood neighbours;
  propagation_.gatherNeighbourhood (q, neighbours, constraintReach ());
  const Eigen::Vector3f side = towards - q;
  float slope = 0.f;
  for (std::size_t i = 0; i < neighbours.size (); ++i)
  {
    const int j = neighbours.indices[i];
    const Eigen::Vector3f d = neighbours.positions[i] - q;
    // Not the point itself, nor the fill (it must not widen its own bound),
    // nor another face, nor the face behind the point.
    if (j == index || j >= static_cast<int> (points_before_front_) ||
        !((neighbours.normals[i] - normal).norm () < kCreaseNormalDifference) || !(d.dot (side) > 0.f))
      continue;
    // Rise that the neighbour's own plane does not share: on a face that
    // curves up for real (a bore's concave wall) the point lies as far above
    // the neighbour's plane as the neighbour above its own, and its plane
    // bounds; a tilted normal has the point on its neighbours' planes.
    const float mutual = std::max (0.f, -d.dot (neighbours.normals[i]));
    slope = std::max (slope, (d.dot (normal) - mutual - tolerance_) / d.norm ());
  }
  return slope;
}

template <typename PointT> bool
ElasticSampler<PointT>::breaksCombinationConstraint (const Eigen::Vector3f &position, const Eigen::Vector3f &origin,
                                                     const Neighbourhood &around) const
{
  const float reach = constraintReach ();
  const float sqr_reach = reach * reach;
  for (std::size_t k = 0; k < around.size (); ++k)
  {
    const Eigen::Vector3f &q = around.positions[k];
    const float dx = q.x () - position.x (), dy = q.y () - position.y (), dz = q.z () - position.z ();
    const float sqr_distance = dx * dx + dy * dy + dz * dz;
    if (!(sqr_distance <= sqr_reach))
      continue;
    // Facing first: a point that does not face the way bounds nothing, and
    // its curvature sign (a neighbourhood gathered) need not be computed.
    const Eigen::Vector3f &normal = around.normals[k];
    if (!constraint_facing_.isZero () && normal.dot (constraint_facing_) < kFacingCosine)
      continue;
    const int sign = curvatureSign (around.indices[k]);
    if (sign == 0)
      continue;
    // Past the plane on the side the label bounds: above a convex point's, below a concave one's.
    const float past_by = static_cast<float> (sign) * (position - q).dot (normal);
    const float distance = std::sqrt (sqr_distance);
    if (!(past_by > tolerance_ + slope_ * distance))
      continue;
    // A convex point whose own face rises past its tangent plane towards
    // the sample has a tilted normal (vertex normals averaged over an
    // irregular mesh's long triangles: a few degrees off on a curved strip),
    // and bounds the sample only beyond that rise. Not a concave one: a
    // point at the top of a wall that curves concavely is labelled so even
    // at a convex crease, its face bends away below its plane for real, and
    // the wall's front ran up past the crease (a thin bowl's flat rim).
    if (sign > 0 && past_by <= tolerance_ + ownFaceSlope (around.indices[k], q, normal, position) * distance)
      continue;
    if (!(sign_towards_front_ && boundsAnotherFace (around.indices[k], q, normal, origin, sign)))
      return true;
  }
  return false;
}

template <typename PointT> bool
ElasticSampler<PointT>::aboveRimPlanes (const Eigen::Vector3f &position) const
{
  for (std::size_t k = 0; k < rim_plane_points_.size (); ++k)
  {
    const Eigen::Vector3f d = position - rim_plane_points_[k];
    if (d.dot (rim_plane_normals_[k]) > rim_plane_tolerance_ + rim_plane_slope_ * d.norm ())
      return true;
  }
  return false;
}

template <typename PointT> std::size_t
ElasticSampler<PointT>::surfacePointsWithin (const Eigen::Vector3f &position, const Eigen::Vector3f &normal,
                                             float reach) const
{
  PointT query;
  query.getVector3fMap () = position;
  thread_local pcl::Indices found;
  thread_local std::vector<float> sqr_distances;
  propagation_.getSearchMethod ()->radiusSearch (query, reach, found, sqr_distances);
  const auto &cloud = *propagation_.getInputCloud ();
  return static_cast<std::size_t> (std::count_if (found.begin (), found.end (), [&] (int j) {
    return !normal.allFinite () ||
           !onOtherSideOfThinPart (cloud[j].getVector3fMap () - position, normal,
                                   cloud[j].getNormalVector3fMap ().normalized ());
  }));
}

template <typename PointT> typename ElasticSampler<PointT>::Verdict
ElasticSampler<PointT>::place (Eigen::Vector3f &position, const Eigen::Vector3f &origin,
                               const Eigen::Vector3f &reference_normal, Eigen::Vector3f &normal) const
{
  thread_local Neighbourhood around;  // its buffers kept from call to call
  if (!optimisePosition (position, reference_normal, normal, around))
    return Verdict::kUnsupported;
  if (bound_radius_ > 0.f && (position - bound_centre_).norm () > bound_radius_)
    return Verdict::kOutsideBound;
  if (surfacePointsWithin (position, normal, kDuplicateReach * equilibrium_distance_) > 0)
    return Verdict::kTooClose;
  if (aboveRimPlanes (position))
    return Verdict::kBeyondRim;
  if (!rim_.empty () && rimGapAround (position, rim_axis_, rim_) > max_rim_gap_along_axis_ &&
      rimGapAround (position, normal, rim_) > max_rim_gap_along_normal_)
    return Verdict::kBeyondRim;
  if (combination_constraint_ && breaksCombinationConstraint (position, origin, around))
    return Verdict::kOvershoot;
  if (combination_constraint_ && std::any_of (crease_chords_.begin (), crease_chords_.end (),
                   [&] (const CreaseChord &c) { return c.crossedBy (position, normal, crease_tolerance_); }))
    return Verdict::kOvershoot;
  return Verdict::kKept;
}

template <typename PointT> void
ElasticSampler<PointT>::count (Verdict verdict, ContractionStats &stats)
{
  switch (verdict)
  {
  case Verdict::kRepelled: ++stats.repelled; break;
  case Verdict::kTooClose: ++stats.too_close; break;
  case Verdict::kOvershoot: ++stats.rejected_by_constraint; break;
  case Verdict::kUnsupported: ++stats.unsupported; break;
  case Verdict::kOutsideBound: ++stats.outside_bound; break;
  case Verdict::kBeyondRim: ++stats.beyond_rim; break;
  case Verdict::kKept: break;
  }
}

template <typename PointT> std::vector<Eigen::Vector3f>
ElasticSampler<PointT>::contractingDirections (const FrontChain &chain) const
{
  // n x t at every vertex, one inward sign for the whole chain: a vote of
  // "away from the mean of the existing neighbours" (a sum of +-1 votes:
  // the same for any number of threads).
  const int m = static_cast<int> (chain.vertices.size ());
  std::vector<Eigen::Vector3f> directions (m);
  int vote = 0;
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 16) reduction(+ : vote)
  for (int i = 0; i < m; ++i)
  {
    const FrontVertex &v = chain.vertices[i];
    directions[i] = v.normal.cross (chainTangent (chain, i));
    if (directions[i].norm () > 1e-6f)
      directions[i].normalize ();
    else
      directions[i].setZero ();
    if (has_inward_centre_ && chain.closed)
    {
      const float side = directions[i].dot (inward_centre_ - v.position);
      vote += side > 0.f ? 1 : (side < 0.f ? -1 : 0);
      continue;
    }
    Neighbourhood around;
    propagation_.gatherNeighbourhood (v.position, around);
    if (around.size () == 0)
      continue;
    Eigen::Vector3f mean = Eigen::Vector3f::Zero ();
    for (const auto &p : around.positions)
      mean += p;
    mean /= static_cast<float> (around.size ());
    const float side = directions[i].dot (v.position - mean);
    vote += side > 0.f ? 1 : (side < 0.f ? -1 : 0);
  }
  if (vote < 0)
    for (auto &d : directions)
      d = -d;
  return directions;
}

template <typename PointT> std::vector<typename ElasticSampler<PointT>::ControlPoint>
ElasticSampler<PointT>::controlPoints (const FrontChain &chain, const std::vector<Eigen::Vector3f> &directions,
                                       int base, const PassState &pass, ContractionStats &stats) const
{
  // A candidate at d_eq along each direction (eq. 5-6), optimised (eq. 7-8)
  // and checked; one discarded by the elastic force of another former
  // boundary point is repelled. Each on its own, so side by side; kept in
  // chain order.
  const float d_eq = equilibrium_distance_;
  const int m = static_cast<int> (chain.vertices.size ());
  // Only on a smooth rim can a gap be bridged (controlCurve), so only there
  // is it worth asking what stopped each discarded candidate; elsewhere
  // every gap counts as a meeting, the paper's rule.
  const bool smooth = smoothRim (chain);
  std::vector<float> arc (smooth ? m : 0, 0.f);
  for (int i = 1; i < static_cast<int> (arc.size ()); ++i)
    arc[i] = arc[i - 1] + (chain.vertices[i].position - chain.vertices[i - 1].position).norm ();
  std::vector<FrontVertex> candidates (m);
  std::vector<Verdict> verdicts (m, Verdict::kUnsupported);
  std::vector<char> met (m, smooth ? 0 : 1);
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 8)
  for (int i = 0; i < m; ++i)
  {
    if (directions[i].isZero ())
    {
      met[i] = 1;  // unsupported: stopped at the shape
      continue;
    }
    FrontVertex &c = candidates[i];
    c = {chain.vertices[i].position + d_eq * directions[i], chain.vertices[i].normal};
    verdicts[i] = place (c.position, chain.vertices[i].position, chain.vertices[i].normal, c.normal);
    std::vector<PointGrid::Neighbour> close;
    if (verdicts[i] == Verdict::kKept)
    {
      pass.former_grid.withinRadius (c.position, kRepulsionReach * d_eq, close);
      if (std::any_of (close.begin (), close.end (), [&] (const auto &q) { return q.id != base + i; }))
        verdicts[i] = Verdict::kRepelled;
    }
    if (smooth)
      met[i] = metOtherBoundary (c, verdicts[i], close, chain, arc, i, base, pass) ? 1 : 0;
  }
  std::vector<ControlPoint> controls;
  bool met_since_kept = false;
  for (int i = 0; i < m; ++i)
  {
    count (verdicts[i], stats);
    met_since_kept = met_since_kept || met[i];
    if (verdicts[i] != Verdict::kKept)
      continue;
    controls.push_back ({candidates[i], met_since_kept});
    met_since_kept = false;
  }
  // Across the start of a closed chain: what was discarded after the last kept.
  if (!controls.empty () && chain.closed)
    controls.front ().met_before = controls.front ().met_before || met_since_kept;
  return controls;
}

template <typename PointT> bool
ElasticSampler<PointT>::smoothRim (const FrontChain &chain)
{
  if (chain.sampled)
    return false;
  const std::size_t m = chain.vertices.size ();
  for (std::size_t k = 0; k + 1 < m + (chain.closed ? 1 : 0); ++k)
    if (chain.vertices[k].normal.dot (chain.vertices[(k + 1) % m].normal) < kSmoothRimCosine)
      return false;
  return true;
}

template <typename PointT> bool
ElasticSampler<PointT>::metOtherBoundary (const FrontVertex &candidate, Verdict verdict,
                                          std::vector<PointGrid::Neighbour> &close, const FrontChain &chain,
                                          const std::vector<float> &arc, int i, int base, const PassState &pass) const
{
  // Kept: nothing met; repelled or too close: by the chain's own neighbours,
  // or by another piece of boundary; any other verdict stopped the front at
  // the shape.
  if (verdict == Verdict::kKept)
    return false;
  if (verdict != Verdict::kRepelled && verdict != Verdict::kTooClose)
    return true;
  if (verdict == Verdict::kTooClose)
  {
    const float reach = kDuplicateReach * equilibrium_distance_;
    pass.former_grid.withinRadius (candidate.position, reach, close);
    // On top of a point that is not a boundary vertex: the surface beyond
    // the rim (the other face at an edge), not the rim's own raggedness.
    if (surfacePointsWithin (candidate.position, candidate.normal, reach) > close.size ())
      return true;
  }
  const int m = static_cast<int> (chain.vertices.size ());
  const float own = kOwnChainArc * equilibrium_distance_;
  const float loop_length =
      chain.closed ? arc.back () + (chain.vertices.front ().position - chain.vertices.back ().position).norm () : 0.f;
  return std::any_of (close.begin (), close.end (), [&] (const PointGrid::Neighbour &q) {
    const int j = q.id - base;
    if (j < 0 || j >= m)
      return true;  // a vertex of another chain
    float along = std::abs (arc[j] - arc[i]);
    if (chain.closed)
      along = std::min (along, loop_length - along);
    return along > own;
  });
}

template <typename PointT> std::vector<std::vector<FrontVertex>>
ElasticSampler<PointT>::controlCurve (const std::vector<ControlPoint> &controls, bool closed_chain, bool &wraps) const
{
  // The kept control points in order, cut where consecutive ones are far
  // apart and the front met another piece of boundary between them (the
  // paper's Fig. 11), or are too far apart to bridge.
  const float d_eq = equilibrium_distance_;
  const auto cut = [&] (const ControlPoint &before, const ControlPoint &after) {
    const float gap = (after.vertex.position - before.vertex.position).norm ();
    return gap > kChainBreak * d_eq && (after.met_before || gap > kMaxBridge * d_eq ||
                                        after.vertex.normal.dot (before.vertex.normal) < kBridgeCosine);
  };
  std::vector<std::vector<FrontVertex>> runs (1);
  for (std::size_t k = 0; k < controls.size (); ++k)
  {
    if (k > 0 && cut (controls[k - 1], controls[k]))
      runs.emplace_back ();
    runs.back ().push_back (controls[k].vertex);
  }
  wraps = closed_chain && controls.size () > 2 && !cut (controls.back (), controls.front ());
  if (wraps && runs.size () > 1)
  {
    // The last run continues into the first across the loop's start.
    runs.back ().insert (runs.back ().end (), runs.front ().begin (), runs.front ().end ());
    runs.erase (runs.begin ());
    wraps = false;
  }
  return runs;
}

template <typename PointT> std::vector<FrontVertex>
ElasticSampler<PointT>::stationsAlong (const std::vector<FrontVertex> &run, bool closed_run,
                                       std::vector<Eigen::Vector3f> &fallback_normals) const
{
  // A station every d_eq of arc length: half a step short of the start of a
  // closed run, and the end of an open one.
  const float d_eq = equilibrium_distance_;
  std::vector<float> arc (run.size () + 1, 0.f);
  const std::size_t segments = closed_run ? run.size () : run.size () - 1;
  for (std::size_t k = 0; k < segments; ++k)
    arc[k + 1] = arc[k] + (run[(k + 1) % run.size ()].position - run[k].position).norm ();
  const float length = arc[segments];
  std::vector<float> stations;
  const float last = closed_run ? length - 0.5f * d_eq : length;
  for (float s = 0.f; s <= last + 1e-6f && stations.size () <= run.size () * 4 + 4; s += d_eq)
    stations.push_back (s);
  if (!closed_run && length - stations.back () > 0.5f * d_eq)
    stations.push_back (length);

  std::vector<FrontVertex> samples (stations.size ());
  fallback_normals.assign (stations.size (), Eigen::Vector3f::Zero ());
  std::size_t segment = 0;
  for (std::size_t k = 0; k < stations.size (); ++k)
  {
    while (segment + 1 < segments && arc[segment + 1] < stations[k])
      ++segment;
    const FrontVertex &a = run[segment % run.size ()];
    const FrontVertex &b = run[(segment + 1) % run.size ()];
    const float span = arc[segment + 1] - arc[segment];
    const float t = segments == 0 || span <= 0.f ? 0.f : std::clamp ((stations[k] - arc[segment]) / span, 0.f, 1.f);
    samples[k] = {(1.f - t) * a.position + t * b.position, Eigen::Vector3f::Zero ()};
    fallback_normals[k] = a.normal;
  }
  return samples;
}

template <typename PointT> void
ElasticSampler<PointT>::sampleAlongCurve (const std::vector<FrontVertex> &run, bool closed_run, PassState &pass,
                                          Front &next) const
{
  // Section 4.2: each station's sample optimised on its own (side by side),
  // reference normal from the nearest former boundary point ...
  const float d_eq = equilibrium_distance_;
  std::vector<Eigen::Vector3f> fallback;
  std::vector<FrontVertex> samples = stationsAlong (run, closed_run, fallback);
  std::vector<Verdict> placed (samples.size ());
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 8)
  for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t> (samples.size ()); ++k)
  {
    std::vector<PointGrid::Neighbour> nearest;
    pass.former_grid.nearestK (samples[k].position, 1, nearest);
    const Eigen::Vector3f reference = nearest.empty () ? fallback[k] : pass.former_vertices[nearest[0].id]->normal;
    const Eigen::Vector3f on_curve = samples[k].position;  // a copy: place moves the sample
    placed[k] = place (samples[k].position, on_curve, reference, samples[k].normal);
  }
  // ... then kept in order along C, never twice on one spot, the new
  // boundary cut where a discarded sample leaves a gap.
  FrontChain out;
  out.sampled = true;
  bool broken = false;
  std::vector<PointGrid::Neighbour> near;
  for (std::size_t k = 0; k < samples.size (); ++k)
  {
    const FrontVertex &sample = samples[k];
    if (placed[k] != Verdict::kKept)
      continue;
    pass.sample_grid.withinRadius (sample.position, kDuplicateReach * d_eq, near);
    if (!near.empty ())
      continue;
    if (!out.vertices.empty () && (sample.position - out.vertices.back ().position).norm () > kChainBreak * d_eq)
    {
      next.push_back (out);
      out.vertices.clear ();
      broken = true;
    }
    pass.sample_grid.insert (sample.position, static_cast<int> (pass.samples++));
    out.vertices.push_back (sample);
  }
  out.closed = closed_run && !broken && out.vertices.size () > 2 &&
               (out.vertices.front ().position - out.vertices.back ().position).norm () <= kChainBreak * d_eq;
  if (!out.vertices.empty ())
    next.push_back (out);
}

template <typename PointT> bool
ElasticSampler<PointT>::contract (const Front &former, Front &next, ContractionStats &stats)
{
  next.clear ();
  stats = ContractionStats ();
  if (!propagation_.checkParameters ("ElasticSampler::contract"))
    return false;
  auto non_negative = [] (float v) { return v >= 0.f && std::isfinite (v); };
  if (!(equilibrium_distance_ > 0.f && std::isfinite (equilibrium_distance_)) || !non_negative (tolerance_) ||
      !non_negative (sign_tolerance_))
  {
    PCL_ERROR ("[pcl_holefill::ElasticSampler::contract] Invalid parameters: equilibrium distance = %g (> 0), "
               "constraint tolerance = %g (>= 0), curvature sign tolerance = %g (>= 0).\n", equilibrium_distance_,
               tolerance_, sign_tolerance_);
    return false;
  }
  curvature_signs_.resize (input_->size (), 2);

  // Every former boundary point: the sources of the elastic force and of
  // the reference normals; and the samples of this pass, so that two pieces
  // of C never sample the same spot.
  PassState pass (equilibrium_distance_);
  for (const auto &chain : former)
    for (const auto &v : chain.vertices)
    {
      pass.former_grid.insert (v.position, static_cast<int> (pass.former_vertices.size ()));
      pass.former_vertices.push_back (&v);
    }
  int base = 0;  // id in the former grid of the chain's first vertex
  for (const auto &chain : former)
  {
    const int m = static_cast<int> (chain.vertices.size ());
    stats.former_boundary_points += m;
    if (m < 2)
    {
      base += m;
      continue;
    }
    // 1-3. Control points along the contracting directions (sec. 4.1).
    const std::vector<ControlPoint> controls = controlPoints (chain, contractingDirections (chain), base, pass, stats);
    base += m;
    stats.kept_control_points += controls.size ();
    if (controls.empty ())
      continue;
    // 4. The control curve C; 5. the new boundary B sampled along it (sec. 4.2).
    bool wraps = false;
    for (const auto &run : controlCurve (controls, chain.closed, wraps))
      sampleAlongCurve (run, wraps, pass, next);
  }
  stats.samples = frontSize (next);
  has_inward_centre_ = false;
  return true;
}

}  // namespace pcl_holefill::detail

#define PCL_INSTANTIATE_ElasticSampler(T) template class pcl_holefill::detail::ElasticSampler<T>;
