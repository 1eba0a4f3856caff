/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/detail/boundary_point_test.h>
#include <pcl_holefill/detail/first_touch.h>
#include <pcl_holefill/hole_boundary_estimation.h>
#include <pcl_holefill/detail/loop_tracing.h>
#include <pcl_holefill/detail/normal_refit.h>
#include <pcl_holefill/detail/sampling_evenness.h>
#include <pcl_holefill/detail/stray_points.h>
#include <pcl_holefill/detail/point_validity.h>
#include <pcl_holefill/detail/thread_count.h>

#include <pcl/console/print.h>

#include <cmath>
#include <limits>

namespace pcl_holefill
{
namespace detail
{
// A rim point is a stray (detail::isStrayPoint) past this many pitches of
// its neighbours, more than the fill's 2: noise of 0.5 % of the diagonal
// (0.7-0.8 pitch) puts its tails past 2 pitches, and at 2 such rim points
// left their loops broken (fandisk, random samples, 0.5 %: 100 -> 72 %
// covered); at 2.5 no noisy corpus case changed, and the strays found the
// same.
constexpr float kRimStrayPitches = 2.5f;
// How much smaller than the hole (in pitches of radius) the disc tested at a
// rim point is: a sampled rim is ragged by about a pitch.
constexpr float kRimRaggedness = 0.5f;
// A rim point's normal more than 90 degrees from its neighbours' mean is
// taken for noise by the loop tracing: a 90 degree crease turns a normal at
// most 45 degrees from that mean (60 degrees, tried, also replaced normals
// at a noisy crease of fandisk and left a hole there open).
constexpr float kMaxTracingNormalCosine = 0.f;
// The empty-disc test looks again without unfolding where the median
// neighbour's normal turns more than 0.25 rad from the point's: PCA normals
// of noisy points (0.3-0.5 rad apart at 0.5 % noise); exact normals of a
// smooth surface stay below, and so do most next to a crease (the plain view
// can only add a rim point the unfolded one refused).
const float kMinPlainViewNormalCosine = std::cos (0.25f);
// The middle stage of the empty-disc test searches this many hole diameters
// around a point (the discs' centres lie at 0.5). On a million random
// samples the detection's stage 1b took 0.45 s with it against 0.75-0.99 s
// without; 0.5 and 0.75 measured 0.45-0.56 and 0.52.
constexpr float kMiddleReach = 0.6f;
// The loop tracing links rim points link_distance_factor pitches apart: the
// cloud's mean pitch, or where the cloud is sparser the pitch around the
// point (its own and its k nearest's, averaged) over kEvenPitchSpread, up
// to kMaxLinkInMeanPitches means. Merged scans are denser in one part than
// in another: with the mean alone, a part 4 times sparser than the rest
// (rim pitches 1.5-2 means) had the rim of a 9-pitch hole across a cube's
// edge linked in two open pieces, a border, and the hole was not filled
// (15 % covered). On evenly dense clouds the rim pitch stays within
// kEvenPitchSpread of the mean (uniformly random samples 0.86-1.24,
// Poisson-disk 0.95-1.05, on the rims of bench/independent_check.py's
// holes), and they link as before.
constexpr float kEvenPitchSpread = 1.25f;
constexpr float kMaxLinkInMeanPitches = 2.f;
}  // namespace detail

template <typename PointT> bool
HoleBoundaryEstimation<PointT>::prepare (const char *caller)
{
  positions_.clear ();
  normals_.clear ();
  rim_spacing_.clear ();
  stray_.clear ();
  stray_count_ = turned_normal_count_ = 0;
  mean_spacing_ = 0.f;
  flags_.assign (input_ ? input_->size () : 0, 0);
  if (!input_ || input_->empty ())
  {
    PCL_WARN ("[pcl_holefill::%s::%s] The input cloud is empty: no loop.\n", getClassName ().c_str (), caller);
    return false;
  }
  if (!checkParameters (caller) || !selectUsablePoints (caller))
    return false;
  const float cell = orderSpatially (caller);
  copyUsablePoints ();
  if (search_)
    search_->setInputCloud (input_, usable_);
  else
  {
    grid_.reset (cell);
    grid_.build (positions_, nullptr, detail::resolveThreadCount (threads_));
  }
  return true;
}

template <typename PointT> bool
HoleBoundaryEstimation<PointT>::checkParameters (const char *caller) const
{
  namespace P = parameters;
  const std::string refused = P::firstRefused ({
      {P::kKSearch, static_cast<float> (k_)},
      {P::kAngleThreshold, angle_threshold_},
      {P::kLinkDistanceFactor, link_factor_},
      {P::kMinLoopPoints, static_cast<float> (min_loop_points_)},
      {P::kMaxHoleDiameter, max_hole_diameter_},
      {P::kMinHoleSize, min_hole_pitches_},
      {P::kMinHoleDiameter, min_hole_diameter_},
  });
  if (!refused.empty ())
  {
    PCL_ERROR ("[pcl_holefill::%s::%s] Invalid parameter: %s.\n", getClassName ().c_str (), caller, refused.c_str ());
    return false;
  }
  return true;
}

template <typename PointT> bool
HoleBoundaryEstimation<PointT>::selectUsablePoints (const char *caller)
{
  if (!initCompute ())
    return false;
  if (!detail::indicesInRange (*indices_, input_->size ()))
  {
    PCL_ERROR ("[pcl_holefill::%s::%s] The indices set with setIndices() address points "
               "outside the cloud (%zu points): no loop.\n", getClassName ().c_str (), caller, input_->size ());
    deinitCompute ();
    return false;
  }
  usable_.reset (new pcl::Indices);
  const std::size_t skipped =
      detail::keepOrientedPoints (*input_, *indices_, *usable_, detail::resolveThreadCount (threads_));
  deinitCompute ();
  if (skipped > 0)
    PCL_WARN ("[pcl_holefill::%s::%s] Skipped %zu of %zu points with non-finite "
              "coordinates or a missing normal.\n", getClassName ().c_str (), caller, skipped, indices_->size ());
  if (usable_->size () < static_cast<std::size_t> (k_) + 1)
  {
    PCL_WARN ("[pcl_holefill::%s::%s] Only %zu usable points (need more than k = %d): "
              "no loop.\n", getClassName ().c_str (), caller, usable_->size (), k_);
    return false;
  }
  return true;
}

template <typename PointT> float
HoleBoundaryEstimation<PointT>::orderSpatially (const char *caller)
{
  // Work in spatial (Morton) order: the per-point pass then reads memory in
  // order. The unordered copy lives only in this function, so that it is
  // gone before the grid is built (the peak memory of a large cloud).
  const int threads = detail::resolveThreadCount (threads_);
  const std::vector<Eigen::Vector3f> unordered = detail::gatherPositions (*input_, usable_.get (), threads);
  const float cell = detail::PointGrid::suggestCellSize (unordered, k_);
  const std::vector<int> order = detail::PointGrid::spatialOrder (unordered, cell, threads);
  // Repeated positions would fill the k nearest with copies of one
  // neighbour: only the first of each is used (spatialOrder puts them together).
  pcl::IndicesPtr ordered (new pcl::Indices);
  detail::selectInOrder (
      static_cast<std::ptrdiff_t> (order.size ()), threads,
      [&] (std::ptrdiff_t i) { return i == 0 || unordered[order[i]] != unordered[order[i - 1]]; },
      [&] (std::ptrdiff_t i) { return (*usable_)[order[i]]; }, *ordered);
  const std::size_t duplicates = order.size () - ordered->size ();
  if (duplicates > 0)
    PCL_WARN ("[pcl_holefill::%s::%s] Ignored %zu points that repeat the position of "
              "another.\n", getClassName ().c_str (), caller, duplicates);
  usable_ = ordered;
  return cell;
}

template <typename PointT> void
HoleBoundaryEstimation<PointT>::copyUsablePoints ()
{
  local_of_.assign (input_->size (), -1);
  positions_.resize (usable_->size ());
  normals_.resize (usable_->size ());
  // Each usable index once: the writes never meet.
#pragma omp parallel for num_threads(detail::resolveThreadCount (threads_)) schedule(static)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (usable_->size ()); ++i)
  {
    const PointT &p = (*input_)[(*usable_)[i]];
    local_of_[(*usable_)[i]] = static_cast<int> (i);
    positions_[i] = p.getVector3fMap ();
    normals_[i] = p.getNormalVector3fMap ().normalized ();
  }
}

template <typename PointT> void
HoleBoundaryEstimation<PointT>::nearestUsable (std::size_t local, int k, std::vector<int> &ids,
                                               std::vector<float> &sqr_distances) const
{
  ids.clear ();
  sqr_distances.clear ();
  if (search_)
  {
    pcl::Indices found;
    std::vector<float> d2;
    search_->nearestKSearch ((*input_)[(*usable_)[local]], k + 1, found, d2);
    for (std::size_t j = 0; j < found.size (); ++j)
    {
      const int id = local_of_[found[j]];
      if (id >= 0 && id != static_cast<int> (local))
      {
        ids.push_back (id);
        sqr_distances.push_back (d2[j]);
      }
    }
    return;
  }
  thread_local std::vector<detail::PointGrid::Neighbour> found;
  grid_.nearestK (positions_[local], k + 1, found);
  for (const auto &n : found)
    if (n.id != static_cast<int> (local))
    {
      ids.push_back (n.id);
      sqr_distances.push_back (n.sqr_distance);
    }
}

template <typename PointT> int
HoleBoundaryEstimation<PointT>::nearestCloudIndex (const Eigen::Vector3f &position, int end_a, int end_b) const
{
  // The nearest of a few, on the ends' side: across a sheet a pitch thick
  // the nearest point to a midpoint can be on the other face, and a rim
  // through it grew filled points there.
  constexpr int kCandidates = 4;
  const Eigen::Vector3f side =
      ((*input_)[end_a].getNormalVector3fMap ().normalized () + (*input_)[end_b].getNormalVector3fMap ().normalized ())
          .normalized ();
  const auto on_side = [&] (const Eigen::Vector3f &p, const Eigen::Vector3f &n) {
    return !side.allFinite () || !detail::onOtherSideOfThinPart (p - position, side, n);
  };
  if (search_)
  {
    PointT query;
    query.getVector3fMap () = position;
    pcl::Indices found;
    std::vector<float> d2;
    search_->nearestKSearch (query, kCandidates, found, d2);
    for (const auto i : found)
      if (on_side ((*input_)[i].getVector3fMap (), (*input_)[i].getNormalVector3fMap ().normalized ()))
        return i;
    return -1;
  }
  std::vector<detail::PointGrid::Neighbour> found;
  grid_.nearestK (position, kCandidates, found);
  for (const auto &f : found)
    if (on_side (positions_[f.id], normals_[f.id]))
      return (*usable_)[f.id];
  return -1;
}

template <typename PointT> void
HoleBoundaryEstimation<PointT>::usableWithin (int local, float radius, std::vector<int> &ids) const
{
  ids.clear ();
  if (search_)
  {
    pcl::Indices found;
    std::vector<float> d2;
    search_->radiusSearch ((*input_)[(*usable_)[local]], radius, found, d2);
    for (const auto i : found)
      if (local_of_[i] >= 0 && local_of_[i] != local && !setAside (local_of_[i]))
        ids.push_back (local_of_[i]);
    return;
  }
  thread_local std::vector<detail::PointGrid::Neighbour> found;
  grid_.withinRadius (positions_[local], radius, found);
  for (const auto &n : found)
    if (n.id != local && !setAside (n.id))
      ids.push_back (n.id);
}

template <typename PointT> bool
HoleBoundaryEstimation<PointT>::normalsAgree (int local, const std::vector<int> &ids) const
{
  const auto agreeing = std::count_if (ids.begin (), ids.end (), [&] (int j) {
    return normals_[j].dot (normals_[local]) > detail::kMinPlainViewNormalCosine;
  });
  // More than half, not the median's "at least half" (16 neighbours: 9, not
  // 8): with "at least half" a noisy PCA-normal dihedral hole (random, 0.5 %)
  // lost 0.7 % coverage (95.3 -> 94.6 %) to rim points that the plain view
  // no longer saw.
  return 2 * static_cast<std::size_t> (agreeing) > ids.size ();
}

template <typename PointT> bool
HoleBoundaryEstimation<PointT>::emptyDiscTouches (int local, const detail::AngularGap &gap,
                                                  const std::vector<int> &nearest, float diameter,
                                                  float pitch, bool on_thin_part) const
{
  // A rim is ragged by about a pitch: the disc tested is that much smaller
  // than the hole it stands for.
  const float test_radius = 0.5f * diameter - detail::kRimRaggedness * pitch;
  const bool unfolding_trusted = normalsAgree (local, nearest);
  const auto touches = [&] (const std::vector<int> &ids) {
    return detail::emptyDiscTouches (positions_[local], normals_[local], gap, positions_.data (), normals_.data (),
                                     ids.data (), static_cast<int> (ids.size ()), diameter, test_radius, true,
                                     on_thin_part);
  };
  // A point of the k nearest inside every disc is inside it among all
  // neighbours too (more points only fill discs), so the wide search below
  // is skipped. On uniformly random samples a fifth of all points pass the
  // angular-gap test and two thirds of those fail here: the search of a
  // disc-sized ball for each (a 7x7x7 block of cells) was half the detection.
  // Not on a thin part, where the disc must also lie over the other face,
  // which the k nearest kept do not hold: more points can fill that need.
  const bool shortcuts = unfolding_trusted && !on_thin_part;
  if (shortcuts && !touches (nearest))
    return false;
  thread_local std::vector<int> ids;
  // The same again within a ball reaching just past the discs' centres
  // before the ball of the whole disc: a third as many cells, and it settles
  // most of the rest.
  if (shortcuts)
  {
    usableWithin (local, detail::kMiddleReach * diameter, ids);
    if (!touches (ids))
      return false;
  }
  usableWithin (local, diameter, ids);
  if (touches (ids))
    return true;
  // The unfolding trusts the neighbours' normals. Noisy ones (PCA normals of
  // noisy points tilt by 0.3-1.4 rad at a rim) scatter the unfolded points
  // into the disc, so look again without them: the plain projection onto the
  // plane fitted to the disc's neighbourhood. At 0.5 % noise with PCA normals
  // that found 24 of 26 rim points of a smooth hole where the unfolding found
  // 14, and left the rim of a hole at a corner to the unfolding.
  const int count = static_cast<int> (ids.size ());
  if (unfolding_trusted || count < 3)
    return false;
  thread_local std::vector<Eigen::Vector3f> around;
  around.clear ();
  for (const int j : ids)
    around.push_back (positions_[j]);
  Eigen::Vector3f plane = detail::fitPlane (around.data (), count).normal;
  if (!plane.allFinite ())
    return false;
  if (plane.dot (normals_[local]) < 0.f)
    plane = -plane;
  return detail::emptyDiscTouches (positions_[local], plane, gap, positions_.data (), normals_.data (), ids.data (),
                                   count, diameter, test_radius, false, on_thin_part);
}

template <typename PointT> Eigen::Vector3f
HoleBoundaryEstimation<PointT>::tracingNormal (int local, const std::vector<int> &ids) const
{
  // The walk links rim points whose normals agree (not across a thin part)
  // and steps along n x gap. A normal that turned far from all of its
  // neighbours' is noise, not a thin part: PCA normals of noisy points on a
  // ridge, oriented, came out 137 degrees from the next rim point's, and the
  // two halves of a hole across the ridge stayed apart. Such a point walks
  // with its neighbours' mean normal.
  Eigen::Vector3f mean = Eigen::Vector3f::Zero ();
  for (const int j : ids)
    mean += normals_[j];
  if (!(mean.norm () > 0.5f * static_cast<float> (ids.size ())))
    return normals_[local];  // the neighbours disagree among themselves too
  mean.normalize ();
  return mean.dot (normals_[local]) < detail::kMaxTracingNormalCosine ? mean : normals_[local];
}

template <typename PointT> float
HoleBoundaryEstimation<PointT>::spacingOf (int local) const
{
  const auto it = std::lower_bound (rim_spacing_.begin (), rim_spacing_.end (), std::make_pair (local, 0.f),
                                    [] (const auto &a, const auto &b) { return a.first < b.first; });
  return it != rim_spacing_.end () && it->first == local ? it->second : mean_spacing_;
}

template <typename PointT> void
HoleBoundaryEstimation<PointT>::measure (BoundaryLoop &loop) const
{
  std::vector<Eigen::Vector3f> points;
  float spacing = 0.f;
  for (const auto i : loop.indices)
  {
    points.push_back ((*input_)[i].getVector3fMap ());
    spacing += spacingOf (local_of_[i]);
  }
  loop.length = detail::loopLength (points, loop.closed);
  loop.diameter = detail::loopDiameter (points);
  loop.mean_spacing = loop.indices.empty () ? 0.f : spacing / static_cast<float> (loop.indices.size ());
}

template <typename PointT> bool
HoleBoundaryEstimation<PointT>::onThinPart (std::size_t local, const Eigen::Vector3f &normal, const int *ids, int count,
                                            bool *other_side) const
{
  // A flipped normal (PCA normals of noisy points) faces the other way too,
  // but lies above or below the tangent plane as the noise puts it; the
  // other face of a sheet lies below, all of it.
  int opposed = 0, behind = 0;
  for (int j = 0; j < count; ++j)
  {
    // The dot product first: most points face their neighbours' way, and
    // this runs for every point of the cloud.
    other_side[j] = false;
    if (!(normals_[ids[j]].dot (normal) < detail::kOppositeNormalCosine))
      continue;
    ++opposed;
    other_side[j] = detail::onOtherSideOfThinPart (positions_[ids[j]] - positions_[local], normal,
                                                   normals_[ids[j]]);
    behind += other_side[j] ? 1 : 0;
  }
  return behind >= detail::kMinOtherSideNeighbours && behind >= detail::kMinOtherSideShare * opposed;
}

template <typename PointT> typename HoleBoundaryEstimation<PointT>::RimCandidates
HoleBoundaryEstimation<PointT>::findRimPoints (std::vector<float> &pitch_of)
{
  const std::size_t n = positions_.size ();
  const int threads = detail::resolveThreadCount (threads_);
  // Each thread keeps the rim points it finds: on random samples a fifth of
  // all points are candidates, and one store under a lock made the threads
  // queue for it.
  std::vector<ThreadRimPoints> found (static_cast<std::size_t> (threads));
  std::vector<float> spacing_of, reach_of, evenness_of;
  detail::resizeTouched (spacing_of, n, threads, 0.f);
  detail::resizeTouched (reach_of, n, threads, 0.f);
  // One in kEvennessStride points is measured, each into its own slot.
  detail::resizeTouched (evenness_of, (n + detail::kEvennessStride - 1) / detail::kEvennessStride, threads, 0.f);
  pitch_of.clear ();
  detail::resizeTouched (pitch_of, n, threads, 0.f);
  auto test_point = [&] (std::size_t i, const int *all_ids, const float *all_d2, int all_count) {
    all_count = std::min (all_count, 64);
    float reach = 0.f;
    for (int j = 0; j < all_count; ++j)
      reach = std::max (reach, all_d2[j]);
    reach_of[i] = reach;
    // The point's own surface only, on a thin part: the face across it
    // would fill the gap of a hole in this one (and halve the pitch).
    int ids[64];
    float d2[64];
    int count = 0;
    bool on_thin_part = false;
    const auto own_side = [&] (const Eigen::Vector3f &normal) {
      bool other_side[64];
      on_thin_part = onThinPart (i, normal, all_ids, all_count, other_side);
      count = 0;
      for (int j = 0; j < all_count; ++j)
        if (!(on_thin_part && other_side[j]))
        {
          ids[count] = all_ids[j];
          d2[count++] = all_d2[j];
        }
      return count > 0
                 ? detail::angularGapOver (angle_threshold_, positions_[i], normal, positions_.data (),
                                           normals_.data (), ids, count)
                 : detail::AngularGap{};
    };
    detail::AngularGap gap = own_side (normals_[i]);
    const int thread = detail::threadNumber ();
    ThreadRimPoints &mine = found[static_cast<std::size_t> (thread)];
    if (gap.angle > angle_threshold_ && normalTurnedOver (i, all_ids, all_count))
    {
      mine.turned_over.push_back (static_cast<int> (i));
      gap = own_side (-normals_[i]);
    }
    if (count == 0)
      return;
    detail::NearestTwo nearest;
    float farthest = 0.f;
    for (int j = 0; j < count; ++j)
    {
      nearest.add (d2[j]);
      farthest = std::max (farthest, d2[j]);
    }
    const float spacing = std::isfinite (nearest.nearest) ? std::sqrt (nearest.nearest) : 0.f;
    spacing_of[i] = spacing;
    pitch_of[i] = detail::samplingPitch (farthest, count, gap.angle > angle_threshold_ ? gap.angle : 0.f);
    if (i % detail::kEvennessStride == 0 && pitch_of[i] > 0.f)
      evenness_of[i / detail::kEvennessStride] =
          detail::tangentialNearest (positions_[i], normals_[i], positions_.data (), ids, count) / pitch_of[i];
    if (!(gap.angle > angle_threshold_))
      return;
    // Stage 1b reads these neighbours again: kept nearest first, as a search
    // returns them (the order of its sums), rather than searched twice (on
    // random samples a fifth of all points get here; the second search was a
    // sixth of the detection).
    std::pair<float, int> nearest_first[64];
    for (int j = 0; j < count; ++j)
      nearest_first[j] = {d2[j], ids[j]};
    std::sort (nearest_first, nearest_first + count);
    RimPoint point{static_cast<int> (i), gap, spacing, std::sqrt (nearest.second)};
    point.on_thin_part = on_thin_part;
    point.nearest_store = thread;
    point.nearest_at = mine.nearest.size ();
    point.nearest_count = count;
    for (int j = 0; j < count; ++j)
      mine.nearest.push_back (nearest_first[j].second);
    mine.points.push_back (point);
  };
  if (!search_)
  {
    // The grid's own cell-by-cell kNN: the fast path.
    grid_.forEachNearestK (k_, threads, [&] (int i, const detail::PointGrid::Neighbour *found, int count) {
      int ids[64];
      float d2[64];
      for (int j = 0; j < count && j < 64; ++j)
      {
        ids[j] = found[j].id;
        d2[j] = found[j].sqr_distance;
      }
      test_point (static_cast<std::size_t> (i), ids, d2, std::min (count, 64));
    });
  }
  else
  {
#pragma omp parallel for num_threads(threads) schedule(dynamic, 2048)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (n); ++i)
    {
      thread_local std::vector<int> ids;
      thread_local std::vector<float> d2;
      nearestUsable (static_cast<std::size_t> (i), k_, ids, d2);
      test_point (static_cast<std::size_t> (i), ids.data (), d2.data (), static_cast<int> (ids.size ()));
    }
  }
  retestBesideStrays (spacing_of, pitch_of, reach_of, found, test_point);
  double sum = 0.0, pitch_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    sum += spacing_of[i];
    pitch_sum += pitch_of[i];
  }
  mean_spacing_ = static_cast<float> (sum / static_cast<double> (n));
  mean_pitch_ = static_cast<float> (pitch_sum / static_cast<double> (n));
  chooseMinHoleSize (evenness_of, pitch_of);
  turnNormalsOver (found);
  return mergeRimCandidates (found);
}

template <typename PointT> void
HoleBoundaryEstimation<PointT>::chooseMinHoleSize (const std::vector<float> &evenness_of, const std::vector<float> &pitch_of)
{
  // A hole must be wider than the gaps the sampling leaves by chance, and
  // how wide those get depends on the sampler: a 6-pitch hole in one face of
  // a fin (the other face's hole seen through it), clear on Poisson-disk or
  // voxel-grid samples, was left open because random samples need 6.
  std::vector<float> values = evenness_of;
  sampling_evenness_ = detail::lowerQuartileOfPositive (values);
  min_hole_size_used_ =
      min_hole_pitches_ > 0.f ? min_hole_pitches_ : detail::minHoleSizeForEvenness (sampling_evenness_);
  // Regions only raise the size (keepHoleSizedGaps): none where the user
  // set one or the cloud's is already the largest.
  region_evenness_ = detail::RegionEvenness ();
  const bool set = min_hole_pitches_ > 0.f || min_hole_diameter_ > 0.f;
  if (!set && min_hole_size_used_ < detail::kRandomSamplingMinHoleSize)
    region_evenness_.build (positions_, pitch_of, evenness_of, detail::kEvennessStride,
                            detail::resolveThreadCount (threads_));
  if (min_hole_diameter_ > 0.f)
    PCL_DEBUG ("[pcl_holefill::%s::compute] Sampling evenness %.2f: min hole diameter %g (set).\n",
               getClassName ().c_str (), sampling_evenness_, min_hole_diameter_);
  else
    PCL_DEBUG ("[pcl_holefill::%s::compute] Sampling evenness %.2f (random 0.3, even 0.6-0.85): min hole size %.2g "
               "pitches%s.\n",
               getClassName ().c_str (), sampling_evenness_, min_hole_size_used_,
               min_hole_pitches_ > 0.f ? " (set)" : "");
}

template <typename PointT> float
HoleBoundaryEstimation<PointT>::minHoleSizeAround (int local, float pitch) const
{
  // A cloud can be sampled evenly in one part and randomly in another
  // (merged scans, a part thinned): the random part's gaps need the random
  // sampling's size even where most of the cloud is even.
  const float evenness = region_evenness_.around (positions_[static_cast<std::size_t> (local)], pitch);
  return evenness > 0.f ? detail::minHoleSizeForEvenness (evenness) : min_hole_size_used_;
}

template <typename PointT> bool
HoleBoundaryEstimation<PointT>::normalTurnedOver (std::size_t local, const int *ids, int count) const
{
  // An estimated normal gets its sign from the orientation, which can fail
  // at a noisy corner: nearly all its neighbours then face away. The
  // empty-disc test drops neighbours that face away (the other side),
  // so the disc around such a point is empty: one on fandisk (random
  // samples, 0.5 % noise, PCA normals), 4 pitches from a corner hole and
  // 1.5 above the face, joined its rim, and the loop ended there, open.
  // (Its neighbours lay below its plane, so it passed for a thin part's
  // point too.) Three in four, not half: beside a crease the other face's
  // normals turn 90 degrees; on a thin part half the neighbours are of the
  // point's own face.
  int opposed = 0;
  for (int j = 0; j < count; ++j)
    opposed += normals_[ids[j]].dot (normals_[local]) < detail::kOtherSideCosine ? 1 : 0;
  return 4 * opposed > 3 * count;
}

template <typename PointT> void
HoleBoundaryEstimation<PointT>::turnNormalsOver (std::vector<ThreadRimPoints> &found)
{
  // After the pass (its threads read these normals as neighbours'); the
  // later stages read the turned ones. Each point once, whichever thread
  // found it.
  std::vector<int> turned;
  for (auto &f : found)
  {
    turned.insert (turned.end (), f.turned_over.begin (), f.turned_over.end ());
    std::vector<int> ().swap (f.turned_over);
  }
  std::sort (turned.begin (), turned.end ());
  turned.erase (std::unique (turned.begin (), turned.end ()), turned.end ());
  for (const int i : turned)
    normals_[static_cast<std::size_t> (i)] = -normals_[static_cast<std::size_t> (i)];
  turned_normal_count_ = turned.size ();
  if (!turned.empty ())
    PCL_WARN ("[pcl_holefill::%s::compute] %zu normals face away from nearly all their neighbours' (their "
              "orientation failed, as it can at noisy corners): detection turned them over; the fill and "
              "the output keep them as given.\n",
              getClassName ().c_str (), turned.size ());
}

template <typename PointT> template <typename TestPoint> void
HoleBoundaryEstimation<PointT>::retestBesideStrays (const std::vector<float> &spacing_of,
                                                    const std::vector<float> &pitch_of,
                                                    const std::vector<float> &reach_of,
                                                    std::vector<ThreadRimPoints> &found, const TestPoint &test_point)
{
  // A stray (a scanner's mixed pixel, 1-4 pitches off the surface) among a
  // rim point's k nearest projects into the hole's side and closes its gap:
  // one stray 4 pitches inside an L-shaped block, under a hole at its
  // corner, hid two of the hole's three faces' rims and the hole went
  // unfound. The points near a stray are tested again without it.
  stray_.clear ();
  const std::vector<std::pair<int, float>> strays = markStrays (spacing_of, pitch_of);
  if (strays.empty ())
    return;
  const std::vector<int> beside = pointsBesideStrays (strays, reach_of);
  std::vector<std::size_t> first_pass_end (found.size ()), first_turned_end (found.size ());
  for (std::size_t t = 0; t < found.size (); ++t)
  {
    first_pass_end[t] = found[t].points.size ();
    first_turned_end[t] = found[t].turned_over.size ();
  }
  const int threads = detail::resolveThreadCount (threads_);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 16)
  for (std::ptrdiff_t b = 0; b < static_cast<std::ptrdiff_t> (beside.size ()); ++b)
  {
    thread_local std::vector<int> ids;
    thread_local std::vector<float> d2;
    const std::size_t q = static_cast<std::size_t> (beside[b]);
    // k more than the test's, so that k remain once the strays are out.
    nearestUsable (q, 2 * k_, ids, d2);
    std::size_t kept = 0;
    for (std::size_t j = 0; j < ids.size () && kept < static_cast<std::size_t> (k_); ++j)
      if (!setAside (ids[j]))
      {
        ids[kept] = ids[j];
        d2[kept++] = d2[j];
      }
    test_point (q, ids.data (), d2.data (), static_cast<int> (kept));
  }
  // The first test's verdict on a retested point goes.
  const auto was_retested = [&] (int local) { return std::binary_search (beside.begin (), beside.end (), local); };
  for (std::size_t t = 0; t < found.size (); ++t)
  {
    auto &points = found[t].points;
    const auto first_pass = points.begin () + static_cast<std::ptrdiff_t> (first_pass_end[t]);
    const auto retested_point = [&] (const RimPoint &r) { return was_retested (r.local); };
    points.erase (std::remove_if (points.begin (), first_pass, retested_point), first_pass);
    auto &turned = found[t].turned_over;
    const auto turned_first_pass = turned.begin () + static_cast<std::ptrdiff_t> (first_turned_end[t]);
    turned.erase (std::remove_if (turned.begin (), turned_first_pass, was_retested), turned_first_pass);
  }
}

template <typename PointT> std::vector<std::pair<int, float>>
HoleBoundaryEstimation<PointT>::markStrays (const std::vector<float> &spacing_of, const std::vector<float> &pitch_of)
{
  // A stray h pitches off the surface has its nearest neighbour h pitches
  // away and its own pitch inflated to about sqrt((h^2 + 5) / 5) (16
  // neighbours): 1.6 at h = 2.5, so 1.25 keeps every stray that
  // isStrayPoint would find; uniformly random samples (the closest
  // neighbours of any sampler) have 0.7 % of their points past it.
  constexpr float kSuspectRatio = 1.25f;
  std::vector<int> suspects;
  for (std::size_t i = 0; i < positions_.size (); ++i)
    if (spacing_of[i] > kSuspectRatio * pitch_of[i])
      suspects.push_back (static_cast<int> (i));
  std::vector<float> reach (suspects.size (), -1.f);  // -1: not a stray
#pragma omp parallel for num_threads(detail::resolveThreadCount (threads_)) schedule(dynamic, 16)
  for (std::ptrdiff_t s = 0; s < static_cast<std::ptrdiff_t> (suspects.size ()); ++s)
  {
    thread_local std::vector<int> ids;
    thread_local std::vector<float> d2;
    nearestUsable (static_cast<std::size_t> (suspects[s]), k_, ids, d2);
    detail::NearestTwo nearest;
    float farthest = 0.f;
    for (const float d : d2)
    {
      nearest.add (d);
      farthest = std::max (farthest, d);
    }
    if (isStray (std::sqrt (nearest.nearest), std::sqrt (nearest.second), ids, pitch_of))
      reach[s] = std::sqrt (farthest);
  }
  std::vector<std::pair<int, float>> strays;
  for (std::size_t s = 0; s < suspects.size (); ++s)
    if (reach[s] >= 0.f)
      strays.emplace_back (suspects[s], reach[s]);
  stray_count_ = strays.size ();
  if (!strays.empty ())
  {
    stray_.assign (positions_.size (), 0);
    for (const auto &s : strays)
      stray_[s.first] = 1;
  }
  return strays;
}

template <typename PointT> std::vector<int>
HoleBoundaryEstimation<PointT>::pointsBesideStrays (const std::vector<std::pair<int, float>> &strays,
                                                    const std::vector<float> &reach_of) const
{
  // Next to a stray, a point's k nearest reach about as far as the stray's
  // own do (a point at a rim, half its disc empty: 1.4 times an inner
  // point's; a stray 2.5 pitches off: 1.5 times). Twice that to spare: the
  // search only gathers, reach_of decides.
  constexpr float kSearchMargin = 2.f;
  std::vector<int> beside, ids;
  for (const auto &s : strays)
  {
    usableWithin (s.first, kSearchMargin * s.second, ids);  // strays left out
    for (const int q : ids)
      if ((positions_[q] - positions_[s.first]).squaredNorm () <= reach_of[q])
        beside.push_back (q);
  }
  std::sort (beside.begin (), beside.end ());
  beside.erase (std::unique (beside.begin (), beside.end ()), beside.end ());
  return beside;
}

template <typename PointT> typename HoleBoundaryEstimation<PointT>::RimCandidates
HoleBoundaryEstimation<PointT>::mergeRimCandidates (std::vector<ThreadRimPoints> &found)
{
  // The points in usable order, whichever thread found them: the same for
  // any thread count. Their neighbours stay in the finders' stores (13 MB
  // of ids on a million random samples: a copy was a serial step).
  RimCandidates rim;
  std::size_t count = 0;
  for (const auto &f : found)
    count += f.points.size ();
  rim.points.reserve (count);
  for (auto &f : found)
  {
    rim.points.insert (rim.points.end (), f.points.begin (), f.points.end ());
    std::vector<RimPoint> ().swap (f.points);
    rim.nearest.push_back (std::move (f.nearest));  // RimPoint::nearest_store: the finder's number
  }
  std::sort (rim.points.begin (), rim.points.end (), [] (const auto &a, const auto &b) { return a.local < b.local; });
  return rim;
}

template <typename PointT> bool
HoleBoundaryEstimation<PointT>::isStray (float nearest, float second, const std::vector<int> &ids,
                                         const std::vector<float> &pitch_of)
{
  // A scanner's stray next to a hole sees the hole's side empty too, and a
  // loop through it put a point 4 pitches off the surface on the rim, from
  // which the fill grew at that height (corpus with 0.5 % strays, a cube's
  // corner on scan lines: max error 0.065).
  float around[64];
  int count = 0;
  for (const int j : ids)
    if (count < 64)
      around[count++] = pitch_of[j];
  return detail::isStrayPoint (nearest, second, around, count, detail::kRimStrayPitches);
}

template <typename PointT> void
HoleBoundaryEstimation<PointT>::keepHoleSizedGaps (RimCandidates &rim, const std::vector<float> &pitch_of) const
{
  std::vector<RimPoint> &rim_points = rim.points;
  std::vector<char> keep (rim_points.size (), 0);
#pragma omp parallel for num_threads(detail::resolveThreadCount (threads_)) schedule(dynamic, 64)
  for (std::ptrdiff_t r = 0; r < static_cast<std::ptrdiff_t> (rim_points.size ()); ++r)
  {
    thread_local std::vector<int> ids;
    const int local = rim_points[r].local;
    const auto first = rim.nearest[static_cast<std::size_t> (rim_points[r].nearest_store)].begin () +
                       static_cast<std::ptrdiff_t> (rim_points[r].nearest_at);
    ids.assign (first, first + rim_points[r].nearest_count);
    if (isStray (rim_points[r].spacing, rim_points[r].second_spacing, ids, pitch_of))
      continue;
    float pitch = pitch_of[local];
    for (const int j : ids)
      pitch += pitch_of[j];
    pitch /= static_cast<float> (ids.size () + 1);
    rim_points[r].pitch = pitch;
    const auto disc_touches = [&] (float size) {
      const float diameter = min_hole_diameter_ > 0.f ? min_hole_diameter_ : size * pitch;
      return emptyDiscTouches (local, rim_points[r].gap, ids, diameter, pitch, rim_points[r].on_thin_part);
    };
    // The region's evenness is looked up only where the cloud's size finds
    // a gap (a few of the candidates), and only raises the size: a part
    // sampled randomly needs more than the even rest. (Lowering it in an
    // even part of a random cloud would test a second disc at every
    // candidate: two thirds of them on random samples.) With a size set,
    // region_evenness_ is empty and the cloud's size stands.
    float size = min_hole_size_used_;
    bool touches = disc_touches (size);
    const float around = touches ? minHoleSizeAround (local, pitch) : size;
    if (around > size)
    {
      size = around;
      touches = disc_touches (size);
    }
    rim_points[r].min_hole_size = size;
    keep[r] = touches ? 1 : 0;
    if (keep[r])
      rim_points[r].walk_normal = tracingNormal (local, ids);
  }
  std::size_t kept = 0;
  for (std::size_t r = 0; r < rim_points.size (); ++r)
    if (keep[r])
      rim_points[kept++] = rim_points[r];
  rim_points.resize (kept);
  std::vector<std::vector<int>> ().swap (rim.nearest);  // read by nothing after this stage
}

template <typename PointT> BoundaryLoop
HoleBoundaryEstimation<PointT>::finishLoop (const detail::TracedLoop &traced, const std::vector<RimPoint> &rim,
                                            const std::vector<float> &pitch_of) const
{
  BoundaryLoop loop;
  loop.closed = traced.closed;
  pcl::Indices coarse;
  std::vector<Eigen::Vector3f> loop_positions, loop_gaps;
  float pitch = 0.f, min_size = 0.f;
  for (const int m : traced.members)
  {
    coarse.push_back ((*usable_)[rim[m].local]);
    loop_positions.push_back (positions_[rim[m].local]);
    loop_gaps.push_back (rim[m].gap.direction);
    pitch += pitch_of[rim[m].local];
    min_size += rim[m].min_hole_size;
  }
  loop.indices = detail::refineByMidpoints (
      coarse, traced.closed, [this] (int i) { return Eigen::Vector3f ((*input_)[i].getVector3fMap ()); },
      [this] (const Eigen::Vector3f &p, int a, int b) { return nearestCloudIndex (p, a, b); },
      4 * coarse.size () + 64);
  measure (loop);
  loop.pitch = pitch / static_cast<float> (traced.members.size ());
  min_size /= static_cast<float> (traced.members.size ());
  const float min_diameter = min_hole_diameter_ > 0.f ? min_hole_diameter_ : min_size * loop.pitch;
  loop.is_hole = loop.closed && detail::gapsPointInside (loop_positions, loop_gaps) && loop.diameter >= min_diameter &&
                 (max_hole_diameter_ <= 0.f || loop.diameter <= max_hole_diameter_);
  return loop;
}

template <typename PointT> void
HoleBoundaryEstimation<PointT>::compute (std::vector<BoundaryLoop> &loops)
{
  loops.clear ();
  if (!prepare ("compute"))
    return;
  // 1. The angular-gap test; 1b. only gaps as large as a hole.
  std::vector<float> pitch_of;
  RimCandidates candidates = findRimPoints (pitch_of);
  keepHoleSizedGaps (candidates, pitch_of);
  const std::vector<RimPoint> &rim = candidates.points;
  rim_spacing_.clear ();
  std::vector<Eigen::Vector3f> rim_positions, rim_normals, rim_gaps;
  std::vector<float> rim_links;
  for (const auto &r : rim)
  {
    const float pitch = std::isfinite (r.pitch) ? r.pitch : mean_pitch_;
    rim_links.push_back (link_factor_ * std::clamp (pitch / detail::kEvenPitchSpread, mean_pitch_,
                                                    detail::kMaxLinkInMeanPitches * mean_pitch_));
    rim_spacing_.push_back ({r.local, r.spacing});
    flags_[(*usable_)[r.local]] = 1;
    rim_positions.push_back (positions_[r.local]);
    rim_normals.push_back (r.walk_normal);
    rim_gaps.push_back (r.gap.direction);
  }
  // 2. Chain the rim points into loops; 3. refine, measure and classify each.
  for (const auto &traced :
       detail::traceBoundaryLoops (rim_positions, rim_normals, rim_gaps, rim_links, min_loop_points_))
    loops.push_back (finishLoop (traced, rim, pitch_of));
}

template <typename PointT> bool
HoleBoundaryEstimation<PointT>::refineFeaturePoints (const pcl::Indices &feature_indices, BoundaryLoop &loop,
                                                     bool closed)
{
  loop = BoundaryLoop ();
  if (!prepare ("refineFeaturePoints"))
    return false;
  if (feature_indices.size () < 2)
  {
    PCL_ERROR ("[pcl_holefill::%s::refineFeaturePoints] Need at least 2 feature "
               "points, got %zu.\n", getClassName ().c_str (), feature_indices.size ());
    return false;
  }
  for (const auto i : feature_indices)
    if (i < 0 || static_cast<std::size_t> (i) >= input_->size () || local_of_[i] < 0)
    {
      PCL_ERROR ("[pcl_holefill::%s::refineFeaturePoints] Feature point %d is out of "
                 "range or not an oriented point.\n", getClassName ().c_str (), static_cast<int> (i));
      return false;
    }
  double sum = 0.0;
  std::vector<int> ids;
  std::vector<float> d2;
  for (const auto i : feature_indices)
  {
    nearestUsable (local_of_[i], 1, ids, d2);
    const float spacing = d2.empty () ? 0.f : std::sqrt (d2[0]);
    rim_spacing_.push_back ({local_of_[i], spacing});
    sum += spacing;
  }
  std::sort (rim_spacing_.begin (), rim_spacing_.end ());
  mean_spacing_ = static_cast<float> (sum / feature_indices.size ());
  loop.closed = closed;
  loop.is_hole = true;
  loop.indices = detail::refineByMidpoints (
      feature_indices, closed, [this] (int i) { return Eigen::Vector3f ((*input_)[i].getVector3fMap ()); },
      [this] (const Eigen::Vector3f &p, int a, int b) { return nearestCloudIndex (p, a, b); }, input_->size ());
  measure (loop);
  return true;
}

}  // namespace pcl_holefill

#define PCL_INSTANTIATE_HoleBoundaryEstimation(T) template class pcl_holefill::HoleBoundaryEstimation<T>;

