/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/bilateral_preprocessor.h>
#include <pcl_holefill/elastic_sampler.h>
#include <pcl_holefill/hole_boundary_estimation.h>
#include <pcl_holefill/hole_filling.h>
#include <pcl_holefill/impl/bilateral_preprocessor.hpp>
#include <pcl_holefill/impl/elastic_sampler.hpp>
#include <pcl_holefill/impl/hole_boundary_estimation.hpp>
#include <pcl_holefill/impl/voxel_hash_search.hpp>
#include <pcl_holefill/loop_tracing.h>
#include <pcl_holefill/impl/normal_orientation.hpp>
#include <pcl_holefill/normal_orientation.h>
#include <pcl_holefill/point_validity.h>
#include <pcl_holefill/thread_count.h>
#include <pcl_holefill/voxel_hash_search.h>

#include <pcl/common/centroid.h>
#include <pcl/common/eigen.h>
#include <pcl/common/io.h>
#include <pcl/console/print.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace pcl_holefill
{
namespace detail
{
// A patch larger than this many discs spanning its rim suggests that more
// than half of the shape is missing there (the paper's admitted failure).
constexpr float kMaxAreaOverRimDisc = 2.5f;
// The fill of a hole stays inside the ball around its rim's centroid of
// radius kBoundScale x (rim radius) + 2 d_eq: a runaway front is cut there.
constexpr float kBoundScale = 1.5f;
// A last boundary narrower than this (in d_eq) has closed onto a point.
constexpr float kClosedFrontDiameter = 4.f;
// More neighbouring normals than this pointing opposite ways: not oriented.
constexpr float kMaxFlippedShare = 0.02f;
// Tolerance of the combination constraint, in mean spacings, on clean data...
constexpr float kToleranceInSpacings = 0.1f;
// ... and in standard deviations of the rim's noise on noisy data: a noisy
// neighbour lies that far off its own tangent plane, and would otherwise
// make every candidate near it look like an overshoot (the fill then stops).
constexpr float kToleranceInNoiseSigmas = 2.5f;
// Above this rim noise (in mean spacings) the first-order extension is off.
constexpr float kFirstOrderMaxNoiseInSpacings = 0.1f;
// The noise is measured in a ball of this many mean spacings around each rim point.
constexpr float kNoiseReachInSpacings = 2.5f;

/** The noise of the surface around a rim: the median, over rim points, of
  * the RMS distance of their neighbours to the best-fitting plane. */
template <typename PointT> float
rimNoise (const pcl::PointCloud<PointT> &cloud, pcl::search::Search<PointT> &search, const pcl::Indices &rim,
          float reach)
{
  std::vector<float> rms;
  pcl::Indices found;
  std::vector<float> sqr_distances;
  for (const auto i : rim)
  {
    if (search.radiusSearch (cloud[i], reach, found, sqr_distances) < 5)
      continue;
    EIGEN_ALIGN16 Eigen::Matrix3f covariance;
    Eigen::Vector4f centroid;
    if (pcl::computeMeanAndCovarianceMatrix (cloud, found, covariance, centroid) == 0)
      continue;
    EIGEN_ALIGN16 Eigen::Vector3f values;
    pcl::eigen33 (covariance, values);
    rms.push_back (std::sqrt (std::max (0.f, values[0])));
  }
  if (rms.empty ())
    return 0.f;
  std::nth_element (rms.begin (), rms.begin () + rms.size () / 2, rms.end ());
  return rms[rms.size () / 2];
}
}  // namespace detail

template <typename PointT> bool
HoleFilling<PointT>::checkParameters () const
{
  auto non_negative = [] (float v) { return v >= 0.f && std::isfinite (v); };
  const char *bad = nullptr;
  if (!non_negative (radius_))
    bad = "radius (>= 0, 0 = automatic)";
  else if (!(shrink_ >= 1.f && std::isfinite (shrink_)))
    bad = "radius shrink factor (>= 1)";
  else if (!non_negative (sigma_d_))
    bad = "sigma_d (>= 0, 0 = automatic)";
  else if (!(sigma_n_ > 0.f))  // kSup (infinity) is allowed, NaN is not
    bad = "sigma_n (> 0, or kSup)";
  else if (!non_negative (sigma_r_))
    bad = "sigma_r (>= 0, 0 = automatic)";
  else if (!(spacing_factor_ >= 0.25f && spacing_factor_ <= 10.f))
    bad = "spacing factor (0.25..10)";
  else if (!(termination_ratio_ >= 0.f && termination_ratio_ < 1.f))
    bad = "termination ratio (0..1)";
  else if (max_passes_ < 1 || max_passes_ > 100000)
    bad = "max passes (1..100000)";
  else if (!(max_growth_ >= 1.f && std::isfinite (max_growth_)))
    bad = "max boundary growth (>= 1)";
  else if (!non_negative (max_hole_diameter_))
    bad = "max hole diameter (>= 0, 0 = no limit)";
  else if (!(min_hole_pitches_ >= 2.f && min_hole_pitches_ <= 100.f))
    bad = "min hole size (2..100 pitches)";
  if (bad)
  {
    PCL_ERROR ("[pcl_holefill::HoleFilling] Invalid parameter: %s. Nothing filtered.\n", bad);
    return false;
  }
  return true;
}

template <typename PointT> bool
HoleFilling<PointT>::collectHoles (const PointCloudConstPtr &working, const SearchPtr &search,
                                   std::vector<BoundaryLoop> &holes) const
{
  holes.clear ();
  if (user_holes_.empty ())
  {
    HoleBoundaryEstimation<PointT> estimation;
    estimation.setInputCloud (working);
    if (search_)  // the user's; without one, detection's own cell-by-cell pass is faster
      estimation.setSearchMethod (search);
    estimation.setMaxHoleDiameter (max_hole_diameter_);
    estimation.setMinHoleSize (min_hole_pitches_);
    estimation.setNumberOfThreads (threads_);
    std::vector<BoundaryLoop> loops;
    estimation.compute (loops);
    for (auto &loop : loops)
      if (loop.is_hole)
        holes.push_back (std::move (loop));
    return true;
  }
  // User loops index the input cloud; the working cloud holds the indexed points.
  std::vector<int> working_of (input_->size (), -1);
  for (std::size_t i = 0; i < indices_->size (); ++i)
    working_of[(*indices_)[i]] = static_cast<int> (i);
  for (const auto &loop : user_holes_)
  {
    BoundaryLoop mapped = loop;
    for (auto &i : mapped.indices)
    {
      if (i < 0 || static_cast<std::size_t> (i) >= working_of.size () || working_of[i] < 0)
      {
        PCL_ERROR ("[pcl_holefill::HoleFilling] A given hole uses index %d, which is not among the input "
                   "points (or the indices set). Nothing filtered.\n", static_cast<int> (i));
        return false;
      }
      i = working_of[i];
    }
    holes.push_back (std::move (mapped));
  }
  return true;
}

template <typename PointT> void
HoleFilling<PointT>::applyFilter (PointCloud &output)
{
  reports_.clear ();
  if (!checkParameters ())
  {
    output.clear ();
    return;
  }
  if (!indicesInRange (*indices_, input_->size ()))
  {
    PCL_ERROR ("[pcl_holefill::HoleFilling] The indices set with setIndices() address points outside the "
               "cloud (%zu points). Nothing filtered.\n", input_->size ());
    output.clear ();
    return;
  }
  if (indices_->empty ())
  {
    PCL_WARN ("[pcl_holefill::HoleFilling] The input is empty: nothing to fill.\n");
    output.clear ();
    return;
  }
  // The points to work on: the input itself when the filter sees all of it
  // unchanged (no copy of a large cloud), else a copy of the indexed points.
  PointCloudConstPtr working = input_;
  const bool whole_input = indices_->size () == input_->size () &&
                           std::all_of (indices_->begin (), indices_->end (),
                                        [k = 0] (pcl::index_t i) mutable { return i == k++; });
  if (!whole_input)
  {
    PointCloudPtr subset (new PointCloud);
    pcl::copyPointCloud (*input_, *indices_, *subset);
    working = subset;
  }
  if (denoise_)
  {
    BilateralPreprocessor<PointT> preprocessor;
    preprocessor.setInputCloud (working);
    preprocessor.setNumberOfThreads (threads_);
    PointCloudPtr denoised (new PointCloud);
    preprocessor.filter (*denoised);
    if (denoised->size () == working->size ())
      working = denoised;
  }

  // Flipped normals would read as sharp edges everywhere: work on an oriented
  // copy (the output keeps the given normals).
  const PointCloudConstPtr given = working;
  const float flipped = flippedNeighbourShare (*working);
  if (flipped > detail::kMaxFlippedShare)
  {
    PCL_WARN ("[pcl_holefill::HoleFilling] %.0f%% of neighbouring normals point opposite ways: the normals are "
              "not consistently oriented. Filling with a consistently oriented copy.\n", 100.f * flipped);
    PointCloudPtr oriented (new PointCloud (*working));
    orientNormalsConsistently (*oriented);
    working = oriented;
  }

  // Detection first, then the search that gathers each hole's surroundings:
  // the two never take memory at the same time.
  SearchPtr search = search_;
  if (!search)
    search.reset (new VoxelHashSearch<PointT> (16));
  std::vector<BoundaryLoop> holes;
  if (!collectHoles (working, search, holes))
  {
    output.clear ();
    return;
  }
  if (holes.empty ())
  {
    PCL_DEBUG ("[pcl_holefill::HoleFilling] No hole to fill: the output is the input.\n");
    writeOutput (*given, {}, output);
    return;
  }
  search->setInputCloud (working);

  std::vector<PointCloud> fills (holes.size ());
  reports_.assign (holes.size (), HoleReport ());
#pragma omp parallel for num_threads(resolveThreadCount (threads_)) schedule(dynamic, 1)
  for (std::ptrdiff_t h = 0; h < static_cast<std::ptrdiff_t> (holes.size ()); ++h)
  {
    fillHole (*working, *search, holes[h], fills[h], reports_[h]);
    reports_[h].points_added = fills[h].size ();
    if (progress_)
    {
#pragma omp critical(pcl_holefill_progress)
      progress_ (static_cast<std::size_t> (h), holes.size (), reports_[h]);
    }
  }

  std::size_t next = working->size ();
  for (std::size_t h = 0; h < holes.size (); ++h)
  {
    reports_[h].first_output_index = next;
    next += fills[h].size ();
  }
  writeOutput (*given, fills, output);
}

template <typename PointT> void
HoleFilling<PointT>::writeOutput (const PointCloud &points, const std::vector<PointCloud> &fills,
                                  PointCloud &output) const
{
  // Allocated once at its final size: copying first and appending after
  // would hold two copies of a large cloud at once.
  std::size_t total = points.size ();
  for (const auto &f : fills)
    total += f.size ();
  const auto header = output.header;
  output.clear ();
  output.reserve (total);
  output.insert (output.end (), points.begin (), points.end ());  // every point, bit for bit
  for (const auto &f : fills)
    output.insert (output.end (), f.begin (), f.end ());
  output.header = header;
  output.width = static_cast<std::uint32_t> (output.size ());
  output.height = 1;
  output.is_dense = points.is_dense;
  output.sensor_origin_ = points.sensor_origin_;
  output.sensor_orientation_ = points.sensor_orientation_;
}

template <typename PointT> void
HoleFilling<PointT>::fillHole (const PointCloud &working, pcl::search::Search<PointT> &search,
                               const BoundaryLoop &loop, PointCloud &filled, HoleReport &report) const
{
  report.boundary_points = loop.indices.size ();
  report.diameter = loop.diameter;
  // The rim: usable points only.
  pcl::Indices rim;
  for (const auto i : loop.indices)
    if (i >= 0 && static_cast<std::size_t> (i) < working.size () && isOrientedPoint (working[i]))
      rim.push_back (i);
  if (rim.size () < 3)
  {
    PCL_WARN ("[pcl_holefill::HoleFilling] A hole has fewer than 3 usable boundary points: skipped.\n");
    return;
  }
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero ();
  for (const auto i : rim)
    centroid += working[i].getVector3fMap ();
  centroid /= static_cast<float> (rim.size ());
  float rim_radius = 0.f;
  double spacing_sum = 0.0;
  pcl::Indices found;
  std::vector<float> sqr_distances;
  for (const auto i : rim)
  {
    rim_radius = std::max (rim_radius, (working[i].getVector3fMap () - centroid).norm ());
    // The nearest distinct neighbour (duplicates say nothing about spacing).
    search.nearestKSearch (working[i], 8, found, sqr_distances);
    const auto distinct = std::find_if (sqr_distances.begin (), sqr_distances.end (), [] (float d) { return d > 0.f; });
    if (distinct != sqr_distances.end ())
      spacing_sum += std::sqrt (*std::min_element (distinct, sqr_distances.end ()));
  }
  const float h = static_cast<float> (spacing_sum / rim.size ());
  if (!(h > 0.f))
  {
    PCL_WARN ("[pcl_holefill::HoleFilling] A hole's rim has no spacing (duplicate points?): skipped.\n");
    return;
  }
  const float d_eq = sigma_r_ > 0.f ? ElasticSampler<PointT>::equilibriumDistanceFromSigmaR (sigma_r_)
                                    : spacing_factor_ * h;
  const float radius = radius_ > 0.f ? radius_ : std::max (4.f * h, 2.5f * d_eq);
  const float min_radius = std::max (2.f * h, 1.5f * d_eq);
  const float bound = detail::kBoundScale * rim_radius + 2.f * d_eq;
  report.spacing = h;
  report.equilibrium_distance = d_eq;
  report.radius = radius;

  // The hole's surroundings, copied: the fill grows this cloud, never the input.
  typename PointCloud::Ptr local (new PointCloud);
  PointT centre;
  centre.getVector3fMap () = centroid;
  search.radiusSearch (centre, bound + radius, found, sqr_distances);
  std::sort (found.begin (), found.end ());  // a deterministic order, whatever the search
  std::unordered_map<int, int> local_index;
  for (const auto i : found)
  {
    local_index[i] = static_cast<int> (local->size ());
    local->push_back (working[i]);
  }
  const std::size_t input_points = local->size ();
  typename VoxelHashSearch<PointT>::Ptr local_search (new VoxelHashSearch<PointT>);
  local_search->setCellSize (radius);  // a radius-r query then reads a 3x3x3 block
  local_search->setInputCloud (local);

  ElasticSampler<PointT> sampler;
  sampler.setInputCloud (local);
  sampler.setSearchMethod (local_search);
  sampler.setSigmaN (sigma_n_);
  sampler.setEquilibriumDistance (d_eq);
  pcl::Indices local_rim;
  for (const auto i : rim)
    if (local_index.count (i))
      local_rim.push_back (local_index[i]);
  report.noise = detail::rimNoise (*local, *local_search, local_rim, detail::kNoiseReachInSpacings * h);
  // The first-order extension extrapolates the rim's curvature from its
  // normals: on a noisy rim (whose normals, estimated from the noisy points,
  // are noisy too) it extrapolates the noise, and the patch runs away.
  report.first_order = first_order_ && report.noise <= detail::kFirstOrderMaxNoiseInSpacings * h;
  sampler.setFirstOrder (report.first_order);
  sampler.setConstraintTolerance (
      std::max (detail::kToleranceInSpacings * h, detail::kToleranceInNoiseSigmas * report.noise));
  sampler.setCombinationConstraint (combination_constraint_);
  sampler.setBoundingBall (centroid, bound);

  Front front (1);
  front[0].closed = loop.closed;
  for (const auto i : rim)
  {
    const auto it = local_index.find (i);
    if (it == local_index.end ())
      continue;
    const PointT &p = (*local)[it->second];
    front[0].vertices.push_back ({p.getVector3fMap (), p.getNormalVector3fMap ().normalized ()});
  }
  // Growth is measured against the first contracted boundary, which is
  // sampled like every later one (the input rim is jagged, hence longer).
  float first_length = 0.f;

  ContractionStats stats;
  float pass_radius = radius;
  report.termination = Termination::kPassLimit;
  for (int pass = 0; pass < max_passes_; ++pass)
  {
    sampler.setRadius (pass_radius);
    sampler.setSigmaD (sigma_d_ > 0.f ? sigma_d_ : 0.5f * pass_radius);
    Front next;
    if (!sampler.contract (front, next, stats))
    {
      report.termination = Termination::kNotStarted;
      break;
    }
    ++report.passes;
    // B joins the surface: other fields from the nearest known point.
    for (const auto &chain : next)
      for (const auto &v : chain.vertices)
      {
        PointT query;
        query.getVector3fMap () = v.position;
        local_search->nearestKSearch (query, 1, found, sqr_distances);
        PointT p = found.empty () ? query : (*local)[found[0]];
        p.getVector3fMap () = v.position;
        p.getNormalVector3fMap () = v.normal;
        local->push_back (p);
      }
    local_search->indexNewPoints ();

    const float ratio = stats.former_boundary_points > 0
                            ? static_cast<float> (stats.kept_control_points) / stats.former_boundary_points
                            : 0.f;
    if (frontSize (next) < 3)
    {
      report.termination = Termination::kNoNewBoundary;
      break;
    }
    if (ratio < termination_ratio_)
    {
      report.termination = Termination::kControlRatio;
      break;
    }
    if (pass == 0)
      first_length = frontLength (next);
    else if (frontLength (next) > max_growth_ * first_length)
    {
      report.termination = Termination::kDiverging;
      break;
    }
    front.swap (next);
    pass_radius = std::max (min_radius, pass_radius / shrink_);
  }
  // Closed: stopped by the paper's rule, and either the last boundary had
  // shrunk to a few samples (an apex, a corner) or most of its candidates
  // were discarded because fronts met (the elastic force, or surface already there).
  const std::size_t discarded = stats.former_boundary_points - stats.kept_control_points;
  std::vector<Eigen::Vector3f> last_boundary;
  for (const auto &chain : front)
    for (const auto &v : chain.vertices)
      last_boundary.push_back (v.position);
  const bool natural_end = report.termination == Termination::kControlRatio ||
                           report.termination == Termination::kNoNewBoundary;
  report.closed = natural_end && (2 * (stats.repelled + stats.too_close) >= discarded ||
                                  loopDiameter (last_boundary) <= detail::kClosedFrontDiameter * d_eq);
  // Each filled point stands for about d_eq^2 of surface.
  const float patch_area = static_cast<float> (local->size () - input_points) * d_eq * d_eq;
  const float rim_disc = static_cast<float> (M_PI) * 0.25f * loop.diameter * loop.diameter;
  if (report.closed && rim_disc > 0.f && patch_area > detail::kMaxAreaOverRimDisc * rim_disc)
    PCL_WARN ("[pcl_holefill::HoleFilling] A hole of diameter %g needed a patch %.1f times the disc on its rim: "
              "more than half of the shape may be missing there, and the patch is a guess.\n",
              loop.diameter, patch_area / rim_disc);
  if (report.termination == Termination::kDiverging || report.termination == Termination::kPassLimit)
    PCL_WARN ("[pcl_holefill::HoleFilling] A hole of diameter %g stopped after %u passes (%s): it is not closed. "
              "More than half of the shape may be missing there.\n",
              loop.diameter, report.passes, toString (report.termination));
  filled.clear ();
  for (std::size_t i = input_points; i < local->size (); ++i)
    filled.push_back ((*local)[i]);
}

}  // namespace pcl_holefill

#define PCL_INSTANTIATE_HoleFilling(T) template class pcl_holefill::HoleFilling<T>;
