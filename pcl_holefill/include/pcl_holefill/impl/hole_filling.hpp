/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/bilateral_preprocessor.h>
#include <pcl_holefill/detail/crease_chords.h>
#include <pcl_holefill/detail/normal_refit.h>
#include <pcl_holefill/detail/stray_points.h>
#include <pcl_holefill/detail/elastic_sampler.h>
#include <pcl_holefill/hole_boundary_estimation.h>
#include <pcl_holefill/hole_filling.h>
#include <pcl_holefill/impl/bilateral_preprocessor.hpp>
#include <pcl_holefill/detail/elastic_sampler.hpp>
#include <pcl_holefill/detail/first_touch.h>
#include <pcl_holefill/impl/hole_boundary_estimation.hpp>
#include <pcl_holefill/impl/voxel_hash_search.hpp>
#include <pcl_holefill/detail/loop_tracing.h>
#include <pcl_holefill/detail/opening.h>
#include <pcl_holefill/impl/normal_orientation.hpp>
#include <pcl_holefill/normal_orientation.h>
#include <pcl_holefill/detail/point_validity.h>
#include <pcl_holefill/detail/rim_side_planes.h>
#include <pcl_holefill/detail/thread_count.h>
#include <pcl_holefill/voxel_hash_search.h>

#include <pcl/common/centroid.h>
#include <pcl/common/eigen.h>
#include <pcl/common/io.h>
#include <pcl/console/print.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace pcl_holefill
{
namespace detail
{
// A patch larger than this many discs spanning its rim suggests that more
// than half of the shape is missing there (the paper's admitted failure).
constexpr float kMaxAreaOverRimDisc = 2.5f;
// A fill that leaves an opening at least kNotClosedIn of its rim's diameter
// wide has not closed in on the hole. With an opening of o diameters the
// band it can have filled along the rim covers at most 1 - o^2 of the disc
// on the rim on a flat hole, 2 sqrt (1 - o^2) on a hemisphere (1.6 at
// o = 0.6, none at o >= 1). A patch over kBandMargin times the hemisphere's
// band went elsewhere (single-view scans: the occluded side grown as a lid
// across a bowl, a bore's wall run past its end, the back of a blob seen
// from one side: 0.9-2.6 discs with openings of 0.69-1.25; holes 48-120 d_eq
// wide) and is withdrawn. The corpus's open patches reach at most 0.93 of
// the bound (a corner's 1.47 discs at 0.75). On a hole under
// kMinWidthToJudge d_eq wide a pass is a tenth of the width or more, too
// coarse to tell: a pyramid's 8 d_eq hole at 0.5 % noise (1.65 discs, an
// opening of 0.88) was mostly covered by its patch (the case 96 %,
// withdrawn 56 %).
constexpr float kNotClosedIn = 0.6f;
constexpr float kBandMargin = 1.2f;
constexpr float kMinWidthToJudge = 20.f;
// The fill of a hole stays inside the ball around its rim's centroid of
// radius kBoundScale x (rim radius) + 2 d_eq: a runaway front is cut there.
constexpr float kBoundScale = 1.5f;
// A hole is open where an empty disc this wide (in d_eq) touches the
// boundary on which its fill stopped: twice the spacing of the fill.
constexpr float kOpenDiscInSpacings = 3.f;
// ... a disc counts as empty when no point lies within this share of its radius.
constexpr float kOpenDiscFill = 0.9f;
// An opening shows on at least this many points. Fewer, close together, are
// the apex of a corner: the faces around a convex corner, unfolded into one
// plane, leave an empty wedge (90 degrees at a cube's corner) even when the
// surface is complete.
constexpr std::size_t kMinOpenPoints = 3;
// An open hole is contracted again from its openings at most this many times.
constexpr int kResumeRounds = 2;
// ... when its boundary normals are within ~66 degrees of their mean (or,
// for a strip, of the narrowest cone's axis): an opening across an edge or a
// cube's corner (45 and 55 degrees with exact normals) is taken up; normals
// that turn further are rough or misoriented, and along them a front runs
// past the edge.
constexpr float kResumeMinNormalCosine = 0.4f;
// Steps of the search for the narrowest cone around the normals.
constexpr int kConeSearchSteps = 64;
// New points must lie within the rim of a closed hole (ElasticSampler::setRim):
// a point is beyond it when the rim leaves a sector empty around it wider
// than pi seen along the hole's axis (the mean of the rim's normals) and
// wider than 200 degrees seen along its own normal. Inside, the widest is
// under pi (pi on a straight stretch of rim); filled points reached 152
// degrees along the axis (a steep apex) and 281 along their normal (same).
constexpr float kMaxRimGapAlongAxis = static_cast<float> (M_PI);
constexpr float kMaxRimGapAlongNormal = static_cast<float> (200.0 * M_PI / 180.0);
// ... and both limits are this wide on a clean rim that shows a crease. The
// test is the backstop for fronts nothing else holds: on noisy rims the
// combination constraint and the rim planes give each face a tolerance of
// several sigma, and a rim without a crease gives them no plane to hold. On
// a clean creased rim they hold each face within 0.1 h, and the test only
// cut valid fill: at the corner of a thin plate (the hole takes the end and
// both faces' corners) the faces' corners lie past the rim's outline in
// every view, seen 183-234 degrees empty (fin corners, 48 cases: 28 -> 41
// covered to 99 %, 11 -> 38 closed, the largest error 0.42 -> 0.35 pitch;
// without any test alike). A noisy fin's end needs narrower limits
// (240 degrees there: sums of max errors at 0.3 / 0.5 % 0.815 / 1.290 ->
// 0.843 / 1.375).
constexpr float kMaxRimGapOnCleanCreasedRim = static_cast<float> (240.0 * M_PI / 180.0);
// ... and the limit along the axis is this wide on a noisy rim that shows a
// crease, up to kMaxNoiseForWiderAxisLimitInPitches of noise. At the corner
// of a thin plate (the hole takes both faces' corners and the sides between)
// the faces' corners lie on the rim's outline seen along the axis (exactly
// pi on a noise-free rim: the outline runs along the plate's edge there),
// and the noise of the rim points puts them to either side of it: at pi the
// test cut about every other one and the fronts stopped with the corners
// open (fin corners, 36 noisy cases: 13 -> 28 covered to 95 %, holes
// reported closed 50 -> 81 of 173, sum of max errors 0.795 -> 0.790).
// Widening the limit along the normal instead (240 degrees) cost more: a
// pyramid's apex at 0.5 % with estimated normals 0.0154 -> 0.0271.
constexpr float kMaxRimGapAlongAxisOnNoisyCreasedRim = static_cast<float> (200.0 * M_PI / 180.0);
// Noisier rims keep pi along the axis: their faces are held within 4 sigma
// (kRimPlaneNoiseSigmas), 2 pitches and more, and the outline is what stops
// a front there. With 200 degrees at 0.5 % the top and bottom faces ran 4.5
// pitches past a fin's corner (scan lines: max error 0.029 -> 0.050) and a
// fin's end face bulged 3.7 pitches out (Poisson-disk, estimated normals:
// 0.0175 -> 0.0287). Rim noise (HoleReport::noise) on the fin at 0.1 / 0.3 / 0.5 %
// of its diagonal (the holes looked at): 0.13-0.16 / 0.38-0.43 / 0.57-0.73 pitch.
constexpr float kMaxNoiseForWiderAxisLimitInPitches = 0.5f;
// The fill stays below the rim's supporting tangent planes
// (ElasticSampler::setRimPlanes), within max(0.1 h, 4 sigma) plus this slope
// (radians, plus the rim's normal spread) times the distance: a face's front
// that reached a corner first ran on past it (a corner hole 0.6 across on
// 100,000 random samples of a cube, exact normals: max error 0.20, now
// 0.0043; an edge hole at 0.3 % noise: 0.097, now 0.011).
constexpr float kRimPlaneSlope = 0.05f;
// Directions more than 120 degrees apart are opposite sides (betweenTwoCreases).
constexpr float kOppositeSidesCosine = -0.5f;
// A narrow face's planes are used only where the rim's normals spread less
// than this (radians): exact or smooth normals.
constexpr float kMaxStripNormalSpread = 0.01f;
constexpr float kRimPlaneNoiseSigmas = 4.f;
// A rim point's plane is supporting when at most this share of the other rim
// points lies above it (noise puts 0.1-0.4 % of a cube's rim there). Taken
// per point, so that a plane that noise or PCA tilted is left out while the
// others bound the fill: the whole rim's share (2 % of its pairs) decided
// all planes or none before, and noisy rims went without (spikes past
// creases, 0.05-0.3 on noisy CAD parts with PCA normals), because their
// tilted planes cut valid fill off (a random dihedral at 0.1 %: 100 -> 93 %).
constexpr float kMaxRimPlaneViolations = 0.02f;
// The contraction stops when the new boundary has fewer points than this.
// Three points span at most a triangle of sides d_eq, less than the empty
// disc of 3 d_eq that the closure check counts as open; what three points
// did instead was march on as a remnant, pass after pass, bending with the
// first-order extension (a cube edge, random samples, PCA normals, 0.1 %:
// one chain of three for 27 passes into the solid, max error 0.21 -> 0.07).
// Fast corpus, 3 -> 4: sums of max errors at 0.1 / 0.3 / 0.5 % 0.302 /
// 0.804 / 1.392 -> 0.301 / 0.799 / 1.302, one case under 95 % covered.
constexpr std::size_t kMinFrontPoints = 4;
// A hole's axis is taken when the rim's normals sum to at least this share
// of their count (they cancel out on a rim around a thin plate's middle).
constexpr float kMinRimAxisStrength = 0.05f;
// ... tested against this many points taken evenly along the rim.
constexpr std::size_t kRimOutlinePoints = 96;
// Passes beyond four times the passes that close a hole, when the bound is automatic.
constexpr int kAutoPassesSlack = 20;
// The fill's search holds the points near the holes (HoleFilling::
// pointsNearHoles), as far as the detection's pitch and spacing, times this
// margin, say a hole's fill reaches. A hole that measures wider is measured
// again over the whole cloud.
constexpr float kNearHolesMargin = 2.f;
// Up to this many holes are tested point by point; more search the whole cloud.
constexpr std::size_t kMaxHolesSearchedApart = 32;
// The searched reach must stay this far inside the ball of points held
// (float rounding of the ball test).
constexpr float kNearHolesSafety = 0.99f;
// Normals blended across a crease are refitted (detail::refitCreaseNormal)
// from the neighbours within this many mean spacings: corner and edge holes
// in random samples of a cube with PCA normals, 24 cases: >= 99 % covered
// 5 -> 23, sum of max errors 0.82 -> 0.06 at 6; 18 and 0.40 at 4.
constexpr float kCreaseReachInSpacings = 6.f;
// Normals near a hole are refitted to creases and curvature only on rims
// whose noise allowance (the constraint's tolerance) is under this share of
// the pitch. 0.25 left PCA normals blended on random cubes at 0.1 % noise
// (tolerance 0.27 pitch; corner hole, max error 0.008-0.088 over 8 seeds
// -> 0.003-0.051); at 0.6 the corpus's sums of max errors at 0.1 / 0.3 % went
// 0.392 / 0.938 -> 0.386 / 0.934. Left: a point within the tolerance of an
// edge lies on both faces' planes, and on the fin's end (scan lines, 0.1 %)
// such points took the faces' normals and a front ran off the end (0.008 ->
// 0.047). Noisier rims keep their normals; the constraint's noise tolerance
// covers their blending.
constexpr float kRefitMaxToleranceInPitches = 0.6f;
// The one-sided neighbourhoods of a rim reach this far from it (pitches):
// the normals within are refitted by a quadric (detail::quadricNormal).
// A sphere cap 32 pitches across, random samples, PCA normals: max error
// 0.014 -> 0.0006 refitting within ~1.6 pitches, 0 within ~4.
constexpr float kRimBiasReachInPitches = 3.f;
// Rims noisier than this (mean spacings; exact positions measure 0-0.005 h,
// the facets of the corpus's meshes) are noisy: their quadric fits take
// more neighbours (quadricNeighbours), and their normals are smoothed when
// rough (smoothNoisyNormals).
constexpr float kRimBiasMaxNoiseInSpacings = 0.02f;
// The quadric's neighbours: 24 on clean rims, this many per unit of noise
// (noise / spacing) on noisy ones, at most kMaxWideNeighbours. The slope a
// fit reads off its neighbours errs by ~noise / (reach sqrt(k)), so ~noise
// / k: 24 on a rim at 0.1 h tilted more than the bias it removed (a random
// cube corner at 0.1 % noise, 0.056 -> 0.086), ~140 (at 0.19 h) takes it
// out (random sphere cap at 0.1 %, PCA normals: 0.017-0.036 -> 0.003-0.004;
// random cube corner: 0.003-0.051 -> 0.003-0.008).
constexpr float kQuadricNeighboursPerNoise = 750.f;
// Noisy rims: the normals within this many pitches of the rim are compared
// with, and may be replaced by, PCA over more neighbours (smoothNoisyNormals).
constexpr float kNoisyRimReachInPitches = 5.f;
// ... over this many neighbours per unit of noise (noise / spacing), from 16
// (PCL's k) to kMaxWideNeighbours. PCA's normal errs by ~noise / (reach
// sqrt(k)), so ~noise / k; a random sphere cap at 0.3 % noise (0.6 h) came
// out 0.03-0.22 off with PCL's 16, 0.007-0.024 with 64, 0.008-0.015 with 192.
constexpr float kWideNeighboursPerNoise = 320.f;
constexpr int kMaxWideNeighbours = 192;
// On a noisy rim smoothed as one piece (no crease), the quadric takes this
// many neighbours per unit of noise (noise / spacing), at most
// kMaxSmoothRimQuadricNeighbours. A large hole amplifies what is left of
// the tilt: a cap 110 pitches across cut from 100,000 random sphere samples
// at 0.1 % noise, PCA normals, four seeds: with the crease test, 192
// neighbours 0.018-0.39 max error (a front ran off), 384 0.007-0.013 and
// 95-100 % covered; without it, 384 0.008-0.010 and 98-100 %, 768 (this
// rule) 0.003-0.005 and 100 %; at 0.3 % on 50,000 samples (capped at 768)
// 0.007-0.012, >= 99.8 %. Corpus: sums of max errors at 0.1 / 0.3 / 0.5 %
// 0.358 / 0.905 / 1.664 -> 0.354 / 0.881 / 1.640, no coverage changed; the
// fin at 0.1 % with estimated normals 0.0011 -> 0.0029 (varying density).
constexpr float kSmoothRimQuadricNeighboursPerNoise = 1600.f;
constexpr int kMaxSmoothRimQuadricNeighbours = 768;
constexpr int kPcaNeighbours = 16;
constexpr std::size_t kMinWideNeighbours = 8;
// Roughness is measured against this many nearest neighbours' normals ...
constexpr std::size_t kRoughnessNeighbours = 16;
// ... and the wide fit replaces normals at most this share as rough: exact
// normals of noisy points (sphere, 0.3 %: 0.7 degrees against the fit's
// 0.7) stay; PCA normals (5.7 degrees) go.
constexpr float kRougherBy = 0.7f;
// A wide fit whose residual variance exceeds this many noise variances
// straddles a crease (sphere at 0.5 % noise, K = 192: at most 1.8; the
// pyramid's apex: 2.6 and more) ...
constexpr float kCreaseResidualInNoiseVariances = 2.2f;
// ... and a rim with more such fits than this share keeps its normals: a
// wide PCA blends faces over several pitches (random cube edge at 0.3 %:
// coverage 99 -> 84 %; pyramid apex at 0.5 %: 100 -> 63 %).
constexpr float kMaxCreasedShare = 0.05f;
// Neighbours from which the sampling pitch around a rim point is measured.
constexpr int kPitchNeighbours = 16;
// More neighbouring normals than this pointing opposite ways: not oriented.
constexpr float kMaxFlippedShare = 0.02f;
// Tolerance of the combination constraint, in mean spacings, on clean data...
constexpr float kToleranceInSpacings = 0.1f;
// ... and in standard deviations of the rim's noise on noisy data: a noisy
// neighbour lies that far off its own tangent plane, and would otherwise
// make every candidate near it look like an overshoot (the fill then stops).
constexpr float kToleranceInNoiseSigmas = 2.5f;
// The convex/concave labels' dead zone, in noise sigmas: half the above. A
// label is a point's height over its neighbours' mean: across an edge it is
// about a sixth of the constraint's reach, under 2.5 sigmas at noise 0.3 %
// of the diagonal, so the edge went unseen (corpus, 0.3 %: sum of max
// errors 1.81 at 2.5, 1.19 at 1.25, 0.98 at 0.75, but coverage >= 95 % at
// 0.5 % noise in 101 of 108 cases at 1.25, 95 at 0.75).
constexpr float kSignToleranceInNoiseSigmas = 1.25f;
// Growth of the constraint's tolerance with distance, per unit of the rim's
// normal spread: pyramid apex, random samples, PCA normals: 87 % -> 98 %
// covered, max error 0.0077 -> 0.0097 (the corpus's clean-normal cases unchanged).
constexpr float kSlopePerNormalSpread = 1.f;
// Above this rim noise (in mean spacings) the first-order extension is off,
// unless the rim's normals are good enough to extrapolate (RimStatistics::normalsAreLinear).
constexpr float kFirstOrderMaxNoiseInSpacings = 0.1f;
// Normals that fit a linear field within this RMS (RimStatistics::nonlinearity)
// are good. Measured: exact normals 0.000-0.013 (sphere, cube, cylinder),
// voxel-grid centroids 0.017-0.021, normals estimated at noise 0.1 % of the
// diagonal 0.018-0.04, at 0.3 % 0.06-0.13.
constexpr float kFirstOrderMaxNormalNonlinearity = 0.015f;
// ... and so are normals within kSmoothRimMaxNonlinearity on a smooth rim,
// one where at most kSmoothRimMaxCreaseShare of the rim points see a crease
// (a neighbour's normal more than kCreaseNormalDifference, ~30 degrees,
// away; see normal_refit.h). Near a crease, estimated normals are blended across it, and
// extrapolating that blend bends the patch (cube edges 0.013 -> 0.023).
constexpr float kSmoothRimMaxNonlinearity = 0.05f;
constexpr float kSmoothRimMaxCreaseShare = 0.02f;
// The rim's normals are measured in a ball of this many mean spacings around each rim point...
constexpr float kNoiseReachInSpacings = 2.5f;
// ... and its noise on this many nearest neighbours: a quadric (6 coefficients)
// fitted with some to spare, over more than one scan line (scans are up to 5
// times denser along their lines than across).
constexpr int kNoiseNeighbours = 24;
// Automatic sigma_n: this many times the rim's normal spread (below), and
// never under kSharpSigmaN, the value that keeps creases sharp on clean rims.
constexpr float kSigmaNPerNormalSpread = 2.f;
constexpr float kSharpSigmaN = 0.1f;
// ... and never over kMaxAutoSigmaN: wider, g2 lets the faces of a corner
// pull each other round on noisy rims (coverage of pyramid corners fell
// from 99 % to 80 % at 0.7).
constexpr float kMaxAutoSigmaN = 0.3f;

// A fill whose fronts ran off (outside_bound) along walls is tried again
// across the opening: more than kMinShareAlongWalls of its points on walls
// past the rim (detail::shareAlongWalls) and the mean |n . axis| of their
// normals under kMaxWallAlignment (detail::alignmentWithLoop). Measured on
// first fills that ran off: boxes without their lid and cylinders without
// their cap 0.62-0.70 and 0.000-0.008 (random and Poisson-disk samples,
// exact and estimated normals), at 0.1 % noise 0.33 and 0.26; where a face
// across would cut off what the fill closed in on, a pyramid's apex at
// 0.5 % noise 0.01-0.13 and 0.35-0.47, a thin fin's end 0.24 and 0.33.
constexpr float kMinShareAlongWalls = 0.3f;
constexpr float kMaxWallAlignment = 0.3f;
// A fill stopped at the rim (its candidates dropped beyond the rim or held
// at the bound) that left an opening this share of the loop's diameter
// wide has closed almost nothing: it counts as run along the walls whatever
// its share (boxes without their lid sampled on scan lines, with varying
// density, at random: 0.95-0.99, 6-8 passes up the walls; share 0.00).
constexpr float kStillOpen = 0.9f;
// The face across an opening may lie this many RMS depths of the rim (its
// points' spread along the face's normal) off a rim point's plane.
constexpr float kRimDepthsAllowed = 3.f;
// An opening's rim is flat when its RMS depth is at most this share of its
// diameter (a rim of random samples: ~0.5 pitch)...
constexpr float kFlatOpeningDepth = 0.05f;
// ... and its crease then lies at this quantile of its points' heights
// (the last row of a sampling lies between the crease and a pitch or two
// short of it; noise puts a few above).
constexpr float kOpeningCreaseQuantile = 0.9f;

// Slack of the crease chords' planes (detail::CreaseChord), in d_eq.
constexpr float kCreaseChordToleranceInDeq = 0.5f;

/** The median of \a values (0 when empty); reorders them. */
inline float
median (std::vector<float> &values)
{
  if (values.empty ())
    return 0.f;
  std::nth_element (values.begin (), values.begin () + values.size () / 2, values.end ());
  return values[values.size () / 2];
}

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN ();

/** RMS distance of the points \a found to the quadric height field over
  * point \a i's tangent plane that fits them best, corrected for the six
  * fitted coefficients (NaN when they do not span two directions). The
  * quadric takes the curvature out, so what is left is the noise; the
  * tangent plane of the point's own normal, not the neighbours' best plane,
  * because on scan lines the neighbours may lie on one line, and a plane
  * through a line and the normal fits them exactly, whatever the noise. */
template <typename PointT> float
heightFieldRms (const pcl::PointCloud<PointT> &cloud, int i, const pcl::Indices &found)
{
  constexpr Eigen::Index kCoefficients = 6;
  constexpr float kMinConditioning = 1e-3f;  // smallest/largest singular value of the scaled design
  const Eigen::Vector3f x = cloud[i].getVector3fMap ();
  const Eigen::Vector3f n = cloud[i].getNormalVector3fMap ().normalized ();
  const Eigen::Vector3f u = n.unitOrthogonal (), v = n.cross (u);
  // Only the neighbours on the point's own side of a crease or of a thin
  // part: the other face is no height field over this tangent plane.
  thread_local pcl::Indices same_face;
  same_face.clear ();
  float reach = 0.f;
  for (const auto q : found)
    if (detail::isOrientedPoint (cloud[q]) &&
        (cloud[q].getNormalVector3fMap ().normalized () - n).norm () <= kCreaseNormalDifference)
    {
      same_face.push_back (q);
      reach = std::max (reach, (cloud[q].getVector3fMap () - x).norm ());
    }
  const Eigen::Index rows = static_cast<Eigen::Index> (same_face.size ());
  if (rows <= 2 * kCoefficients || !(reach > 0.f))
    return kNaN;
  Eigen::MatrixXf a (rows, kCoefficients);
  Eigen::VectorXf heights (rows);
  for (Eigen::Index k = 0; k < rows; ++k)
  {
    const Eigen::Vector3f d = cloud[same_face[k]].getVector3fMap () - x;
    const float s = d.dot (u) / reach, t = d.dot (v) / reach;
    a.row (k) << 1.f, s, t, s * s, s * t, t * t;
    heights[k] = d.dot (n);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXf> svd (a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const auto &singular = svd.singularValues ();
  if (!(singular[kCoefficients - 1] > kMinConditioning * singular[0]))
    return kNaN;
  return (a * svd.solve (heights) - heights).norm () / std::sqrt (static_cast<float> (rows - kCoefficients));
}

/** The median |n_i - n_q| over the neighbours \a found (NaN if none);
  * \a differences is scratch space. */
template <typename PointT> float
normalSpread (const pcl::PointCloud<PointT> &cloud, int i, const pcl::Indices &found, std::vector<float> &differences)
{
  const Eigen::Vector3f n = cloud[i].getNormalVector3fMap ().normalized ();
  differences.clear ();
  for (const auto q : found)
    if (q != i && detail::isOrientedPoint (cloud[q]))
      differences.push_back ((cloud[q].getNormalVector3fMap ().normalized () - n).norm ());
  return differences.empty () ? kNaN : median (differences);
}

/** Is point \a q's normal more than kCreaseNormalDifference from the unit normal \a n? */
template <typename PointT> bool
acrossACrease (const pcl::PointCloud<PointT> &cloud, int q, const Eigen::Vector3f &n)
{
  return detail::isOrientedPoint (cloud[q]) &&
         (cloud[q].getNormalVector3fMap ().normalized () - n).norm () > kCreaseNormalDifference;
}

/** Does a neighbour's normal differ from point \a i's by more than kCreaseNormalDifference? */
template <typename PointT> bool
seesCrease (const pcl::PointCloud<PointT> &cloud, int i, const pcl::Indices &found)
{
  const Eigen::Vector3f n = cloud[i].getNormalVector3fMap ().normalized ();
  return std::any_of (found.begin (), found.end (), [&] (int q) { return acrossACrease (cloud, q, n); });
}

/** Is point \a i on a strip between two creases: neighbours whose normals
  * differ from its own by more than kCreaseNormalDifference on opposite
  * sides of it (tangent directions more than 120 degrees apart)? The end of
  * a plate a few pitches thick is such a strip; a face near a corner sees
  * the other faces at right angles, not opposite. */
template <typename PointT> bool
betweenTwoCreases (const pcl::PointCloud<PointT> &cloud, int i, const pcl::Indices &found)
{
  const Eigen::Vector3f x = cloud[i].getVector3fMap ();
  const Eigen::Vector3f n = cloud[i].getNormalVector3fMap ().normalized ();
  std::vector<Eigen::Vector3f> sides;
  for (const auto q : found)
  {
    if (!acrossACrease (cloud, q, n))
      continue;
    Eigen::Vector3f d = cloud[q].getVector3fMap () - x;
    d -= d.dot (n) * n;
    if (d.norm () > 0.f)
      sides.push_back (d.normalized ());
  }
  for (std::size_t a = 0; a < sides.size (); ++a)
    for (std::size_t b = a + 1; b < sides.size (); ++b)
      if (sides[a].dot (sides[b]) < kOppositeSidesCosine)
        return true;
  return false;
}

/** RMS residual of the least-squares fit n(u, v) = a + b u + c v of the
  * normals \a found around point \a i (u, v its tangent coordinates over
  * \a reach); NaN with fewer than \a min_rows usable neighbours. */
template <typename PointT> float
linearNormalResidual (const pcl::PointCloud<PointT> &cloud, int i, const pcl::Indices &found, float reach,
                      Eigen::Index min_rows)
{
  const Eigen::Vector3f x = cloud[i].getVector3fMap ();
  const Eigen::Vector3f n = cloud[i].getNormalVector3fMap ().normalized ();
  const Eigen::Vector3f u = n.unitOrthogonal (), v = n.cross (u);
  Eigen::MatrixXf a (found.size (), 3), normals (found.size (), 3);
  Eigen::Index rows = 0;
  for (const auto q : found)
  {
    if (!detail::isOrientedPoint (cloud[q]))
      continue;
    const Eigen::Vector3f d = cloud[q].getVector3fMap () - x;
    a.row (rows) << 1.f, d.dot (u) / reach, d.dot (v) / reach;
    normals.row (rows++) = cloud[q].getNormalVector3fMap ().normalized ().transpose ();
  }
  if (rows < min_rows)
    return kNaN;
  const Eigen::MatrixXf fit = a.topRows (rows).colPivHouseholderQr ().solve (normals.topRows (rows));
  return (a.topRows (rows) * fit - normals.topRows (rows)).norm () / std::sqrt (static_cast<float> (rows));
}

/** What the surface and its normals do around a rim, from one search per
  * rim point (neighbours within the same reach). Each is a median over rim
  * points, so that the few near a crease do not count. */
struct RimStatistics
{
  /** Median |n_p - n_q| over the neighbours: curvature within the reach and
    * the noise of estimated normals (a crease shows in fewer than half of a
    * point's neighbours, so it does not count). */
  float normal_spread = 0.f;
  /** RMS residual of a linear fit of the normals: what the first-order
    * extension would extrapolate wrongly. Curvature fits; noise does not. */
  float nonlinearity = 0.f;
  /** Share of rim points with a neighbour's normal ~30 degrees away. */
  float crease_share = 0.f;

  /** Are the normals good enough for the first-order extension: linear
    * within kFirstOrderMaxNormalNonlinearity, or within
    * kSmoothRimMaxNonlinearity where the rim has no crease? */
  bool
  normalsAreLinear () const
  {
    return nonlinearity <= kFirstOrderMaxNormalNonlinearity ||
           (nonlinearity <= kSmoothRimMaxNonlinearity && crease_share <= kSmoothRimMaxCreaseShare);
  }
};

// Rim points with fewer neighbours within the statistics' reach are left out.
constexpr int kMinStatisticsNeighbours = 5;

inline void
keepFinite (std::vector<float> &values, float value)
{
  if (std::isfinite (value))
    values.push_back (value);
}

/** The rim's noise: the median over rim points of the RMS height of their
  * kNoiseNeighbours over their fitted quadric. Measured on the given
  * normals, before the refits that depend on it. */
template <typename PointT> float
measureRimNoise (const pcl::PointCloud<PointT> &cloud, pcl::search::Search<PointT> &search, const pcl::Indices &rim,
                 float reach)
{
  std::vector<float> noise;
  pcl::Indices found;
  std::vector<float> sqr_distances;
  for (const auto i : rim)
    if (search.radiusSearch (cloud[i], reach, found, sqr_distances) >= kMinStatisticsNeighbours &&
        search.nearestKSearch (cloud[i], kNoiseNeighbours, found, sqr_distances) > 0)
      keepFinite (noise, heightFieldRms (cloud, i, found));
  return median (noise);
}

template <typename PointT> RimStatistics
measureRimStatistics (const pcl::PointCloud<PointT> &cloud, pcl::search::Search<PointT> &search,
                      const pcl::Indices &rim, float reach)
{
  constexpr int kMinFitNeighbours = 8;  // a fit of 3 unknowns per component, with some to spare
  std::vector<float> spread, residual, scratch;
  std::size_t seen = 0, creased = 0;
  pcl::Indices found;
  std::vector<float> sqr_distances;
  for (const auto i : rim)
  {
    if (search.radiusSearch (cloud[i], reach, found, sqr_distances) < kMinStatisticsNeighbours)
      continue;
    ++seen;
    keepFinite (spread, normalSpread (cloud, i, found, scratch));
    creased += seesCrease (cloud, i, found) ? 1 : 0;
    if (found.size () >= kMinFitNeighbours)
      keepFinite (residual, linearNormalResidual (cloud, i, found, reach, kMinFitNeighbours));
  }
  RimStatistics statistics;
  statistics.normal_spread = median (spread);
  statistics.nonlinearity = median (residual);
  statistics.crease_share = seen ? static_cast<float> (creased) / seen : 0.f;
  return statistics;
}

/** Sets the normal of each point of \a cloud marked in \a changed to its
  * entry of \a normals; returns how many. The refits write only after every
  * point has been read: the same output for any thread count. */
template <typename PointT> std::size_t
writeNormals (const std::vector<Eigen::Vector3f> &normals, const std::vector<char> &changed,
              pcl::PointCloud<PointT> &cloud)
{
  std::size_t count = 0;
  for (std::size_t i = 0; i < changed.size (); ++i)
    if (changed[i])
    {
      cloud[i].getNormalVector3fMap () = normals[i];
      ++count;
    }
  return count;
}

/** The combination constraint's tolerance for a rim of mean spacing
  * \a spacing and noise \a noise: the allowance of the normal refits too. */
inline float
constraintTolerance (float spacing, float noise)
{
  return std::max (kToleranceInSpacings * spacing, kToleranceInNoiseSigmas * noise);
}

/** Is a rim of mean spacing \a spacing and noise \a noise clean: its noise
  * under what the constraint's noise-free tolerance (0.1 h) allows? */
inline bool
noiseFree (float spacing, float noise)
{
  return constraintTolerance (spacing, noise) <= kToleranceInSpacings * spacing;
}

/** Every how many rim points the outline takes one (at most kRimOutlinePoints along a rim of \a n). */
inline std::size_t
outlineStep (std::size_t n)
{
  return std::max<std::size_t> (1, (n + kRimOutlinePoints - 1) / kRimOutlinePoints);
}

/** How many neighbours a fit over \a per_noise neighbours per unit of noise
  * takes on a rim of mean spacing \a spacing and noise \a noise. */
inline int
neighboursForNoise (float per_noise, float noise, float spacing, int fewest, int most = kMaxWideNeighbours)
{
  const float wanted = std::ceil (per_noise * noise / spacing);
  return std::isfinite (wanted) ? static_cast<int> (std::clamp (wanted, static_cast<float> (fewest),
                                                                static_cast<float> (most)))
                                : fewest;
}

/** The quadric's neighbours (kQuadricNeighboursPerNoise). */
inline int
quadricNeighbours (float noise, float spacing)
{
  return neighboursForNoise (kQuadricNeighboursPerNoise, noise, spacing, kNoiseNeighbours);
}

/** The quadric's neighbours on a rim smoothed as one piece
  * (kSmoothRimQuadricNeighboursPerNoise). */
inline int
smoothRimQuadricNeighbours (float noise, float spacing)
{
  return neighboursForNoise (kSmoothRimQuadricNeighboursPerNoise, noise, spacing, kNoiseNeighbours,
                             kMaxSmoothRimQuadricNeighbours);
}

/** The wide PCA's neighbours (kWideNeighboursPerNoise). */
inline int
wideNeighbours (float noise, float spacing)
{
  return neighboursForNoise (kWideNeighboursPerNoise, noise, spacing, kPcaNeighbours);
}
/** Keeps the planes (points and unit normals) that support the rim: at most
  * kMaxRimPlaneViolations of the rim's points \a witnesses (in loop order)
  * lie above one, by more than \a tolerance + \a slope x distance. Every
  * plane of a convex rim does; so do those of the faces that a convex edge
  * or corner joins to concave or saddle-shaped parts, whose own planes are
  * left out. Every rim point witnesses, also those next to a crease that
  * give no plane: on a face that curves up towards a crease (fandisk's
  * channel running into its side face) only they rise above the channel's
  * planes, which cut the fill off there. A rise runs along the rim: a point
  * above whose loop neighbours are not (a stray return on the rim, 4
  * pitches off) does not count. */
inline void
keepSupportingPlanes (std::vector<Eigen::Vector3f> &points, std::vector<Eigen::Vector3f> &normals,
                      const std::vector<Eigen::Vector3f> &witnesses, float tolerance, float slope)
{
  const std::size_t n = witnesses.size ();
  std::vector<char> supporting (points.size (), 0), above (n, 0);
  for (std::size_t i = 0; i < points.size (); ++i)
  {
    for (std::size_t j = 0; j < n; ++j)
    {
      const Eigen::Vector3f d = witnesses[j] - points[i];
      above[j] = d.dot (normals[i]) > tolerance + slope * d.norm () ? 1 : 0;
    }
    std::size_t rising = 0;
    for (std::size_t j = 0; j < n; ++j)
      rising += above[j] && (above[(j + n - 1) % n] || above[(j + 1) % n]) ? 1 : 0;
    supporting[i] = static_cast<float> (rising) <= kMaxRimPlaneViolations * static_cast<float> (n);
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < points.size (); ++i)
    if (supporting[i])
    {
      points[kept] = points[i];
      normals[kept++] = normals[i];
    }
  points.resize (kept);
  normals.resize (kept);
}

/** The cosine of the half-angle of (nearly) the narrowest cone around the
  * unit \a normals: the axis starts at their mean and steps towards the
  * normal farthest from it by shrinking steps, \a steps times (Badoiu and
  * Clarkson's core-set walk for the smallest enclosing ball, on the sphere).
  * One step gives the cone around their mean; more, an axis that does not
  * lean towards the face that gives more of them. -1 when the mean is 0. */
inline float
narrowestConeCosine (const std::vector<Eigen::Vector3f> &normals, int steps)
{
  Eigen::Vector3f axis = Eigen::Vector3f::Zero ();
  for (const auto &n : normals)
    axis += n;
  if (!(axis.norm () > 0.f))
    return -1.f;
  axis.normalize ();
  float best = -1.f;
  for (int step = 1; step <= steps; ++step)
  {
    const auto farthest = std::min_element (normals.begin (), normals.end (),
                                            [&] (const Eigen::Vector3f &a, const Eigen::Vector3f &b) {
                                              return a.dot (axis) < b.dot (axis);
                                            });
    best = std::max (best, farthest->dot (axis));
    const Eigen::Vector3f moved = axis + (*farthest - axis) / static_cast<float> (step + 1);
    if (!(moved.norm () > 0.f))
      break;
    axis = moved.normalized ();
  }
  return best;
}

}  // namespace detail

template <typename PointT> bool
HoleFilling<PointT>::checkParameters () const
{
  namespace P = parameters;
  const std::string refused = P::firstRefused ({
      {P::kRadius, radius_},
      {P::kRadiusShrinkFactor, shrink_},
      {P::kSigmaD, sigma_d_},
      {P::kSigmaN, sigma_n_},
      {P::kSigmaR, sigma_r_},
      {P::kSpacingFactor, spacing_factor_},
      {P::kTerminationRatio, termination_ratio_},
      {P::kMaxPasses, static_cast<float> (max_passes_)},
      {P::kMaxBoundaryGrowth, max_growth_},
      {P::kMaxHoleDiameter, max_hole_diameter_},
      {P::kMinHoleSize, min_hole_pitches_},
  });
  if (!refused.empty ())
  {
    PCL_ERROR ("[pcl_holefill::%s::checkParameters] Invalid parameter: %s. Nothing filtered.\n",
               getClassName ().c_str (), refused.c_str ());
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
        PCL_ERROR ("[pcl_holefill::%s::collectHoles] A given hole uses index %d, which is not among the input "
                   "points (or the indices set). Nothing filtered.\n", getClassName ().c_str (), static_cast<int> (i));
        return false;
      }
      i = working_of[i];
    }
    // Measured like a detected loop: the report and the warnings need its size.
    std::vector<Eigen::Vector3f> positions;
    for (const auto i : mapped.indices)
      if (detail::isOrientedPoint ((*working)[i]))
        positions.push_back ((*working)[i].getVector3fMap ());
    mapped.length = detail::loopLength (positions, mapped.closed);
    mapped.diameter = detail::loopDiameter (positions);
    holes.push_back (std::move (mapped));
  }
  return true;
}

template <typename PointT> bool
HoleFilling<PointT>::inputIsUsable () const
{
  if (!checkParameters ())
    return false;
  if (!detail::indicesInRange (*indices_, input_->size ()))
  {
    PCL_ERROR ("[pcl_holefill::%s::applyFilter] The indices set with setIndices() address points outside the "
               "cloud (%zu points). Nothing filtered.\n", getClassName ().c_str (), input_->size ());
    return false;
  }
  if (indices_->empty ())
  {
    PCL_WARN ("[pcl_holefill::%s::applyFilter] The input is empty: nothing to fill.\n", getClassName ().c_str ());
    return false;
  }
  return true;
}

template <typename PointT> void
HoleFilling<PointT>::prepareClouds (PointCloudConstPtr &given, PointCloudConstPtr &working) const
{
  // The input itself when the filter sees all of it unchanged (no copy of a
  // large cloud), else a copy of the indexed points.
  working = input_;
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
  given = working;
  const float flipped = flippedNeighbourShare (*working);
  if (flipped > detail::kMaxFlippedShare)
  {
    PCL_WARN ("[pcl_holefill::%s::applyFilter] %.0f%% of neighbouring normals point opposite ways: the normals are "
              "not consistently oriented. Filling with a consistently oriented copy.\n", getClassName ().c_str (),
              100.f * flipped);
    PointCloudPtr oriented (new PointCloud (*working));
    orientNormalsConsistently (*oriented);
    working = oriented;
  }
}

template <typename PointT> typename HoleFilling<PointT>::Surroundings
HoleFilling<PointT>::contractHole (const PointCloud &working, pcl::search::Search<PointT> &search,
                                   const BoundaryLoop &loop, const pcl::Indices &rim, const HoleScale &scale,
                                   HoleReport &report, int threads, bool across_opening) const
{
  // 2. The surroundings; the fill's copy of their normals refitted where
  // the hole or the noise biases them (beyond the paper); the sampler.
  Surroundings surroundings;
  surroundings.threads = threads;
  gatherSurroundings (working, search, rim, scale, surroundings);
  report.noise = detail::measureRimNoise (*surroundings.cloud, *surroundings.search, surroundings.rim,
                                          detail::kNoiseReachInSpacings * scale.spacing);
  report.refitted_normals = refitNormals (surroundings, scale, report.noise);
  Eigen::Vector3f across = Eigen::Vector3f::Zero ();
  const float rim_depth = across_opening ? turnRimAcrossOpening (surroundings, across) : 0.f;
  detail::ElasticSampler<PointT> sampler;
  setUpSampler (sampler, surroundings, scale, report);
  if (across_opening)
  {
    // The rim is a crease all round: the face across keeps to its own
    // normal (sharp g2), flat (no curvature to extend from walls that do
    // not curve into it), and its first ring contracts towards the loop's
    // centre (the walls below give the vote nothing to go by).
    report.sigma_n = detail::kSharpSigmaN;
    sampler.setSigmaN (report.sigma_n);
    report.first_order = false;
    sampler.setFirstOrder (false);
    sampler.setConstraintSlope (0.f);
    sampler.setInwardCentre (scale.centre);
    // The walls' tangent planes stand across the face and bound nothing of
    // it; on noisy walls the curvature sign of a point is its own noise, and
    // a "concave" wall point rejected every sample inwards of it (0.1 %
    // noise: 3 passes, 10 % of a box's lid covered).
    sampler.setConstraintFacing (across);
    // A rim too uneven to be flattened (turnRimAcrossOpening) keeps its
    // depth: the face settles at its mean height, within that depth of
    // every rim point's plane.
    sampler.setConstraintTolerance (
        std::max (detail::constraintTolerance (scale.spacing, report.noise), detail::kRimDepthsAllowed * rim_depth));
  }
  sampler.setNumberOfThreads (threads);
  if (loop.closed)  // an open border encloses nothing
    encloseByRim (sampler, surroundings, rimGapLimits (surroundings, scale, report, across_opening));
  if (loop.closed && !across_opening)  // the faces of the rim's normals: across an opening there is one
  {
    keepBelowRimPlanes (sampler, surroundings, scale, report);
    keepFacesApartAtCreases (sampler, surroundings, scale, report);
  }

  // 3. Do ... Until: contract the boundary pass by pass (sec. 4).
  detail::Front front (1);
  front[0].closed = loop.closed;
  for (const auto i : surroundings.rim)
  {
    const PointT &p = (*surroundings.cloud)[i];
    front[0].vertices.push_back ({p.getVector3fMap (), p.getNormalVector3fMap ().normalized ()});
  }
  const detail::Front last = contractUntilTermination (sampler, surroundings, std::move (front), scale, report);

  // 4. Is it closed? Where it is not and the fronts stopped by the paper's
  // rule, a part of the hole was abandoned (a front cut where its candidates
  // overshot, typically on rough estimated normals along an edge, while the
  // rest closed elsewhere): contract again from each opening's own boundary.
  detail::Front openings = resumable (checkClosure (surroundings, last, scale, report), scale);
  for (int round = 0; round < detail::kResumeRounds && !openings.empty () && stoppedNaturally (report) &&
                      report.outside_bound == 0;
       ++round)
  {
    detail::Front again;
    for (auto &opening : openings)
    {
      const detail::Front ends = resumeOpening (sampler, surroundings, std::move (opening), scale, report);
      again.insert (again.end (), ends.begin (), ends.end ());
    }
    sampler.setBoundingBall (scale.centre, scale.bound);
    openings = resumable (checkClosure (surroundings, again, scale, report), scale);
    ++report.resumed;
  }
  return surroundings;
}

template <typename PointT> Eigen::Vector3f
HoleFilling<PointT>::surroundingsCentroid (const Surroundings &surroundings)
{
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero ();
  for (std::size_t i = 0; i < surroundings.input_points; ++i)
    centroid += (*surroundings.cloud)[i].getVector3fMap ();
  return centroid / static_cast<float> (std::max<std::size_t> (1, surroundings.input_points));
}

template <typename PointT> void
HoleFilling<PointT>::rimPositionsAndNormals (const Surroundings &surroundings, std::vector<Eigen::Vector3f> &positions,
                                             std::vector<Eigen::Vector3f> &normals)
{
  positions.clear ();
  normals.clear ();
  for (const auto i : surroundings.rim)
  {
    positions.push_back ((*surroundings.cloud)[i].getVector3fMap ());
    normals.push_back ((*surroundings.cloud)[i].getNormalVector3fMap ().normalized ());
  }
}

template <typename PointT> bool
HoleFilling<PointT>::ranAlongWalls (const Surroundings &surroundings, const HoleReport &report)
{
  if (report.outside_bound == 0 && report.beyond_rim == 0)
    return false;  // nothing left the region the rim spans
  const PointCloud &cloud = *surroundings.cloud;
  std::vector<Eigen::Vector3f> rim, filled, filled_normals;
  for (const auto i : surroundings.rim)
    rim.push_back (cloud[i].getVector3fMap ());
  for (std::size_t i = surroundings.input_points; i < cloud.size (); ++i)
  {
    filled.push_back (cloud[i].getVector3fMap ());
    filled_normals.push_back (cloud[i].getNormalVector3fMap ().normalized ());
  }
  const float share = detail::shareAlongWalls (rim, filled), alignment = detail::alignmentWithLoop (rim, filled_normals);
  // Stopped at the rim: the paper's ratio rule ended the fill a few passes
  // up the walls (their candidates dropped beyond the rim), before any got
  // far enough past it to count in the share.
  const bool stopped_at_rim = !report.closed && report.open_diameter >= detail::kStillOpen * report.diameter;
  PCL_DEBUG ("[pcl_holefill::HoleFilling::ranAlongWalls] %zu filled points: %.2f of them along the walls, normals "
             "aligned %.2f with the loop's axis; %s.\n", filled.size (), share, alignment,
             stopped_at_rim ? "stopped at the rim" : "not stopped at the rim");
  return (share > detail::kMinShareAlongWalls || stopped_at_rim) && alignment < detail::kMaxWallAlignment;
}

template <typename PointT> float
HoleFilling<PointT>::turnRimAcrossOpening (Surroundings &surroundings, Eigen::Vector3f &across)
{
  PointCloud &cloud = *surroundings.cloud;
  std::vector<Eigen::Vector3f> positions, normals;
  rimPositionsAndNormals (surroundings, positions, normals);
  across = detail::openingNormal (positions, normals, surroundingsCentroid (surroundings));
  if (across.isZero ())
    return 0.f;
  for (const auto i : surroundings.rim)
    cloud[i].getNormalVector3fMap () = across;
  // A sampled rim is the last row of the walls' samples: up to a pitch or
  // two short of the crease, jagged across the face. On a flat rim the
  // fill's copy of it is moved onto the plane of its outermost points, so
  // that the face lies at the crease and flat, not at the rim's mean
  // height with its jags (a cylinder's cap: 0.8 pitch low, 2 pitches off).
  const float depth = detail::depthAlong (positions, across);
  if (!(depth <= detail::kFlatOpeningDepth * detail::loopDiameter (positions)))
    return depth;
  const float crease = detail::quantileAlong (positions, across, detail::kOpeningCreaseQuantile);
  for (const auto i : surroundings.rim)
    cloud[i].getVector3fMap () += (crease - cloud[i].getVector3fMap ().dot (across)) * across;
  surroundings.search->setInputCloud (surroundings.cloud);
  return 0.f;
}

template <typename PointT> void
HoleFilling<PointT>::fillHoles (const PointCloudConstPtr &working, pcl::search::Search<PointT> &search,
                                const std::vector<BoundaryLoop> &holes, std::vector<PointCloud> &fills)
{
  fills.assign (holes.size (), PointCloud ());
  reports_.assign (holes.size (), HoleReport ());
  const int threads = static_cast<int> (detail::resolveThreadCount (threads_));
  // 1. Each hole's rim and scale. The fill searches the cloud around its
  // hole only: a search over the points near the holes is built in a
  // fraction of the time of one over a million points (ten small holes
  // spent 0.2 s there). A hole whose measuring or surroundings look farther
  // than those points reach is measured again over the whole cloud; the
  // neighbours, and so the output, are the same either way.
  std::vector<pcl::Indices> rims (holes.size ());
  std::vector<HoleScale> scales (holes.size ());
  std::vector<char> usable (holes.size (), 0);
  const auto measure_all = [&] {
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (std::ptrdiff_t h = 0; h < static_cast<std::ptrdiff_t> (holes.size ()); ++h)
    {
      scales[h] = HoleScale ();
      usable[h] = measureHole (*working, search, holes[h], rims[h], scales[h]) ? 1 : 0;
    }
  };
  std::vector<Eigen::Vector4f> reaches;
  const pcl::IndicesPtr near = search_ ? pcl::IndicesPtr () : pointsNearHoles (*working, holes, reaches);
  bool whole = !near;
  if (near)
  {
    search.setInputCloud (working, near);
    measure_all ();
    for (std::size_t h = 0; h < holes.size (); ++h)
    {
      const float looked = (reaches[h].head<3> () - scales[h].centre).norm () + scales[h].searched_reach;
      whole = whole || (usable[h] && !(looked < detail::kNearHolesSafety * reaches[h].w ()));
    }
  }
  if (whole)
  {
    search.setInputCloud (working);
    measure_all ();
  }
  // 2-5. The fills, holes side by side; a single hole gets the threads
  // itself (its candidates are placed side by side within each pass).
  const auto fill_one = [&] (std::size_t h, int threads_of_hole) {
    reports_[h].boundary_points = holes[h].indices.size ();
    reports_[h].boundary = holes[h].indices;
    reports_[h].diameter = holes[h].diameter;
    if (!usable[h])
      PCL_WARN ("[pcl_holefill::%s::fillHoles] A hole has fewer than 3 usable boundary points, or no spacing "
                "around them (duplicates?): skipped.\n", getClassName ().c_str ());
    else
      fillHole (*working, search, holes[h], rims[h], scales[h], fills[h], reports_[h], threads_of_hole);
    reports_[h].points_added = fills[h].size ();
    if (progress_)
    {
#pragma omp critical(pcl_holefill_progress)
      progress_ (h, holes.size (), reports_[h]);
    }
  };
  if (holes.size () == 1)
    fill_one (0, threads);  // outside any parallel region: its own regions reuse the thread pool
  else
  {
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (std::ptrdiff_t h = 0; h < static_cast<std::ptrdiff_t> (holes.size ()); ++h)
      fill_one (static_cast<std::size_t> (h), 1);
  }
  std::size_t next = working->size ();
  for (std::size_t h = 0; h < holes.size (); ++h)
  {
    reports_[h].first_output_index = next;
    next += fills[h].size ();
  }
}

template <typename PointT> void
HoleFilling<PointT>::applyFilter (PointCloud &output)
{
  reports_.clear ();
  if (!inputIsUsable ())
  {
    output.clear ();
    return;
  }
  PointCloudConstPtr given, working;
  prepareClouds (given, working);
  // Detection first, then the search that gathers each hole's surroundings:
  // the two never take memory at the same time.
  SearchPtr search = search_;
  if (!search)
  {
    auto own = pcl::make_shared<VoxelHashSearch<PointT>> (16);
    own->setNumberOfThreads (threads_);
    search = own;
  }
  std::vector<BoundaryLoop> holes;
  if (!collectHoles (working, search, holes))
  {
    output.clear ();
    return;
  }
  if (holes.empty ())
    PCL_DEBUG ("[pcl_holefill::%s::applyFilter] No hole to fill: the output is the input.\n",
               getClassName ().c_str ());
  std::vector<PointCloud> fills;
  if (!holes.empty ())
    fillHoles (working, *search, holes, fills);
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
  detail::reserveTouched (output.points, total, detail::resolveThreadCount (threads_));
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

template <typename PointT> bool
HoleFilling<PointT>::measureRim (const PointCloud &working, pcl::search::Search<PointT> &search,
                                 const pcl::Indices &rim, HoleScale &scale) const
{
  measureRimExtent (working, rim, scale);
  // h, the mean nearest-neighbour distance, sets the reach of the local
  // fits; the pitch, sqrt(area per point), sets the spacing of the fill so
  // that it is as dense as the input (the two differ by 2x on random samples).
  double spacing_sum = 0.0;
  std::vector<float> pitches;
  pcl::Indices found;
  std::vector<float> sqr_distances;
  std::vector<Eigen::Vector3f> positions, normals;
  std::vector<int> ids;
  for (const auto i : rim)
  {
    const int asked = detail::kPitchNeighbours + 1;
    search.nearestKSearch (working[i], asked, found, sqr_distances);
    const float looked = static_cast<int> (found.size ()) < asked
                             ? std::numeric_limits<float>::infinity ()
                             : (working[i].getVector3fMap () - scale.centre).norm () +
                                   std::sqrt (*std::max_element (sqr_distances.begin (), sqr_distances.end ()));
    scale.searched_reach = std::max (scale.searched_reach, looked);
    positions.clear ();
    normals.clear ();
    float nearest = 0.f, farthest = 0.f;
    const Eigen::Vector3f normal = working[i].getNormalVector3fMap ().normalized ();
    for (std::size_t k = 0; k < found.size (); ++k)
    {
      if (!(sqr_distances[k] > 0.f) || !detail::isOrientedPoint (working[found[k]]))
        continue;  // the point itself, duplicates and unusable points say nothing about spacing
      if (detail::onOtherSideOfThinPart (working[found[k]].getVector3fMap () - working[i].getVector3fMap (), normal,
                                         working[found[k]].getNormalVector3fMap ().normalized ()))
        continue;  // the other face of a sheet: not this surface's density
      nearest = positions.empty () ? sqr_distances[k] : std::min (nearest, sqr_distances[k]);
      farthest = std::max (farthest, sqr_distances[k]);
      positions.push_back (working[found[k]].getVector3fMap ());
      normals.push_back (working[found[k]].getNormalVector3fMap ().normalized ());
    }
    if (positions.empty ())
      continue;
    spacing_sum += std::sqrt (nearest);
    ids.resize (positions.size ());
    std::iota (ids.begin (), ids.end (), 0);
    const detail::AngularGap gap = detail::largestAngularGap (working[i].getVector3fMap (), normal, positions.data (),
                                              normals.data (), ids.data (), static_cast<int> (ids.size ()));
    pitches.push_back (detail::samplingPitch (farthest, static_cast<int> (positions.size ()), gap.angle));
  }
  if (pitches.empty () || !(spacing_sum > 0.0))
    return false;
  scale.spacing = static_cast<float> (spacing_sum / pitches.size ());
  std::nth_element (pitches.begin (), pitches.begin () + pitches.size () / 2, pitches.end ());
  scale.pitch = pitches[pitches.size () / 2];
  deriveSizes (scale);
  // gatherSurroundings looks this far too.
  scale.searched_reach = std::max (scale.searched_reach, scale.bound + scale.radius);
  return scale.d_eq > 0.f && std::isfinite (scale.d_eq);
}

template <typename PointT> void
HoleFilling<PointT>::measureRimExtent (const PointCloud &working, const pcl::Indices &rim, HoleScale &scale)
{
  scale.centre.setZero ();
  for (const auto i : rim)
    scale.centre += working[i].getVector3fMap ();
  scale.centre /= static_cast<float> (rim.size ());
  scale.rim_radius = 0.f;
  for (const auto i : rim)
    scale.rim_radius = std::max (scale.rim_radius, (working[i].getVector3fMap () - scale.centre).norm ());
}

template <typename PointT> void
HoleFilling<PointT>::deriveSizes (HoleScale &scale) const
{
  const float h = scale.spacing;
  scale.d_eq = sigma_r_ > 0.f ? detail::ElasticSampler<PointT>::equilibriumDistanceFromSigmaR (sigma_r_)
                              : spacing_factor_ * scale.pitch;
  // r reaches 3.5 pitches at least: on random samples (h = p / 2) 4 h alone
  // is too few neighbours, and a fill of 150 passes drifts off the surface.
  // The combination constraint keeps the reach of 4 h (see setConstraintRadius).
  scale.radius = radius_ > 0.f ? radius_ : std::max ({4.f * h, 3.5f * scale.pitch, 2.5f * scale.d_eq});
  scale.constraint_radius = radius_ > 0.f ? 0.f : std::max (4.f * h, 2.5f * scale.d_eq);
  scale.min_radius = std::max (2.f * h, 1.5f * scale.d_eq);
  scale.bound = detail::kBoundScale * scale.rim_radius + 2.f * scale.d_eq;
  // Fronts move d_eq a pass from every side: about diameter / (2 d_eq)
  // passes close the hole. The automatic bound leaves four times that.
  scale.max_passes = max_passes_ > 0 ? max_passes_
                                     : detail::kAutoPassesSlack +
                                           static_cast<int> (std::ceil (2.f * 2.f * scale.rim_radius / scale.d_eq));
}

template <typename PointT> void
HoleFilling<PointT>::gatherSurroundings (const PointCloud &working, pcl::search::Search<PointT> &search,
                                         const pcl::Indices &rim, const HoleScale &scale,
                                         Surroundings &surroundings) const
{
  surroundings.cloud.reset (new PointCloud);
  PointT centre;
  centre.getVector3fMap () = scale.centre;
  pcl::Indices found;
  std::vector<float> sqr_distances;
  search.radiusSearch (centre, scale.bound + scale.radius, found, sqr_distances);
  std::sort (found.begin (), found.end ());  // a deterministic order, whatever the search
  leaveOutStrayPoints (working, rim, surroundings.threads, found);
  // The local index of found[k] is k: the sorted list itself maps cloud
  // indices to local ones.
  surroundings.cloud->resize (found.size ());
  for (std::size_t k = 0; k < found.size (); ++k)
    (*surroundings.cloud)[k] = working[found[k]];
  surroundings.input_points = surroundings.cloud->size ();
  surroundings.rim.clear ();
  for (const auto i : rim)
  {
    const auto it = std::lower_bound (found.begin (), found.end (), i);
    if (it != found.end () && *it == i)
      surroundings.rim.push_back (static_cast<int> (it - found.begin ()));
  }
  surroundings.search.reset (new VoxelHashSearch<PointT>);
  // The widest frequent query is optimisePosition's, (1 + kGatherSlack) r:
  // it then reads a 3x3x3 block of cells (a 5x5x5 one with cells of r).
  surroundings.search->setCellSize ((1.f + detail::kGatherSlack) * scale.radius);
  surroundings.search->setNumberOfThreads (surroundings.threads);
  surroundings.search->setInputCloud (surroundings.cloud);
}

template <typename PointT> void
HoleFilling<PointT>::leaveOutStrayPoints (const PointCloud &working, const pcl::Indices &rim, int threads,
                                          pcl::Indices &found)
{
  // Judged among the gathered points alone, so that the fill reads nothing
  // beyond them (the search may hold only the points near the holes).
  std::vector<Eigen::Vector3f> positions (found.size ());
  for (std::size_t k = 0; k < found.size (); ++k)
    positions[k] = working[found[k]].getVector3fMap ();
  const std::vector<char> stray = detail::markStrayPoints (positions, threads);
  pcl::Indices sorted_rim (rim);
  std::sort (sorted_rim.begin (), sorted_rim.end ());
  std::size_t kept = 0;
  for (std::size_t k = 0; k < found.size (); ++k)
    if (!stray[k] || std::binary_search (sorted_rim.begin (), sorted_rim.end (), found[k]))
      found[kept++] = found[k];
  if (kept < found.size ())
    PCL_DEBUG ("[pcl_holefill::HoleFilling::leaveOutStrayPoints] %zu stray points left out of the fill's support\n",
               found.size () - kept);
  found.resize (kept);
}

template <typename PointT> typename HoleFilling<PointT>::RimGapLimits
HoleFilling<PointT>::rimGapLimits (const Surroundings &surroundings, const HoleScale &scale, const HoleReport &report,
                                   bool across_opening) const
{
  // Every rim point is asked, also those with fewer than the 5 neighbours
  // RimStatistics::crease_share counts: taken from that share instead, one
  // of the 48 fin corners (random, 20 pitches) lost its widened limits and
  // 18 points of coverage.
  const RimGapLimits strict{detail::kMaxRimGapAlongAxis, detail::kMaxRimGapAlongNormal};
  if (across_opening || !combination_constraint_ ||
      !rimSeesCrease (surroundings, detail::kNoiseReachInSpacings * scale.spacing))
    return strict;
  if (detail::noiseFree (scale.spacing, report.noise))
    return {detail::kMaxRimGapOnCleanCreasedRim, detail::kMaxRimGapOnCleanCreasedRim};
  return report.noise <= detail::kMaxNoiseForWiderAxisLimitInPitches * scale.pitch
             ? RimGapLimits{detail::kMaxRimGapAlongAxisOnNoisyCreasedRim, strict.along_normal}
             : strict;
}

template <typename PointT> void
HoleFilling<PointT>::encloseByRim (detail::ElasticSampler<PointT> &sampler, const Surroundings &surroundings,
                                   const RimGapLimits &limits)
{
  const std::size_t n = surroundings.rim.size ();
  const std::size_t step = detail::outlineStep (n);
  std::vector<Eigen::Vector3f> outline;
  for (std::size_t k = 0; k < n; k += step)
    outline.push_back ((*surroundings.cloud)[surroundings.rim[k]].getVector3fMap ());
  Eigen::Vector3f axis = Eigen::Vector3f::Zero ();
  for (const auto i : surroundings.rim)
    axis += (*surroundings.cloud)[i].getNormalVector3fMap ();
  if (!(axis.norm () > detail::kMinRimAxisStrength * static_cast<float> (n)))
    return;
  sampler.setRim (std::move (outline), axis, limits.along_axis, limits.along_normal);
}

template <typename PointT> void
HoleFilling<PointT>::keepBelowRimPlanes (detail::ElasticSampler<PointT> &sampler, Surroundings &surroundings,
                                         const HoleScale &scale, const HoleReport &report)
{
  // Rim points evenly along the loop, those next to a crease left out:
  // their estimated normals are the least sure, and a plane tilted by a few
  // degrees there cut valid points off a corner (random cubes, PCA normals:
  // 98.8 -> 89.2 % covered).
  const PointCloud &cloud = *surroundings.cloud;
  const std::size_t n = surroundings.rim.size ();
  const std::size_t step = detail::outlineStep (n);
  // A face narrower than the reach (the end of a plate a few pitches
  // thick) has every rim point next to a crease: left out, it held nothing,
  // and the faces beside it grew past it as flat flaps (the corpus's fin,
  // jittered, 0.5 %: max error 0.073). Its points between two creases are
  // kept, if no plane of its own remains and the rim's normals are smooth:
  // estimated ones are tilted next to a crease, and their planes cut valid
  // fill (a hole across a bore's edge from PCA normals: 0.013 -> 0.024).
  const bool smooth_normals = report.normal_spread <= detail::kMaxStripNormalSpread;
  // On a noisy rim a face up to twice the reach wide counts as a strip too:
  // its middle points see one of its creases each, not both, and it gave no
  // plane. It showed once the view along the axis allowed 200 degrees
  // (rimGapLimits): the faces beside it ran past it (a box plate 5.6 pitches
  // thick, jittered, 0.3 %, a corner ball: the top face 5.7 pitches past the
  // corner, 0.0170 -> 0.0349; with this 0.0173). It holds them on noisier
  // rims too, where the axis keeps pi: fin corners, noisy sum of max errors
  // 0.790 -> 0.766 (jittered 0.5 % 0.0364 -> 0.0214). On clean rims the
  // strict rule stays: one corner case with PCA normals lost coverage
  // (99.7 -> 98.5 %).
  const bool one_crease_strips = !detail::noiseFree (scale.spacing, report.noise);
  std::vector<Eigen::Vector3f> points, normals;
  std::vector<int> strip;  // rim points between two creases (or next to one, on a noisy rim)
  pcl::Indices found;
  std::vector<float> sqr_distances;
  for (std::size_t k = 0; k < n; k += step)
  {
    const int i = surroundings.rim[k];
    surroundings.search->radiusSearch (cloud[i], detail::kNoiseReachInSpacings * scale.spacing, found, sqr_distances);
    if (!detail::seesCrease (cloud, i, found))
    {
      points.push_back (cloud[i].getVector3fMap ());
      normals.push_back (cloud[i].getNormalVector3fMap ().normalized ());
    }
    else if (smooth_normals && (one_crease_strips || detail::betweenTwoCreases (cloud, i, found)))
      strip.push_back (i);
  }
  const std::size_t away_from_creases = normals.size ();
  const float same_face = detail::sameFaceCosine ();
  for (const int i : strip)
  {
    const Eigen::Vector3f normal = cloud[i].getNormalVector3fMap ().normalized ();
    if (std::none_of (normals.begin (), normals.begin () + away_from_creases,
                      [&] (const Eigen::Vector3f &m) { return m.dot (normal) > same_face; }))
    {
      points.push_back (cloud[i].getVector3fMap ());
      normals.push_back (normal);
    }
  }
  // Noise moves each rim point, and its plane, off the surface: with 96
  // of them, one lies past 2.5 sigma (the constraint's allowance) on most
  // noisy rims and cut the whole face's fill off (noisy cubes: 100 -> 89 %
  // covered). kRimPlaneNoiseSigmas leaves that to chance. The rim's normal
  // spread and kRimPlaneSlope cover the error of the normals, growing with distance.
  const float tolerance =
      std::max (detail::kToleranceInSpacings * scale.spacing, detail::kRimPlaneNoiseSigmas * report.noise);
  const float slope = detail::kRimPlaneSlope + report.normal_spread;
  holdAtRimSidePlanes (surroundings, tolerance, points, normals);
  std::vector<Eigen::Vector3f> rim_positions;
  for (const auto i : surroundings.rim)
    rim_positions.push_back (cloud[i].getVector3fMap ());
  detail::keepSupportingPlanes (points, normals, rim_positions, tolerance, slope);
  if (!points.empty ())
    sampler.setRimPlanes (std::move (points), std::move (normals), tolerance, slope);
}

template <typename PointT> void
HoleFilling<PointT>::holdAtRimSidePlanes (Surroundings &surroundings, float tolerance,
                                          std::vector<Eigen::Vector3f> &points, std::vector<Eigen::Vector3f> &normals)
{
  PointCloud &cloud = *surroundings.cloud;
  std::vector<Eigen::Vector3f> positions, rim_normals;
  rimPositionsAndNormals (surroundings, positions, rim_normals);
  const std::vector<detail::RimSidePlane> sides = detail::findRimSidePlanes (positions, rim_normals, tolerance);
  for (const auto &side : sides)
  {
    points.push_back (side.point);
    normals.push_back (side.normal);
    // The rim points on the taken face carry the face beside's normal: in
    // the fill's copy they take the taken face's, so that their fronts run
    // down it (fandisk's vertices: 63 -> 77 % covered; held by the plane
    // alone, their fronts had nowhere to go and the fill stopped at 26 %).
    if (side.turns_rim)
      for (const int q : side.on)
        cloud[surroundings.rim[q]].getNormalVector3fMap () = side.normal;
  }
  if (!sides.empty ())
    PCL_DEBUG ("[pcl_holefill::HoleFilling::holdAtRimSidePlanes] %zu side planes of the rim.\n", sides.size ());
}

template <typename PointT> void
HoleFilling<PointT>::keepFacesApartAtCreases (detail::ElasticSampler<PointT> &sampler,
                                              const Surroundings &surroundings, const HoleScale &scale,
                                              const HoleReport &report)
{
  std::vector<Eigen::Vector3f> positions, normals;
  rimPositionsAndNormals (surroundings, positions, normals);
  // The chord misses a curved crease by its sagitta and the crossings lie
  // within a spacing of the crease: half d_eq of slack, more with noise.
  sampler.setCreaseChords (detail::findCreaseChords (positions, normals, scale.spacing),
                           std::max (detail::kCreaseChordToleranceInDeq * scale.d_eq,
                                     detail::constraintTolerance (scale.spacing, report.noise)));
}

template <typename PointT> void
HoleFilling<PointT>::setUpSampler (detail::ElasticSampler<PointT> &sampler, const Surroundings &surroundings,
                                   const HoleScale &scale, HoleReport &report) const
{
  const float h = scale.spacing;
  sampler.setInputCloud (surroundings.cloud);
  sampler.setSearchMethod (surroundings.search);
  sampler.setEquilibriumDistance (scale.d_eq);
  const detail::RimStatistics rim = detail::measureRimStatistics (
      *surroundings.cloud, *surroundings.search, surroundings.rim, detail::kNoiseReachInSpacings * h);
  report.normal_spread = rim.normal_spread;
  // Automatic sigma_n: g2 must tell a crease from what the normals do on one
  // smooth piece (its curvature, the noise of estimated normals). Narrower
  // than that, g2 starves eq. (1) of neighbours on curved or noisy rims and
  // the patch follows the noise; wider, creases round off.
  report.sigma_n = sigma_n_ > 0.f ? sigma_n_
                                  : std::clamp (detail::kSigmaNPerNormalSpread * report.normal_spread,
                                                detail::kSharpSigmaN, detail::kMaxAutoSigmaN);
  sampler.setSigmaN (report.sigma_n);
  // The first-order extension extrapolates the rim's curvature from its
  // normals: where they are noisy (estimated from noisy points) it
  // extrapolates the noise, and the patch runs away. Noisy points with good
  // normals keep it: without it a sphere cap came out flat (max error 0.02,
  // the cap's sagitta, at noise 0.1 % of the diagonal; now 0.0011-0.0016).
  report.first_order =
      first_order_ && (report.noise <= detail::kFirstOrderMaxNoiseInSpacings * h || rim.normalsAreLinear ());
  sampler.setFirstOrder (report.first_order);
  sampler.setConstraintTolerance (detail::constraintTolerance (h, report.noise));
  sampler.setCurvatureSignTolerance (
      std::max (detail::kToleranceInSpacings * h, detail::kSignToleranceInNoiseSigmas * report.noise));
  // A reference point's tangent plane is only as good as its normal. PCA
  // normals near a crease are tilted towards the other face, and a sample on
  // the true face, d away, then lies d sin(tilt) past that plane: the
  // tolerance grows with d by the rim's normal spread (an angle, ~0 for exact
  // normals on flat faces). Not on noisy rims, where the spread is the noise
  // of the normals and the noise tolerance above already applies.
  sampler.setConstraintSlope (report.first_order ? detail::kSlopePerNormalSpread * report.normal_spread : 0.f);
  sampler.setCombinationConstraint (combination_constraint_);
  // Clean rims only: at 0.3 / 0.5 % noise the labels of half neighbourhoods
  // raised the corpus's sums of max errors by 5-6 % (doc/parameters.md, "A
  // wall between two faces").
  sampler.setSignTowardsFront (detail::noiseFree (h, report.noise));
  sampler.setConstraintRadius (scale.constraint_radius);
  sampler.setBoundingBall (scale.centre, scale.bound);
}

template <typename PointT> detail::Front
HoleFilling<PointT>::resumeOpening (detail::ElasticSampler<PointT> &sampler, Surroundings &surroundings,
                                    detail::FrontChain opening, const HoleScale &scale, HoleReport &report) const
{
  // The fill of an opening closes in on it: pass k stays inside the ball
  // around the opening's boundary shrunk by k d_eq / 2 (fronts move in by
  // d_eq a pass), within twice the passes that close it from all sides. A
  // front that does not close in (one face's front running past an edge
  // whose other face has no fill yet, the apex of a corner) is cut there,
  // not counted as a runaway.
  std::vector<Eigen::Vector3f> positions;
  Eigen::Vector3f centre = Eigen::Vector3f::Zero ();
  for (const auto &v : opening.vertices)
  {
    positions.push_back (v.position);
    centre += v.position;
  }
  centre /= static_cast<float> (std::max<std::size_t> (1, positions.size ()));
  float radius = 0.f;
  for (const auto &p : positions)
    radius = std::max (radius, (p - centre).norm ());
  const int budget = 2 * static_cast<int> (std::ceil (detail::loopDiameter (positions) / (2.f * scale.d_eq))) + 2;
  const std::size_t outside_before = report.outside_bound;
  detail::Front ends{std::move (opening)};
  for (int pass = 0; pass < budget; ++pass)
  {
    const float ball = radius + scale.d_eq - 0.5f * static_cast<float> (pass) * scale.d_eq;
    if (!(ball > 0.f))
      break;
    sampler.setBoundingBall (centre, ball);
    ends = contractUntilTermination (sampler, surroundings, std::move (ends), scale, report, 1);
    if (report.termination != Termination::kPassLimit || report.passes >= static_cast<unsigned> (scale.max_passes))
      break;
  }
  report.outside_bound = outside_before;
  return ends;
}

template <typename PointT> bool
HoleFilling<PointT>::stoppedNaturally (const HoleReport &report)
{
  return report.termination == Termination::kControlRatio || report.termination == Termination::kNoNewBoundary;
}

template <typename PointT> Termination
HoleFilling<PointT>::terminationOf (const detail::ContractionStats &stats, const detail::Front &next, int pass,
                                    float first_length, unsigned passes_done, int max_passes) const
{
  if (detail::frontSize (next) < detail::kMinFrontPoints)
    return Termination::kNoNewBoundary;
  const float ratio = stats.former_boundary_points > 0
                          ? static_cast<float> (stats.kept_control_points) / stats.former_boundary_points
                          : 0.f;
  if (ratio < termination_ratio_)
    return Termination::kControlRatio;
  if (pass > 0 && detail::frontLength (next) > max_growth_ * first_length)
    return Termination::kDiverging;
  if (passes_done >= static_cast<unsigned> (max_passes))
    return Termination::kPassLimit;
  return Termination::kNotStarted;  // not yet: go on
}

template <typename PointT> detail::Front
HoleFilling<PointT>::contractUntilTermination (detail::ElasticSampler<PointT> &sampler, Surroundings &surroundings,
                                               detail::Front front, const HoleScale &scale, HoleReport &report,
                                               int pass_budget) const
{
  // Growth is measured against the first contracted boundary, which is
  // sampled like every later one (the input rim is jagged, hence longer).
  float first_length = 0.f;
  float pass_radius = scale.radius;
  detail::Front next;
  report.termination = Termination::kPassLimit;
  for (int pass = 0; pass < pass_budget && report.passes < static_cast<unsigned> (scale.max_passes); ++pass)
  {
    sampler.setRadius (pass_radius);
    sampler.setSigmaD (sigma_d_ > 0.f ? sigma_d_ : 0.5f * pass_radius);
    detail::ContractionStats stats;
    if (!sampler.contract (front, next, stats))
    {
      report.termination = Termination::kNotStarted;
      next.clear ();
      break;
    }
    ++report.passes;
    report.outside_bound += stats.outside_bound;
    report.beyond_rim += stats.beyond_rim;
    PCL_DEBUG ("[pcl_holefill::%s::contractUntilTermination] pass %d: |B'| %zu, kept %zu, repelled %zu, on "
               "surface %zu, overshoot %zu, unsupported %zu, outside %zu, beyond rim %zu, |B| %zu\n",
               getClassName ().c_str (), pass, stats.former_boundary_points, stats.kept_control_points,
               stats.repelled, stats.too_close, stats.rejected_by_constraint, stats.unsupported,
               stats.outside_bound, stats.beyond_rim, stats.samples);
    // B joins the surface: other fields from the nearest known point.
    std::vector<detail::FrontVertex> joining;
    for (const auto &chain : next)
      joining.insert (joining.end (), chain.vertices.begin (), chain.vertices.end ());
    std::vector<PointT, Eigen::aligned_allocator<PointT>> joined (joining.size ());
#pragma omp parallel for num_threads(surroundings.threads) schedule(dynamic, 64)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t> (joining.size ()); ++k)
    {
      PointT query;
      query.getVector3fMap () = joining[k].position;
      pcl::Indices nearest;
      std::vector<float> nearest_sqr;
      surroundings.search->nearestKSearch (query, 1, nearest, nearest_sqr);
      joined[k] = nearest.empty () ? query : (*surroundings.cloud)[nearest[0]];
      joined[k].getVector3fMap () = joining[k].position;
      joined[k].getNormalVector3fMap () = joining[k].normal;
    }
    surroundings.cloud->insert (surroundings.cloud->end (), joined.begin (), joined.end ());
    surroundings.search->indexNewPoints ();
    if (pass == 0)
      first_length = detail::frontLength (next);
    const Termination end = terminationOf (stats, next, pass, first_length, report.passes, scale.max_passes);
    if (end != Termination::kNotStarted)
    {
      report.termination = end;
      break;
    }
    front.swap (next);
    next.clear ();
    pass_radius = std::max (scale.min_radius, pass_radius / shrink_);
  }
  // Where the fill stopped: the last boundary and what grew from it.
  front.insert (front.end (), next.begin (), next.end ());
  return front;
}

template <typename PointT> detail::Front
HoleFilling<PointT>::checkClosure (const Surroundings &surroundings, const detail::Front &last_front,
                                   const HoleScale &scale, HoleReport &report) const
{
  // The boundary where the fill stopped, and every filled point: a gap left
  // early (between the rim and the first pass, or where a front was cut)
  // lies next to filled points too.
  std::vector<detail::FrontVertex> tested;
  for (const auto &chain : last_front)
    tested.insert (tested.end (), chain.vertices.begin (), chain.vertices.end ());
  for (std::size_t i = surroundings.input_points; i < surroundings.cloud->size (); ++i)
  {
    const PointT &p = (*surroundings.cloud)[i];
    tested.push_back ({p.getVector3fMap (), p.getNormalVector3fMap ().normalized ()});
  }
  // Where an empty disc of kOpenDiscInSpacings d_eq touches them, the fronts have not met.
  const float diameter = detail::kOpenDiscInSpacings * scale.d_eq;
  std::vector<char> is_open (tested.size (), 0);
  std::vector<Eigen::Vector3f> gap_of (tested.size ());
#pragma omp parallel for num_threads(surroundings.threads) schedule(dynamic, 64)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (tested.size ()); ++i)
    is_open[i] = emptyDiscAt (surroundings, tested[i], diameter, gap_of[i]) ? 1 : 0;
  std::vector<Eigen::Vector3f> open, open_normals, open_gaps;
  for (std::size_t i = 0; i < tested.size (); ++i)
    if (is_open[i])
    {
      open.push_back (tested[i].position);
      open_normals.push_back (tested[i].normal);
      open_gaps.push_back (gap_of[i]);
    }
  // The open points, chained into the loops around each opening. An opening
  // shows on several points spread over more than the disc's radius; a tight
  // group of a few is the apex of a convex corner, whose faces, unfolded into
  // one plane, always leave an empty wedge.
  const auto loops = detail::traceBoundaryLoops (open, open_normals, open_gaps, diameter,
                                         static_cast<int> (detail::kMinOpenPoints));
  detail::Front openings;
  report.open_points = 0;
  report.open_diameter = 0.f;
  for (const auto &loop : loops)
  {
    detail::FrontChain chain;
    chain.closed = loop.closed;
    std::vector<Eigen::Vector3f> positions;
    for (const int m : loop.members)
    {
      chain.vertices.push_back ({open[m], open_normals[m]});
      positions.push_back (open[m]);
    }
    const float spread = detail::loopDiameter (positions);
    if (spread < 0.5f * diameter)
      continue;
    report.open_points += chain.vertices.size ();
    report.open_diameter = std::max (report.open_diameter, spread);
    openings.push_back (std::move (chain));
  }
  report.closed = openings.empty () && report.termination != Termination::kNotStarted;
  return openings;
}

template <typename PointT> detail::Front
HoleFilling<PointT>::resumable (const detail::Front &openings, const HoleScale &scale)
{
  // Only openings inside the rim whose boundary normals stay within
  // kResumeMinNormalCosine of their mean. Openings across an edge or a corner
  // qualify: by the time they are taken up both faces around them are filled,
  // so the combination constraint has both sides, and the shrinking ball of
  // resumeOpening bounds the rest. Normals turning further are rough or
  // misoriented, and a front along them ran past the edge (a cube corner on
  // random samples with PCA normals and 0.1 % noise: 0.031 off).
  //
  // The mean leans towards the face that gives more boundary points: a strip
  // left along a bore's edge (9 points on the bottom face, 4 on the wall)
  // had its mean 67 degrees from the wall's normals, and was not taken up.
  // An opening up to the rim's radius across is such a strip, and the
  // narrowest cone around its normals decides (45 degrees there). A wider
  // one is most of the hole left unfilled: contracted again it met the same
  // stops and ran further (fandisk's vertices, 4 faces round an opening as
  // wide as the hole, 78 degrees from their mean: 44 points past the ball,
  // 6.8 -> 8.7 h off), and the mean keeps deciding.
  detail::Front kept;
  for (const auto &chain : openings)
  {
    bool inside = true;
    std::vector<Eigen::Vector3f> positions, normals;
    for (const auto &v : chain.vertices)
    {
      inside = inside && (v.position - scale.centre).norm () <= scale.rim_radius;
      positions.push_back (v.position);
      normals.push_back (v.normal);
    }
    const bool strip = detail::loopDiameter (positions) <= scale.rim_radius;
    const int steps = strip ? detail::kConeSearchSteps : 1;  // 1: the cone around the mean
    if (inside && !normals.empty () &&
        detail::narrowestConeCosine (normals, steps) >= detail::kResumeMinNormalCosine)
      kept.push_back (chain);
  }
  return kept;
}

template <typename PointT> bool
HoleFilling<PointT>::emptyDiscAt (const Surroundings &surroundings, const detail::FrontVertex &v, float diameter,
                                  Eigen::Vector3f &gap_direction) const
{
  thread_local std::vector<Eigen::Vector3f> positions, normals;
  thread_local std::vector<int> ids, near;
  pcl::Indices found;
  std::vector<float> sqr_distances;
  PointT query;
  query.getVector3fMap () = v.position;
  surroundings.search->radiusSearch (query, diameter, found, sqr_distances);
  positions.clear ();
  normals.clear ();
  near.clear ();
  const float sqr_radius = 0.25f * diameter * diameter;
  for (std::size_t k = 0; k < found.size (); ++k)
    if (sqr_distances[k] > 0.f)
    {
      if (sqr_distances[k] <= sqr_radius)
        near.push_back (static_cast<int> (positions.size ()));
      positions.push_back ((*surroundings.cloud)[found[k]].getVector3fMap ());
      normals.push_back ((*surroundings.cloud)[found[k]].getNormalVector3fMap ().normalized ());
    }
  ids.resize (positions.size ());
  std::iota (ids.begin (), ids.end (), 0);
  const int count = static_cast<int> (ids.size ());
  // The gap gates the disc. Beside an edge, the other face's points at the
  // disc's far reach, unfolded across it, close the gap of a strip left
  // along the edge (to 85 degrees on a bored cube, 3 pitches wide: never
  // tried); the neighbours within the disc's radius leave it open. Next to
  // a corner all of them decide: unfolding three faces into one plane
  // leaves an empty wedge near the apex that the near ones do not cover
  // (15 fin corners reported open, covered to 99-100 %).
  const bool one_edge = detail::besideOneOtherFace (v.normal, normals.data (), ids.data (), count);
  const std::vector<int> &gap_ids = one_edge ? near : ids;
  const detail::AngularGap gap = detail::largestAngularGap (v.position, v.normal, positions.data (), normals.data (),
                                                            gap_ids.data (), static_cast<int> (gap_ids.size ()));
  gap_direction = gap.direction;
  return gap.angle > static_cast<float> (M_PI / 2.0) &&
         detail::emptyDiscTouches (v.position, v.normal, gap, positions.data (), normals.data (), ids.data (), count,
                           diameter, detail::kOpenDiscFill * 0.5f * diameter);
}

template <typename PointT> float
HoleFilling<PointT>::discsCovered (const BoundaryLoop &loop, const HoleScale &scale, std::size_t added)
{
  // Each filled point stands for about d_eq^2 of surface.
  const float patch_area = static_cast<float> (added) * scale.d_eq * scale.d_eq;
  const float rim_disc = static_cast<float> (M_PI) * 0.25f * loop.diameter * loop.diameter;
  return rim_disc > 0.f ? patch_area / rim_disc : 0.f;
}

template <typename PointT> bool
HoleFilling<PointT>::grewPastHole (const BoundaryLoop &loop, const HoleScale &scale, std::size_t added,
                                   const HoleReport &report)
{
  if (report.closed || !(report.open_diameter >= detail::kNotClosedIn * loop.diameter) ||
      !(loop.diameter >= detail::kMinWidthToJudge * scale.d_eq))
    return false;
  const float open = report.open_diameter / loop.diameter;
  const float hemisphere_band = 2.f * std::sqrt (std::max (0.f, 1.f - open * open));
  return discsCovered (loop, scale, added) > detail::kBandMargin * hemisphere_band;
}

template <typename PointT> void
HoleFilling<PointT>::warnAbout (const BoundaryLoop &loop, const HoleScale &scale, std::size_t added,
                                const HoleReport &report) const
{
  const float discs = discsCovered (loop, scale, added);
  if (report.closed && discs > detail::kMaxAreaOverRimDisc)
    PCL_WARN ("[pcl_holefill::%s::fillHole] A hole of diameter %g needed a patch %.1f times the disc on its rim: "
              "more than half of the shape may be missing there, and the patch is a guess.\n",
              getClassName ().c_str (), loop.diameter, discs);
  if (report.withdrawn)
  {
    PCL_WARN ("[pcl_holefill::%s::fillHole] The fill of a hole of diameter %g covered %.1f times the disc on its "
              "rim but left an opening of %g: it grew past the hole (the hidden side of a single view, an open "
              "tube?), so none of its %zu points were added.\n",
              getClassName ().c_str (), loop.diameter, discs, report.open_diameter, added);
    return;
  }
  if (report.outside_bound > 0)
    PCL_WARN ("[pcl_holefill::%s::fillHole] The fill of a hole of diameter %g reached the region its rim can span "
              "(%zu samples stopped there): the patch may be growing away from the surface.\n",
              getClassName ().c_str (), loop.diameter, report.outside_bound);
  if (!report.closed)
    PCL_WARN ("[pcl_holefill::%s::fillHole] A hole of diameter %g is not closed after %u passes (%s): an opening "
              "of about %g is left (%zu boundary points)%s.\n",
              getClassName ().c_str (), loop.diameter, report.passes, toString (report.termination),
              report.open_diameter, report.open_points,
              report.beyond_rim > 0 ? "; samples beyond its rim were dropped (is the loop a border?)" : "");
}

template <typename PointT> std::size_t
HoleFilling<PointT>::removeRimNormalBias (Surroundings &surroundings, const HoleScale &scale, int neighbours,
                                          bool one_piece, float tolerance) const
{
  PointCloud &cloud = *surroundings.cloud;
  // The points whose neighbourhoods the hole makes one-sided: those near the rim.
  const float reach = detail::kRimBiasReachInPitches * scale.pitch;
  const std::vector<char> near_rim = markNearRim (surroundings, reach, reach);
  const auto n = static_cast<std::ptrdiff_t> (surroundings.input_points);
  std::vector<Eigen::Vector3f> refitted (n);
  std::vector<char> changed (n, 0);
  forEachMarked (surroundings, near_rim, neighbours, [&] (std::ptrdiff_t i, const pcl::Indices &nearest,
                                                          const std::vector<Eigen::Vector3f> &positions) {
    if (!one_piece && detail::seesCrease (cloud, static_cast<int> (i), nearest))
      return;  // one smooth piece only: creases are refitCreaseNormals' work
    const Eigen::Vector3f own = cloud[i].getNormalVector3fMap ().normalized ();
    refitted[i] = detail::quadricNormal (cloud[i].getVector3fMap (), own, positions.data (),
                                         static_cast<int> (positions.size ()), tolerance);
    changed[i] = refitted[i] != own ? 1 : 0;
  });
  return detail::writeNormals (refitted, changed, cloud);
}

template <typename PointT> bool
HoleFilling<PointT>::rimSeesCrease (const Surroundings &surroundings, float reach)
{
  const PointCloud &cloud = *surroundings.cloud;
  pcl::Indices found;
  std::vector<float> sqr_distances;
  return std::any_of (surroundings.rim.begin (), surroundings.rim.end (), [&] (int i) {
    surroundings.search->radiusSearch (cloud[i], reach, found, sqr_distances);
    return detail::seesCrease (cloud, i, found);
  });
}

template <typename PointT> std::size_t
HoleFilling<PointT>::refitNormals (Surroundings &surroundings, const HoleScale &scale, float noise) const
{
  bool rough = false;
  const bool noisy = noise > detail::kRimBiasMaxNoiseInSpacings * scale.spacing;
  const std::size_t smoothed = noisy ? smoothNoisyNormals (surroundings, scale, noise, rough) : 0;
  // Blended across a crease, PCA normals round the edges off; fitted to
  // one-sided neighbourhoods, they tilt away from the hole.
  const float tolerance = detail::constraintTolerance (scale.spacing, noise);
  const bool crease_refit = tolerance <= detail::kRefitMaxToleranceInPitches * scale.pitch;
  const std::size_t creases = crease_refit ? refitCreaseNormals (surroundings, scale, tolerance) : 0;
  // A smoothed rim with no crease refitted is one smooth piece (the wide
  // fits' residuals showed no crease): the quadric then needs no crease
  // test, which on the noisy normals beyond the smoothed band would see
  // creases everywhere and refit nothing; and it runs at any noise, since
  // its tilt (~1.6 degrees at 0.1 % noise) grows into a fill riding above
  // a large hole (a cap 110 pitches across: 55-69 % covered).
  const bool one_piece = smoothed > 0 && creases == 0;
  std::size_t tilts = 0;
  if (one_piece)
    tilts = removeRimNormalBias (surroundings, scale, detail::smoothRimQuadricNeighbours (noise, scale.spacing), true,
                                 tolerance);
  else if (crease_refit && (!noisy || rough))
    tilts = removeRimNormalBias (surroundings, scale, detail::quadricNeighbours (noise, scale.spacing), false,
                                 tolerance);
  return smoothed + creases + tilts;
}

template <typename PointT>
template <typename Visit>
void
HoleFilling<PointT>::forEachMarked (const Surroundings &surroundings, const std::vector<char> &marked, int k,
                                    Visit &&visit)
{
  const PointCloud &cloud = *surroundings.cloud;
  const auto n = static_cast<std::ptrdiff_t> (surroundings.input_points);
#pragma omp parallel for num_threads(surroundings.threads) schedule(dynamic, 64)
  for (std::ptrdiff_t i = 0; i < n; ++i)
  {
    if (!marked[i] || !detail::isOrientedPoint (cloud[i]))
      continue;
    thread_local std::vector<Eigen::Vector3f> positions;
    thread_local pcl::Indices nearest;
    nearestInputPoints (surroundings, i, k, nearest, positions);
    visit (i, nearest, positions);
  }
}

template <typename PointT> void
HoleFilling<PointT>::nearestInputPoints (const Surroundings &surroundings, std::ptrdiff_t i, int k,
                                         pcl::Indices &nearest, std::vector<Eigen::Vector3f> &positions)
{
  const PointCloud &cloud = *surroundings.cloud;
  std::vector<float> sqr_distances;
  surroundings.search->nearestKSearch (cloud[i], k, nearest, sqr_distances);
  positions.clear ();
  for (const auto q : nearest)
    if (static_cast<std::size_t> (q) < surroundings.input_points && detail::isOrientedPoint (cloud[q]))
      positions.push_back (cloud[q].getVector3fMap ());
}

template <typename PointT> std::vector<char>
HoleFilling<PointT>::markNearRim (Surroundings &surroundings, float reach, float core_reach)
{
  const PointCloud &cloud = *surroundings.cloud;
  std::vector<char> near_rim (surroundings.input_points, 0);
  pcl::Indices found;
  std::vector<float> sqr_distances;
  for (const auto i : surroundings.rim)
  {
    surroundings.search->radiusSearch (cloud[i], reach, found, sqr_distances);
    for (std::size_t f = 0; f < found.size (); ++f)
      if (static_cast<std::size_t> (found[f]) < surroundings.input_points)
      {
        const char mark = sqr_distances[f] <= core_reach * core_reach ? 2 : 1;
        near_rim[found[f]] = std::max (near_rim[found[f]], mark);
      }
  }
  return near_rim;
}

template <typename PointT> std::size_t
HoleFilling<PointT>::smoothNoisyNormals (Surroundings &surroundings, const HoleScale &scale, float noise,
                                         bool &rough) const
{
  rough = false;
  const int k = detail::wideNeighbours (noise, scale.spacing);
  const float reach = detail::kNoisyRimReachInPitches * scale.pitch;
  // 2: within reach, to refit; 1: read by their fits, ~sqrt(k) spacings further.
  const std::vector<char> fitted =
      markNearRim (surroundings, reach + std::sqrt (static_cast<float> (k)) * scale.spacing, reach);
  PointCloud &cloud = *surroundings.cloud;
  const auto n = static_cast<std::ptrdiff_t> (surroundings.input_points);
  std::vector<Eigen::Vector3f> own (n, Eigen::Vector3f::Zero ()), wide (n, Eigen::Vector3f::Zero ());
  std::vector<float> residual (n, 0.f);
  std::vector<std::vector<int>> nearest_few (n);
  std::vector<char> use (n, 0);
  forEachMarked (surroundings, fitted, k, [&] (std::ptrdiff_t i, const pcl::Indices &nearest,
                                               const std::vector<Eigen::Vector3f> &positions) {
    if (positions.size () < detail::kMinWideNeighbours)
      return;
    const detail::PlaneFit plane = detail::fitPlane (positions.data (), static_cast<int> (positions.size ()));
    own[i] = cloud[i].getNormalVector3fMap ().normalized ();
    wide[i] = plane.normal.dot (own[i]) < 0.f ? Eigen::Vector3f (-plane.normal) : plane.normal;
    residual[i] = plane.residual;
    const auto few = std::min<std::size_t> (nearest.size (), detail::kRoughnessNeighbours);
    nearest_few[i].assign (nearest.begin (), nearest.begin () + static_cast<std::ptrdiff_t> (few));
    use[i] = fitted[i] == 2 ? 1 : 0;
  });
  // Only where the given normals are rougher than the wide fit: exact
  // normals of noisy points are smooth already, and a fit would add its own
  // noise and tilt to them.
  rough = detail::normalRoughness (wide, nearest_few, use) <
          detail::kRougherBy * detail::normalRoughness (own, nearest_few, use);
  if (!rough)
    return 0;
  // A wide plane straddling a crease fits no face: its residual exceeds
  // the noise's. Creased rims keep their normals for refitCreaseNormals.
  std::size_t fits = 0, creased = 0;
  for (std::ptrdiff_t i = 0; i < n; ++i)
    if (use[i])
    {
      ++fits;
      creased += residual[i] > detail::kCreaseResidualInNoiseVariances * noise * noise ? 1 : 0;
    }
  if (static_cast<float> (creased) > detail::kMaxCreasedShare * static_cast<float> (fits))
    return 0;
  return detail::writeNormals (wide, use, cloud);
}

template <typename PointT> std::size_t
HoleFilling<PointT>::refitCreaseNormals (Surroundings &surroundings, const HoleScale &scale, float tolerance) const
{
  // The plane test counts neighbours within the combination constraint's
  // tolerance (the same allowance for noise) over ~3 pitches (6 h): a
  // plane of a face must hold points beyond the ~2-pitch band of blended
  // normals along the edge.
  const float reach = detail::kCreaseReachInSpacings * scale.spacing;
  if (!rimSeesCrease (surroundings, reach))
    return 0;  // a smooth rim: nothing blended for the fill to continue
  PointCloud &cloud = *surroundings.cloud;
  const auto n = static_cast<std::ptrdiff_t> (surroundings.input_points);
  std::vector<Eigen::Vector3f> refitted (n);
  std::vector<char> changed (n, 0);
#pragma omp parallel for num_threads(surroundings.threads) schedule(dynamic, 64)
  for (std::ptrdiff_t i = 0; i < n; ++i)
  {
    if (!detail::isOrientedPoint (cloud[i]))
      continue;
    thread_local std::vector<Eigen::Vector3f> positions, normals;
    pcl::Indices near;
    std::vector<float> near_sqr_distances;
    surroundings.search->radiusSearch (cloud[i], reach, near, near_sqr_distances);
    positions.clear ();
    normals.clear ();
    for (const auto q : near)
      if (detail::isOrientedPoint (cloud[q]))
      {
        positions.push_back (cloud[q].getVector3fMap ());
        normals.push_back (cloud[q].getNormalVector3fMap ().normalized ());
      }
    changed[i] = detail::refitCreaseNormal (cloud[i].getVector3fMap (), cloud[i].getNormalVector3fMap ().normalized (),
                                            positions.data (), normals.data (), static_cast<int> (positions.size ()),
                                            tolerance, refitted[i]);
  }
  return detail::writeNormals (refitted, changed, cloud);
}

template <typename PointT> pcl::Indices
HoleFilling<PointT>::usableRim (const PointCloud &working, const BoundaryLoop &loop)
{
  pcl::Indices rim;
  for (const auto i : loop.indices)
    if (i >= 0 && static_cast<std::size_t> (i) < working.size () && detail::isOrientedPoint (working[i]))
      rim.push_back (i);
  return rim;
}

template <typename PointT> Eigen::Vector4f
HoleFilling<PointT>::estimatedReach (const PointCloud &working, const BoundaryLoop &loop) const
{
  // measureRim's centre and rim radius; its spacing and pitch as the
  // detection measured them, times a margin; what they set, as measureRim sets it.
  const pcl::Indices rim = usableRim (working, loop);
  if (rim.empty () || !(loop.pitch > 0.f) || !(loop.mean_spacing > 0.f))
    return Eigen::Vector4f::Zero ();  // given loops carry no pitch
  HoleScale scale;
  measureRimExtent (working, rim, scale);
  scale.spacing = detail::kNearHolesMargin * loop.mean_spacing;
  scale.pitch = detail::kNearHolesMargin * loop.pitch;
  deriveSizes (scale);
  return {scale.centre.x (), scale.centre.y (), scale.centre.z (), scale.bound + scale.radius};
}

template <typename PointT> pcl::IndicesPtr
HoleFilling<PointT>::pointsNearHoles (const PointCloud &working, const std::vector<BoundaryLoop> &holes,
                                      std::vector<Eigen::Vector4f> &reaches) const
{
  reaches.clear ();
  if (holes.size () > detail::kMaxHolesSearchedApart)
    return pcl::IndicesPtr ();
  for (const auto &loop : holes)
  {
    reaches.push_back (estimatedReach (working, loop));
    if (!(reaches.back ().w () > 0.f))
      return pcl::IndicesPtr ();
  }
  std::vector<char> near (working.size (), 0);
#pragma omp parallel for num_threads(detail::resolveThreadCount (threads_)) schedule(static)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (working.size ()); ++i)
    for (const auto &ball : reaches)
      if ((working[i].getVector3fMap () - ball.head<3> ()).squaredNorm () <= ball.w () * ball.w ())
      {
        near[i] = 1;
        break;
      }
  auto indices = pcl::make_shared<pcl::Indices> ();
  for (std::size_t i = 0; i < near.size (); ++i)
    if (near[i])
      indices->push_back (static_cast<pcl::index_t> (i));
  // Most of the cloud: the whole cloud's search costs no more.
  if (indices->size () > working.size () / 2)
    return pcl::IndicesPtr ();
  return indices;
}

template <typename PointT> bool
HoleFilling<PointT>::measureHole (const PointCloud &working, pcl::search::Search<PointT> &search,
                                  const BoundaryLoop &loop, pcl::Indices &rim, HoleScale &scale) const
{
  rim = usableRim (working, loop);
  return rim.size () >= 3 && measureRim (working, search, rim, scale);
}

template <typename PointT> void
HoleFilling<PointT>::fillHole (const PointCloud &working, pcl::search::Search<PointT> &search,
                               const BoundaryLoop &loop, const pcl::Indices &rim, const HoleScale &scale,
                               PointCloud &filled, HoleReport &report, int threads) const
{
  filled.clear ();
  report.centre = scale.centre;
  report.spacing = scale.spacing;
  report.pitch = scale.pitch;
  report.equilibrium_distance = scale.d_eq;
  report.radius = scale.radius;

  // 2-4. The surroundings, the passes, the closure check.
  const HoleReport measured = report;
  Surroundings surroundings = contractHole (working, search, loop, rim, scale, report, threads, false);
  // 5. An opening (detail/opening.h): the fronts ran off along its walls,
  // or set out along them and were stopped at the rim.
  // Across it instead, if that leaves less of it open.
  if (loop.closed && ranAlongWalls (surroundings, report))
  {
    HoleReport across = measured;
    across.across_opening = true;
    Surroundings capped = contractHole (working, search, loop, rim, scale, across, threads, true);
    PCL_DEBUG ("[pcl_holefill::%s::fillHole] Across the opening: %u passes, %s, %zu outside the bound, an "
               "opening of %g left (along the walls: %g).\n", getClassName ().c_str (), across.passes,
               across.closed ? "closed" : "open", across.outside_bound, across.open_diameter, report.open_diameter);
    if (across.outside_bound == 0 && (across.closed || across.open_diameter < report.open_diameter))
    {
      report = across;
      surroundings = std::move (capped);
    }
  }
  const std::size_t added = surroundings.cloud->size () - surroundings.input_points;
  report.withdrawn = grewPastHole (loop, scale, added, report);
  warnAbout (loop, scale, added, report);
  if (report.withdrawn)
    return;
  for (std::size_t i = surroundings.input_points; i < surroundings.cloud->size (); ++i)
    filled.push_back ((*surroundings.cloud)[i]);
}

}  // namespace pcl_holefill

#define PCL_INSTANTIATE_HoleFilling(T) template class pcl_holefill::HoleFilling<T>;
