/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 *
 * A slice of the robustness corpus (test/corpus): every sampling at least
 * once, clean and noisy, exact and estimated normals, hole-free clouds.
 * Ground truth is the model's exact surface and the balls that were cut,
 * never a figure the code under test computed. Bounds are what the code
 * reached on these seeds plus the margin stated at each.
 */
#include "corpus.h"

#include <pcl_holefill/detail/boundary_point_test.h>
#include <pcl_holefill/hole_boundary_estimation.h>
#include <pcl_holefill/hole_filling.h>
#include <pcl_holefill/normal_orientation.h>

#include <pcl/console/print.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <tuple>

namespace
{
using corpus::Sampling;
using pcl_holefill::shapes::Cloud;

using corpus::Outcome;

Outcome
fillCase (const corpus::Case &c)
{
  pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
  return corpus::runCase (c);
}

corpus::Case
makeCase (const pcl_holefill::shapes::Shape &shape, Sampling sampling, double noise, bool estimated, bool holes)
{
  corpus::Case c;
  c.shape = shape;
  c.points = 20000;
  c.sampling = sampling;
  c.noise = noise;
  c.estimated = estimated;
  if (holes)
    c.holes = corpus::holesOf (shape, c.points);
  return c;
}

const std::vector<Sampling> kSamplings = corpus::allSamplings ();

std::string
samplingName (const testing::TestParamInfo<std::tuple<int, int>> &info)
{
  static const char *models[] = {"cube", "sphere", "torus", "lblock", "fin"};
  return std::string (models[std::get<0> (info.param)]) + "_" + corpus::toString (kSamplings[std::get<1> (info.param)]);
}

pcl_holefill::shapes::Shape
model (int i)
{
  using namespace pcl_holefill::shapes;
  switch (i)
  {
  case 0: return cube ();
  case 1: return sphere ();
  case 2: return corpus::torus ();
  case 3: return corpus::lBlock ();
  default: return corpus::fin ();
  }
}
}  // namespace

// Stray returns (0.5 % of the points moved 1 to 4 pitches off the surface,
// as a scanner's mixed pixels). Two causes, both in these cases:
// - one among a rim point's one-sided neighbours pulled the least-squares
//   quadric of the normal refit through itself, the rim normal tilted by up
//   to 12 degrees, and the rim's tangent plane cut the fill short (sphere
//   jittered 73.2 % covered, max error 2.8 pitches; voxel grid 89.3 %, 9.3
//   pitches; cube random, PCA normals, 98.6 %, 1.0 pitch);
// - one next to a hole saw the hole's side empty and joined its loop, or one
//   was left inside the hole, and the fill grew through it at its offset
//   (cube scan lines: 3.8 pitches; pyramid jittered: 3.3 pitches).
TEST (Strays, NeitherTiltTheRimNorCarryTheFillOffTheSurface)
{
  const std::vector<std::tuple<int, Sampling, bool>> cases = {{1, Sampling::kJittered, false},
                                                              {1, Sampling::kVoxel, false},
                                                              {0, Sampling::kRandom, true},
                                                              {0, Sampling::kScan, false}};
  for (const auto &[m, sampling, estimated] : cases)
  {
    auto c = makeCase (model (m), sampling, 0.0, estimated, true);
    c.strays = 0.005;
    const Outcome o = fillCase (c);
    const double p = corpus::pitch (c.shape, c.points);
    const std::string name = c.shape.name + " " + corpus::toString (sampling);
    EXPECT_EQ (o.detection.found, o.detection.cut) << name;
    EXPECT_EQ (o.detection.false_holes, 0u) << name;
    EXPECT_TRUE (o.fill.kept_unchanged) << name;
    EXPECT_GE (o.fill.coverage, 0.98) << name;    // reached: 99.6, 99.8, 99.8, 98.8 %
    EXPECT_LE (o.fill.max_error, 0.4 * p) << name;  // reached: 0.19, 0.02, 0.10, 0.00 pitch
  }
  // The pyramid's apex on jittered samples: its rim's stray. A cylinder on
  // scan lines: two strays side by side (each other's nearest neighbour),
  // 3.8 pitches inside, on a rim. Exact normals.
  for (const auto &[shape, sampling] : {std::make_pair (pcl_holefill::shapes::openPyramid (), Sampling::kJittered),
                                        std::make_pair (corpus::cylinder (), Sampling::kScan)})
  {
    auto c = makeCase (shape, sampling, 0.0, false, true);
    c.strays = 0.005;
    const Outcome o = fillCase (c);
    EXPECT_LE (o.fill.max_error, 0.4 * corpus::pitch (c.shape, c.points)) << shape.name;  // reached: 0.07, 0.10 pitch
  }
  // The L-block, density varying, PCA normals: one stray 4 pitches inside,
  // under the hole at a corner, was among the k nearest of the rim points of
  // two of its three faces and closed their angular gaps; the hole went
  // unfound (83.2 % covered).
  auto c = makeCase (corpus::lBlock (), Sampling::kVarying, 0.0, true, true);
  c.strays = 0.005;
  const Outcome o = fillCase (c);
  EXPECT_EQ (o.detection.found, o.detection.cut);
  EXPECT_EQ (o.detection.false_holes, 0u);
  EXPECT_TRUE (o.fill.kept_unchanged);
  EXPECT_GE (o.fill.coverage, 0.98);  // reached: 99.5 %
}

// The pitch means the same for every sampler: sqrt(area per point).
TEST (SamplingPitch, MatchesTheAreaPerPointOfEverySampler)
{
  const auto shape = pcl_holefill::shapes::flatPatch ();
  for (const auto s : kSamplings)
  {
    const Cloud cloud = corpus::sampleSurface (shape, 10000, s, 3);
    pcl_holefill::HoleBoundaryEstimation<pcl::PointNormal> estimation;
    estimation.setInputCloud (Cloud::Ptr (new Cloud (cloud)));
    std::vector<pcl_holefill::BoundaryLoop> loops;
    estimation.compute (loops);
    const double truth = std::sqrt (shape.area () / cloud.size ());
    // 10 %: the estimate from 16 neighbours, averaged over the cloud
    EXPECT_NEAR (estimation.getMeanPitch (), truth, 0.1 * truth) << corpus::toString (s);
  }
}

namespace
{
/** Holes \a estimation finds in a flat patch of \a sampling with gaps cut
  * 4 and 9 pitches across (at x = 0.3 and 0.7); each loop's first point must
  * lie on the rim of one. */
std::size_t
holesFoundInAPatch (Sampling sampling, pcl_holefill::HoleBoundaryEstimation<pcl::PointNormal> &estimation)
{
  const auto shape = pcl_holefill::shapes::flatPatch ();
  const double p = corpus::pitch (shape, 20000);
  const Cloud cloud = corpus::sampleSurface (shape, 20000, sampling, 5);
  const auto cut = pcl_holefill::shapes::cutHoles (
      cloud, {{Eigen::Vector3d (0.3, 0.5, 0.5), 2.0 * p}, {Eigen::Vector3d (0.7, 0.5, 0.5), 4.5 * p}});
  estimation.setInputCloud (Cloud::Ptr (new Cloud (cut.kept)));
  std::vector<pcl_holefill::BoundaryLoop> loops;
  estimation.compute (loops);
  std::size_t holes = 0;
  for (const auto &l : loops)
    if (l.is_hole)
    {
      ++holes;
      const Eigen::Vector3f first = cut.kept[l.indices[0]].getVector3fMap ();
      const double off_rim = std::min (std::abs ((first - Eigen::Vector3f (0.3f, 0.5f, 0.5f)).norm () - 2.0 * p),
                                       std::abs ((first - Eigen::Vector3f (0.7f, 0.5f, 0.5f)).norm () - 4.5 * p));
      EXPECT_LE (off_rim, 2.0 * p);
    }
  return holes;
}
}  // namespace

// By default a gap of 4 pitches on uniformly random samples is sampling (its
// min hole size: 6), one of 9 is a hole.
TEST (MinHoleSize, SeparatesSmallGapsFromHoles)
{
  pcl_holefill::HoleBoundaryEstimation<pcl::PointNormal> estimation;
  EXPECT_EQ (holesFoundInAPatch (Sampling::kRandom, estimation), 1u);
  EXPECT_FLOAT_EQ (estimation.getMinHoleSizeUsed (), 6.f);
}

// How evenly a cloud is sampled sets the default min hole size: 6 pitches
// on samples as uneven as uniformly random ones or scan lines, 4 on even
// ones, noisy or not, normals exact or estimated (the evenness is measured
// in the tangent plane; noise along the normal does not count). Reached on
// the cube: random 0.30, scan lines 0.39-0.41, jittered 0.59-0.63, Poisson-disk
// 0.72-0.78, voxel grid 0.78-0.83; the bounds are the thresholds (0.45, 0.55).
TEST (MinHoleSize, FollowsTheEvennessOfTheSampling)
{
  for (const Sampling sampling : kSamplings)
    for (const double noise : {0.0, 0.005})
      for (const bool estimated : {false, true})
      {
        const auto c = makeCase (pcl_holefill::shapes::cube (), sampling, noise, estimated, false);
        const auto cut = corpus::build (c);
        pcl_holefill::HoleBoundaryEstimation<pcl::PointNormal> estimation;
        estimation.setInputCloud (Cloud::Ptr (new Cloud (cut.kept)));
        std::vector<pcl_holefill::BoundaryLoop> loops;
        pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
        estimation.compute (loops);
        const bool uneven = sampling == Sampling::kRandom || sampling == Sampling::kScan;
        SCOPED_TRACE (testing::Message () << corpus::toString (sampling) << " noise " << noise
                                          << (estimated ? " PCA" : " exact") << ": evenness "
                                          << estimation.getSamplingEvenness ());
        if (uneven)
        {
          EXPECT_LE (estimation.getSamplingEvenness (), 0.45f);
          EXPECT_FLOAT_EQ (estimation.getMinHoleSizeUsed (), 6.f);
        }
        else
        {
          EXPECT_GE (estimation.getSamplingEvenness (), 0.55f);
          EXPECT_FLOAT_EQ (estimation.getMinHoleSizeUsed (), 4.f);
        }
      }
}

// On Poisson-disk samples, whose own gaps are under 2 pitches, the default
// min hole size is 4 pitches: the gap of 4 pitches is a hole too.
TEST (MinHoleSize, IsSmallerOnEvenSamples)
{
  pcl_holefill::HoleBoundaryEstimation<pcl::PointNormal> estimation;
  EXPECT_EQ (holesFoundInAPatch (Sampling::kPoisson, estimation), 2u);
  EXPECT_FLOAT_EQ (estimation.getMinHoleSizeUsed (), 4.f);
  estimation.setMinHoleSize (6.f);  // as set, not chosen
  EXPECT_EQ (holesFoundInAPatch (Sampling::kPoisson, estimation), 1u);
  EXPECT_FLOAT_EQ (estimation.getMinHoleSizeUsed (), 6.f);
}

// Two holes 12 pitches across, a bridge of 1 to 3 pitches between them, on
// random samples. The walk round the first hole took the rim across the
// bridge for a second row of its own and left the second hole's walk stuck
// at both ends of the bridge: an open piece, taken for a border (one hole
// of the two found on 2 of these 9 clouds). A bridge a pitch wide may be
// broken by the gaps of random samples: then the two are one hole, as wide
// as both (found so on 2 clouds).
TEST (LoopTracing, TwoHolesAcrossANarrowBridgeAreBothFound)
{
  const auto shape = pcl_holefill::shapes::flatPatch ();
  const double p = corpus::pitch (shape, 20000);
  for (const double bridge : {1.0, 2.0, 3.0})
    for (const unsigned seed : {1u, 3u, 7u})
    {
      const Cloud cloud = corpus::sampleSurface (shape, 20000, Sampling::kRandom, seed);
      const double offset = 6.0 * p + 0.5 * bridge * p;
      const auto cut = pcl_holefill::shapes::cutHoles (cloud, {{Eigen::Vector3d (0.5 - offset, 0.5, 0.5), 6.0 * p},
                                                               {Eigen::Vector3d (0.5 + offset, 0.5, 0.5), 6.0 * p}});
      pcl_holefill::HoleBoundaryEstimation<pcl::PointNormal> estimation;
      estimation.setInputCloud (Cloud::Ptr (new Cloud (cut.kept)));
      std::vector<pcl_holefill::BoundaryLoop> loops;
      estimation.compute (loops);
      std::vector<float> sides;  // the x of each hole's centre
      float widest = 0.f;
      testing::Message found;
      for (const auto &l : loops)
      {
        found << (l.is_hole ? "hole " : "border ") << l.diameter / p << (l.closed ? " closed; " : " open; ");
        if (!l.is_hole)
          continue;
        Eigen::Vector3f centre = Eigen::Vector3f::Zero ();
        for (const auto i : l.indices)
          centre += cut.kept[i].getVector3fMap ();
        sides.push_back (centre.x () / static_cast<float> (l.indices.size ()) - 0.5f);
        widest = std::max (widest, l.diameter);
      }
      SCOPED_TRACE (testing::Message () << "bridge " << bridge << " pitches, seed " << seed << ": " << found);
      if (bridge == 1.0 && sides.size () == 1u)
      {
        EXPECT_GE (widest, 24.0 * p);  // one hole round both
        continue;
      }
      EXPECT_EQ (sides.size (), 2u);
      if (sides.size () == 2u)
      {
        EXPECT_LT (sides[0] * sides[1], 0.f);  // one on each side of the bridge
      }
    }
}

namespace
{
// The points of \a cloud with x >= 0.5, and 1 in 4 of the others, drawn
// at random: a cloud with a density step.
Cloud
thinHalf (const Cloud &cloud, unsigned seed)
{
  Cloud thinned;
  std::mt19937 random (seed);
  std::uniform_real_distribution<double> unit (0.0, 1.0);
  for (const auto &q : cloud)
    if (q.x >= 0.5f || unit (random) < 0.25)
      thinned.push_back (q);
  return thinned;
}
}  // namespace

// Merged scans are denser in one part than in another. A cube sampled
// uniformly at random, its half x < 0.5 four times sparser than the other
// (its pitch 1.6 times the cloud's mean): with the loop tracing's link taken
// from the mean pitch alone, the rim of one of two 10-pitch holes in the
// sparse half came out in open pieces, a border, and was not filled (64 %
// and 69 % of the cut covered, seeds 1 and 7); the link follows the pitch
// around each rim point now.
TEST (DensityStep, HolesInTheSparserPartAreFoundAndFilled)
{
  const auto shape = pcl_holefill::shapes::cube ();
  for (const unsigned seed : {1u, 7u})
  {
    const Cloud cloud = thinHalf (corpus::sampleSurface (shape, 40000, Sampling::kRandom, seed), seed);
    // The sparse half's own pitch: its area (half the cube's 6) over its points.
    const auto sparse = static_cast<double> (std::count_if (cloud.begin (), cloud.end (), [] (const auto &q) { return q.x < 0.5f; }));
    const double p = std::sqrt (3.0 / sparse);
    const std::vector<pcl_holefill::shapes::Ball> balls{{Eigen::Vector3d (0.25, 0.0, 0.0), 5.0 * p},   // an edge
                                                        {Eigen::Vector3d (0.25, 0.5, 1.0), 5.0 * p}};  // a face
    const auto cut = pcl_holefill::shapes::cutHoles (cloud, balls);
    const Cloud::Ptr kept (new Cloud (cut.kept));
    const auto detection = corpus::detectHoles (kept, balls, p);
    pcl_holefill::HoleFilling<pcl::PointNormal> filler;
    filler.setInputCloud (kept);
    Cloud output;
    filler.filter (output);
    const auto fill = pcl_holefill::shapes::evaluateFill (shape, cut, balls, output, p);
    SCOPED_TRACE (testing::Message () << "seed " << seed << ", sparse pitch " << p);
    EXPECT_EQ (detection.found, 2u);
    EXPECT_EQ (detection.false_holes, 0u);
    // reached: 100 % (both seeds)
    EXPECT_GE (fill.coverage, 0.99);
    // reached: 0.002 pitch (flat faces, a sharp edge); margin 0.25 pitch
    EXPECT_LE (fill.max_error, 0.25 * p);
    double past = 0.0;  // how far the farthest filled point lies outside the cut balls
    for (std::size_t i = cut.kept.size (); i < output.size (); ++i)
    {
      double nearest = std::numeric_limits<double>::max ();
      for (const auto &b : balls)
        nearest = std::min (nearest, (output[i].getVector3fMap ().cast<double> () - b.centre).norm () - b.radius);
      past = std::max (past, nearest);
    }
    // reached: 1.17 and 1.53 pitches (a rim point of random samples lies a
    // pitch or more past the ball); the bound is 2
    EXPECT_LE (past, 2.0 * p);
    EXPECT_TRUE (fill.kept_unchanged);
  }
}

// A cloud sampled evenly in one part and randomly in another: voxel-grid
// and Poisson-disk samples of a cube whose half x < 0.5 was thinned to 1 in 4 at random (a
// part of a merged scan, a region decimated). The min hole size chosen from
// the whole cloud's evenness was the even samplings' 4 pitches, and the
// thinned half's random gaps (up to about 5 of its pitches) came out as
// false holes and were filled; each region is judged by its own evenness now.
// Holes of 10 pitches in either half are found.
TEST (DensityStep, AThinnedPartOfAnEvenCloudKeepsItsGaps)
{
  const auto shape = pcl_holefill::shapes::cube ();
  for (const auto sampling : {Sampling::kVoxel, Sampling::kPoisson})
  for (const unsigned seed : {1u, 3u, 7u})
  {
    const Cloud cloud = thinHalf (corpus::sampleSurface (shape, 32000, sampling, seed), seed);
    const auto dense = static_cast<double> (std::count_if (cloud.begin (), cloud.end (), [] (const auto &q) { return q.x >= 0.5f; }));
    const double p = std::sqrt (3.0 / dense);  // the even half's pitch; the thinned half's is 2 p
    SCOPED_TRACE (testing::Message () << corpus::toString (sampling) << ", seed " << seed << ", even pitch " << p);
    const Cloud::Ptr whole (new Cloud (cloud));
    // Hole-free: nothing found, nothing added.
    const auto none = corpus::detectHoles (whole, {}, p);
    EXPECT_EQ (none.false_holes, 0u);
    pcl_holefill::HoleFilling<pcl::PointNormal> filler;
    filler.setInputCloud (whole);
    Cloud output;
    filler.filter (output);
    EXPECT_EQ (output.size (), cloud.size ());
    // A hole of 10 pitches on a face of each half, the thinned half's 11
    // pitches (its own 5.5) from the step. (Centred at x = 0.25, 4 of its
    // own pitches from the step, its rim joined the rim points that the step
    // itself gives the dense side, an open border: Poisson-disk seed 3, as
    // before this change.)
    const std::vector<pcl_holefill::shapes::Ball> balls{{Eigen::Vector3d (0.2, 0.5, 1.0), 10.0 * p},  // 10 of its own pitches
                                                        {Eigen::Vector3d (0.75, 0.5, 1.0), 5.0 * p}};
    const auto cut = pcl_holefill::shapes::cutHoles (cloud, balls);
    const auto detection = corpus::detectHoles (Cloud::Ptr (new Cloud (cut.kept)), balls, p);
    EXPECT_EQ (detection.found, 2u);
    EXPECT_EQ (detection.false_holes, 0u);
  }
}

class HoleFree : public testing::TestWithParam<std::tuple<int, int>>
{};

// No hole, no point added, every point unchanged: whatever the sampling.
TEST_P (HoleFree, CloudComesBackUnchanged)
{
  const auto c = makeCase (model (std::get<0> (GetParam ())), kSamplings[std::get<1> (GetParam ())], 0.0, false, false);
  const Outcome o = fillCase (c);
  EXPECT_EQ (o.detection.false_holes, 0u);
  EXPECT_EQ (o.output, o.input);
  EXPECT_TRUE (o.fill.kept_unchanged);
}

INSTANTIATE_TEST_SUITE_P (EverySampling, HoleFree,
                          testing::Combine (testing::Values (0, 1, 2), testing::Range (0, 6)), samplingName);

class CleanHoles : public testing::TestWithParam<std::tuple<int, int>>
{};

// Clean input, exact normals, no option: every hole found, nothing false,
// covered, on the surface, nothing outside the holes, input untouched.
TEST_P (CleanHoles, FoundCoveredAndOnTheSurface)
{
  const auto c = makeCase (model (std::get<0> (GetParam ())), kSamplings[std::get<1> (GetParam ())], 0.0, false, true);
  const Outcome o = fillCase (c);
  const double p = corpus::pitch (c.shape, c.points);
  EXPECT_EQ (o.detection.found, o.detection.cut);
  EXPECT_EQ (o.detection.false_holes, 0u);
  EXPECT_TRUE (o.fill.kept_unchanged);
  // reached: 99.4 % (the cube's scan lines) to 100 %; margin 1.4 points. The
  // fin's voxel grid was at 95.2 % while its min hole size was that of random
  // samples: the 5.9-pitch hole the cut left in its bottom face went unfound.
  EXPECT_GE (o.fill.coverage, 0.98);
  // reached: up to 1.2 pitches (a scan-line cube's edge); margin 0.8 pitch
  EXPECT_LE (o.fill.max_error, 2.0 * p);
  // reached: at most 4 points beyond one pitch outside a cut ball
  EXPECT_LE (o.fill.outside, 8u);
  // As dense as the input: filled points per removed sample. reached: 0.67
  // (the fin, voxel grid) to 1.01; margin 0.12 each way.
  EXPECT_GE (o.density, 0.55);
  EXPECT_LE (o.density, 1.15);
}

INSTANTIATE_TEST_SUITE_P (EverySampling, CleanHoles,
                          testing::Combine (testing::Values (0, 1, 3), testing::Range (0, 6)), samplingName);
// The thin fin on every sampling. On scan lines the hole across the fin's
// thin end grew off the part (max error 0.067, 23 points outside the cut)
// until new points had to lie within the hole's rim (reached: 0.0059).
INSTANTIATE_TEST_SUITE_P (ThinPart, CleanHoles,
                          testing::Combine (testing::Values (4), testing::Range (0, 6)), samplingName);

class NoisyThinEnd : public testing::TestWithParam<std::tuple<int, double>>
{};

// The hole cut round the fin's thin end (0.04 thick, 5 pitches) on noisy
// samples. Its rim was traced as two half-loops: a walk from the lower rim
// went round the end face and "came home" to the upper rim, 5 pitches away
// across the plate. Each half was filled as a hole of its own (3 reports
// for 2 holes), and fronts ran off the end of the plate (max errors 0.052 to
// 0.071). The walk no longer steps or closes between opposite normals, and
// new points must lie within the rim. On jittered samples at 0.5 % the top
// and bottom faces still grew past the end as flat flaps (max error 0.073,
// 9 pitches): every rim point of the end face is next to a crease, so none
// gave a rim plane to hold them; now the end face's own are kept.
TEST_P (NoisyThinEnd, IsOneLoopAndItsFillStaysOnThePart)
{
  const auto c = makeCase (corpus::fin (), kSamplings[std::get<0> (GetParam ())], std::get<1> (GetParam ()), false, true);
  const Outcome o = fillCase (c);
  EXPECT_EQ (o.detection.found, o.detection.cut);
  EXPECT_EQ (o.detection.false_holes, 0u);
  // One report for the end hole (was two: its halves). On even samples the
  // top hole gets two: its cut reaches the bottom face, 5.9 pitches across.
  ASSERT_EQ (o.reports_per_ball.size (), 2u);
  EXPECT_EQ (o.reports_per_ball[1], 1u);
  EXPECT_GE (o.reports_per_ball[0], 1u);
  EXPECT_LE (o.reports_per_ball[0], 2u);
  EXPECT_TRUE (o.fill.kept_unchanged);
  // reached: 0.0055 (voxel) to 0.0176 (scan lines), jittered 0.5 %: 0.019;
  // was 0.052 to 0.071, jittered 0.5 %: 0.073
  EXPECT_LE (o.fill.max_error, 0.025);
}

INSTANTIATE_TEST_SUITE_P (
    Samplings, NoisyThinEnd,
    testing::Values (std::make_tuple (1, 0.005), std::make_tuple (2, 0.003), std::make_tuple (2, 0.005),
                     std::make_tuple (3, 0.003), std::make_tuple (4, 0.003)),
    [] (const testing::TestParamInfo<std::tuple<int, double>> &info) {
      return corpus::toString (kSamplings[std::get<0> (info.param)]) + std::string ("_noise") +
             std::to_string (static_cast<int> (std::get<1> (info.param) * 1000 + 0.5));
    });

// A ball at a corner of the fin (a plate 5.2 pitches thick), 20 pitches
// across, takes the corners of both faces and the end and side strips
// between them: one loop round the plate. The faces' corners lie past the
// rim's outline in every view of the enclosure test, and it cut their fill
// off (79.1-86.4 % covered on four of these eight, none reported closed).
// On a clean rim with a crease the test now leaves the faces to the
// combination constraint, which holds them within 0.1 h.
TEST (ThinPlateCorner, IsFilledToTheCornerOnEveryFace)
{
  const double p = corpus::pitch (corpus::fin (), 20000);
  for (const auto &ball : corpus::finCornerHoles (20000))
  {
    auto c = makeCase (corpus::fin (), Sampling::kPoisson, 0.0, false, false);
    c.holes = {ball};
    const Outcome o = fillCase (c);
    std::ostringstream name;
    name << ball.centre.transpose ();
    EXPECT_EQ (o.detection.found, 1u) << name.str ();
    EXPECT_EQ (o.detection.false_holes, 0u) << name.str ();
    EXPECT_TRUE (o.fill.kept_unchanged) << name.str ();
    EXPECT_GE (o.fill.coverage, 0.995) << name.str ();     // reached: 99.9-100 %
    EXPECT_LE (o.fill.max_error, 0.2 * p) << name.str ();  // reached: 0.01-0.08 pitch
    EXPECT_EQ (o.closed, o.reported) << name.str ();       // reached: all closed
  }
}

// The same eight corners on noisy samples (exact normals). The faces'
// corners lie on the rim's outline seen along the hole's axis, and the
// noise of the rim points put them past it: the enclosure test (pi along
// the axis) cut about every other one, and the fronts stopped with the
// corners open. On a noisy rim with a crease the axis now allows 200
// degrees, up to half a pitch of rim noise; the side strips' rim planes hold
// the faces at the corners.
struct NoisyCorners
{
  Sampling sampling;
  double noise;
  double max_error;  //!< bound: what this code reached plus a quarter
};

void
PrintTo (const NoisyCorners &c, std::ostream *os)
{
  *os << corpus::toString (c.sampling) << ", noise " << c.noise << ", max error " << c.max_error;
}

class NoisyThinPlateCorners : public testing::TestWithParam<NoisyCorners>
{};

TEST_P (NoisyThinPlateCorners, AreFilledToTheirCorners)
{
  auto c = makeCase (corpus::fin (), GetParam ().sampling, GetParam ().noise, false, false);
  c.holes = corpus::finCornerHoles (20000);
  const Outcome o = fillCase (c);
  EXPECT_EQ (o.detection.found, o.detection.cut);
  EXPECT_EQ (o.detection.false_holes, 0u);
  EXPECT_TRUE (o.fill.kept_unchanged);
  EXPECT_GE (o.fill.coverage, 0.95);
  EXPECT_LE (o.fill.max_error, GetParam ().max_error);
  EXPECT_EQ (o.closed_but_open, 0u);
}

// Reached: Poisson-disk 0.1 % 96.6 % covered (was 91.5 %), max error 0.0081;
// jittered 0.3 % 97.2 % (was 92.0 %), 0.0081; scan lines 0.3 % 97.5 % (was
// 87.1 %), 0.0193; jittered 0.5 % 98.1 %, 0.0214 (was 0.0364: the faces ran
// past the side strips, whose middle points see one crease each and gave
// no rim plane).
INSTANTIATE_TEST_SUITE_P (Samplings, NoisyThinPlateCorners,
                          testing::Values (NoisyCorners{Sampling::kPoisson, 0.001, 0.0105},
                                           NoisyCorners{Sampling::kJittered, 0.003, 0.010},
                                           NoisyCorners{Sampling::kScan, 0.003, 0.024},
                                           NoisyCorners{Sampling::kJittered, 0.005, 0.027}),
                          [] (const testing::TestParamInfo<NoisyCorners> &info) {
                            return corpus::toString (info.param.sampling) + std::string ("_noise") +
                                   std::to_string (static_cast<int> (info.param.noise * 1000 + 0.5));
                          });

/** Cuts the ball of \a radius spacings \a h at \a centre out of \a cloud
  * (corpus::meshVertices), fills it with no option and scores the fill against
  * \a mesh; \a reports: the holes the filler reported. */
pcl_holefill::shapes::FillQuality
fillBallOfVertices (const pcl_holefill::shapes::Shape &mesh, const Cloud &cloud, const Eigen::Vector3d &centre,
                    double radius, double h, std::size_t &reports)
{
  const std::vector<pcl_holefill::shapes::Ball> cut_balls = {{centre, radius * h}};
  const auto cut = pcl_holefill::shapes::cutHoles (cloud, cut_balls);
  pcl_holefill::HoleFilling<pcl::PointNormal> filler;
  filler.setInputCloud (cut.kept.makeShared ());
  Cloud output;
  filler.filter (output);
  reports = filler.getReports ().size ();
  return pcl_holefill::shapes::evaluateFill (mesh, cut, cut_balls, output, h);
}

/** One ball cut from fandisk's vertices, and what its fill must reach. */
struct VertexBall
{
  Eigen::Vector3d centre;  // unit-cube coordinates
  double radius;           // spacings
  double min_coverage, max_error_in_spacings;
  std::size_t max_outside;
};

/** Fills each ball of fandisk's vertices alone and checks it against its bounds. */
void
expectBallsOfVerticesFilled (const std::vector<VertexBall> &balls)
{
  pcl_holefill::shapes::Shape mesh;
  std::string error;
  ASSERT_TRUE (corpus::fandisk (mesh, error)) << error;
  const Cloud cloud = corpus::meshVertices (mesh);
  const double h = pcl_holefill::shapes::meanSpacing (cloud);
  pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
  for (const auto &c : balls)
  {
    std::size_t reports = 0;
    const auto quality = fillBallOfVertices (mesh, cloud, c.centre, c.radius, h, reports);
    std::ostringstream name;
    name << c.centre.transpose () << ", " << c.radius << " spacings";
    EXPECT_EQ (reports, 1u) << name.str ();
    EXPECT_TRUE (quality.kept_unchanged) << name.str ();
    EXPECT_GE (quality.coverage, c.min_coverage) << name.str ();
    EXPECT_LE (quality.max_error, c.max_error_in_spacings * h) << name.str ();
    EXPECT_LE (quality.outside, c.max_outside) << name.str ();
  }
}

// Holes in fandisk's mesh vertices, on a face next to a wall that meets
// two faces (a step beside a floor, the foot of its thin plate). The wall's
// points were labelled concave by the face in front of them and rejected
// every sample of the floor behind them (section 4.4's constraint): 56-92 %
// covered, one flap 3.8 spacings off. A point whose plane the sample's
// front vertex is past already, and whose neighbours on the vertex's side
// label it otherwise, no longer rejects it.
TEST (MeshVertices, FaceBesideAWallIsFilled)
{
  pcl_holefill::shapes::Shape mesh;
  std::string error;
  // The test command installs libcgal-demo: without fandisk this case is not run, and says so.
  ASSERT_TRUE (corpus::fandisk (mesh, error)) << error;
  const Cloud cloud = corpus::meshVertices (mesh);
  const double h = pcl_holefill::shapes::meanSpacing (cloud);
  // Centre (unit-cube coordinates) and radius in spacings.
  const std::vector<std::pair<Eigen::Vector3d, double>> balls = {
      {{0.5401, 0.1062, 0.7062}, 6.16}, {{0.5081, 0.5111, 0.7495}, 5.05}, {{0.6138, 0.2721, 0.5172}, 4.32},
      {{0.4212, 0.0784, 0.9500}, 6.83}, {{0.4133, 0.0496, 0.7866}, 5.68}, {{0.2569, 0.3986, 0.9360}, 4.42}};
  pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
  double coverage = 0.0;  // mean over the balls
  for (const auto &[centre, radius] : balls)
  {
    std::size_t reports = 0;
    const auto quality = fillBallOfVertices (mesh, cloud, centre, radius, h, reports);
    std::ostringstream name;
    name << centre.transpose () << ", " << radius << " spacings";
    EXPECT_EQ (reports, 1u) << name.str ();
    EXPECT_TRUE (quality.kept_unchanged) << name.str ();
    EXPECT_GE (quality.coverage, 0.8) << name.str ();      // reached: 83.6-100 % (before: 56.4-92.0 %)
    EXPECT_LE (quality.max_error, 2.0 * h) << name.str ();  // reached: 0-1.55 h (before: up to 3.76 h)
    coverage += quality.coverage / static_cast<double> (balls.size ());
  }
  EXPECT_GE (coverage, 0.92);  // reached: 94.3 % (before: 79.3 %)
}

// Two balls of bench/mesh_vertices_check.py (exact normals: each vertex's is
// the area-weighted mean of its faces'). On a curved strip of long thin
// triangles those normals lie a few degrees off the surface, and samples on
// it (0.01-0.2 h off the mesh) stood 0.3 h past the tangent planes of
// points labelled convex: the first pass kept 17 of 61 and the ratio rule
// ended the fill. Elsewhere a wall's front ran up past a convex edge as a
// sheet, 6.6 h out of the ball.
TEST (MeshVertices, TiltedVertexNormalsBoundOnlyBeyondTheirOwnFace)
{
  expectBallsOfVerticesFilled ({
      // reached: 61.4 % of the cut vertices covered (before 27.9 %), none
      // outside; 4.4 h: a resumed front runs flat off the fillet. (It was
      // 1.8 h while largestAngularGap read some parallel neighbour
      // directions as a whole turn, depending on their order and rounding:
      // 28 points of this cloud had a gap of 2 pi. In the bench's
      // coordinates, where the rounding fell otherwise, the ball had 4.6 h
      // before and after that fix.)
      {{0.9061, 0.3421, 0.6447}, 9.9488, 0.5, 5.0, 0},
      // reached: 78.5 % (before 74.2 %), 6.8 h (before 10.0 h), farthest
      // filled point 0.9 h outside the ball (before 6.6 h)
      {{0.5427, 0.1943, 0.7642}, 9.6254, 0.7, 8.0, 0}});
}

// Three balls of bench/mesh_vertices_check.py (exact normals) where the
// hole reaches a face that curves up towards its normals (fandisk's
// channel) and the crease where it meets a side face. Whether a rim point's
// tangent plane bounds the fill was asked of the other planes' points only,
// and those next to a crease give none: the side face's rim points, which
// stand above the channel's planes, were not asked, and the channel's
// planes cut the fill off along the crease. Every rim point is asked now.
TEST (MeshVertices, PlanesOfAFaceThatCurvesUpDoNotBoundTheFill)
{
  // reached: 100 / 100 / 92.6 % of the cut vertices covered (before 73.0 /
  // 97.9 / 89.9 %), max errors 0.52 / 0.25 / 0.31 h (before 0.20 / 0.24 /
  // 1.38 h), none outside
  expectBallsOfVerticesFilled ({{{0.0251, 0.3325, 0.6092}, 8.7152, 0.99, 0.8, 0},
                                {{0.9018, 0.5111, 0.2067}, 7.6069, 0.99, 0.8, 0},
                                {{0.5389, 0.3250, 0.8431}, 7.0746, 0.9, 0.8, 0}});
}

class ThinSheet : public testing::TestWithParam<std::tuple<double, int>>
{};

// A hole in one face of a sheet two pitches thick or less (sheet metal, a
// wall scanned from both sides), the other face intact. It was not found:
// the angular-gap test saw the face below fill the gap, and the orientation
// check counted the faces' opposite normals as flipped (29 %) and
// re-oriented them all one way. With those fixed, a midpoint of the rim
// took a point of the face below, and candidates were "too close" to it
// (a sheet 0.3 pitch thick: 40 % covered, reported closed); and a gap of
// random samples in the sheet's side strip, where both faces end, was
// reported as a hole 9 pitches across until a disc on a thin part had to
// lie over the other face.
TEST_P (ThinSheet, AHoleInOneFaceIsFoundAndFilledOnThatFace)
{
  const auto [thickness_in_pitches, sampling] = GetParam ();
  const double p = corpus::pitch (corpus::sheet (0.0), 20000);
  const double thickness = thickness_in_pitches * p;
  const auto shape = corpus::sheet (thickness);
  const Cloud cloud = corpus::sampleSurface (shape, 20000, kSamplings[sampling], 11);
  const Eigen::Vector3f centre (0.5f, 0.5f, static_cast<float> (0.5 + 0.5 * thickness));
  const float radius = static_cast<float> (8.0 * p);
  Cloud kept, removed;
  for (const auto &q : cloud)
    ((q.getVector3fMap () - centre).norm () < radius && q.normal_z > 0.5f ? removed : kept).push_back (q);
  pcl_holefill::HoleFilling<pcl::PointNormal> filler;
  filler.setInputCloud (kept.makeShared ());
  Cloud output;
  filler.filter (output);
  testing::Message holes;
  for (const auto &r : filler.getReports ())
    holes << "hole at " << r.centre.transpose () << ", " << r.diameter / p << " pitches; ";
  ASSERT_EQ (filler.getReports ().size (), 1u) << holes;  // was 0
  EXPECT_TRUE (filler.getReports ()[0].closed);
  ASSERT_GE (output.size (), kept.size ());
  for (std::size_t i = 0; i < kept.size (); ++i)
    ASSERT_EQ (std::memcmp (output[i].data, kept[i].data, sizeof (float) * 3), 0);
  // On the top face, inside the cut: reached |dz| <= 0.00001 pitch; margin 0.05 pitch.
  for (std::size_t i = kept.size (); i < output.size (); ++i)
  {
    EXPECT_NEAR (output[i].z, centre.z (), 0.05 * p);
    EXPECT_LT ((output[i].getVector3fMap () - centre).norm (), radius + 2.0 * p);
  }
  // Every removed sample within 1.5 pitches of a top-face output point
  // (the face below is within a pitch of all of them). reached: 100 %.
  std::size_t covered = 0;
  for (const auto &r : removed)
    covered += std::any_of (output.begin (), output.end (), [&] (const pcl::PointNormal &q) {
      return q.normal_z > 0.5f && (q.getVector3fMap () - r.getVector3fMap ()).norm () < 1.5 * p;
    });
  EXPECT_GE (static_cast<double> (covered), 0.99 * static_cast<double> (removed.size ()));
  // As dense as the input (the face below halved the measured pitch: 1.5
  // times too dense). reached: 0.84 to 1.19; margin 0.15 each way.
  const double density = static_cast<double> (output.size () - kept.size ()) / static_cast<double> (removed.size ());
  EXPECT_GE (density, 0.69);
  EXPECT_LE (density, 1.34);
}

// The same sheets without the hole: nothing found, nothing added.
TEST_P (ThinSheet, WithoutAHoleComesBackUnchanged)
{
  const auto [thickness_in_pitches, sampling] = GetParam ();
  const double p = corpus::pitch (corpus::sheet (0.0), 20000);
  const Cloud cloud = corpus::sampleSurface (corpus::sheet (thickness_in_pitches * p), 20000, kSamplings[sampling], 11);
  pcl_holefill::HoleFilling<pcl::PointNormal> filler;
  filler.setInputCloud (cloud.makeShared ());
  Cloud output;
  filler.filter (output);
  EXPECT_TRUE (filler.getReports ().empty ());
  EXPECT_EQ (output.size (), cloud.size ());
}

INSTANTIATE_TEST_SUITE_P (
    Thickness, ThinSheet,
    // 0.3 pitch on jittered samples only: random ones leave the sheet's
    // side strip (a third of a pitch wide) mostly empty, and a voxel grid
    // mixes the two faces into one layer of points.
    testing::Values (std::make_tuple (0.3, 2), std::make_tuple (0.5, 0), std::make_tuple (0.5, 2), std::make_tuple (1.0, 0),
                     std::make_tuple (1.0, 2), std::make_tuple (1.0, 3), std::make_tuple (2.0, 0), std::make_tuple (2.0, 4)),
    [] (const testing::TestParamInfo<std::tuple<double, int>> &info) {
      return corpus::toString (kSamplings[std::get<1> (info.param)]) + std::string ("_thickness") +
             std::to_string (static_cast<int> (std::get<0> (info.param) * 10 + 0.5)) + "_tenths";
    });

class NoisyHoles : public testing::TestWithParam<std::tuple<int, int>>
{};

// Noise of 0.3 % of the diagonal along the normal, exact normals.
TEST_P (NoisyHoles, FoundAndCoveredWithinTheNoise)
{
  const double noise = 0.003;
  const auto c = makeCase (model (std::get<0> (GetParam ())), kSamplings[std::get<1> (GetParam ())], noise, false, true);
  const Outcome o = fillCase (c);
  const double sigma = noise * corpus::diagonal (c.shape);
  EXPECT_EQ (o.detection.found, o.detection.cut);
  EXPECT_EQ (o.detection.false_holes, 0u);
  EXPECT_TRUE (o.fill.kept_unchanged);
  // Coverage of the removed samples' noise-free positions (the surface to cover).
  EXPECT_GE (o.fill.coverage, 0.99);           // reached: 100 % (95.8 % on cube scan lines before the noise was measured right)
  EXPECT_LE (o.fill.max_error, 2.5 * sigma);  // reached: 2.06 sigma (cube, varying density)
}

INSTANTIATE_TEST_SUITE_P (EverySampling, NoisyHoles,
                          testing::Combine (testing::Values (0, 1), testing::Range (0, 6)), samplingName);

// The rim's noise, measured on scan lines (4 times denser along a line than
// across, as scanners sample). It sets the combination constraint's
// tolerance. It was a plane's RMS over the neighbours within 2.5 mean
// spacings: on scan lines those lie on one line, and a plane through that
// line and the normal fits them exactly, so it read 0.1 sigma. The fill then
// took noisy neighbours for overshoots and stopped early: coverage 45-72 %
// on fandisk and pyramid scans at noise 0.1-0.5 %, now 98-100 %. Read as 0.1
// sigma, the noise left the tolerance at its floor, 0.1 mean spacings.
class ScanLineNoise : public testing::TestWithParam<int>
{};

TEST_P (ScanLineNoise, IsMeasuredAndTheHolesClose)
{
  const double noise = 0.003;
  const auto c = makeCase (model (GetParam ()), Sampling::kScan, noise, false, true);
  const Outcome o = fillCase (c);
  const double sigma = noise * corpus::diagonal (c.shape);
  EXPECT_EQ (o.detection.found, o.detection.cut);
  EXPECT_TRUE (o.fill.kept_unchanged);
  EXPECT_GE (o.min_noise, 0.65 * sigma);  // reached: 0.75 (L-block) to 1.08 sigma
  EXPECT_LE (o.max_noise, 1.3 * sigma);
  EXPECT_GE (o.fill.coverage, 0.99);           // reached: 100 % (was 95.8 to 100 %)
  EXPECT_LE (o.fill.max_error, 2.5 * sigma);  // reached: 0.71 to 1.89 sigma
  // A hole reported closed is covered. Reached: 98.75 % (cube corner: 2 of
  // 160 samples at 1.50 and 1.53 pitches from the fill, covered meaning
  // within 1.5), 100 % on the others. Before the closure test's gate counted
  // the near neighbours only, 99.4 % (1 sample, at 1.79 pitches): the gap
  // narrowed and split in two, and the 99 % of closed_but_open counts
  // samples of a ball this small one by one.
  EXPECT_GE (o.min_closed_coverage, 0.985);
}

INSTANTIATE_TEST_SUITE_P (SmoothAndSharp, ScanLineNoise, testing::Values (0, 1, 2, 3),
                          [] (const testing::TestParamInfo<int> &info) { return model (info.param).name; });

// A sphere's caps from noisy points with exact normals, at noise 0.1 % and
// 0.5 % of the diagonal: the normals fit a linear field, so the first-order
// extension stays on and the caps stay round. With it switched off on every
// noisy rim (before), they came out flat: max error 0.018-0.021 (the cap's
// sagitta), 11 sigma at 0.1 %.
class NoisyPointsExactNormals : public testing::TestWithParam<std::tuple<int, int>>
{};

TEST_P (NoisyPointsExactNormals, RoundHolesStayRound)
{
  const double noise = std::get<0> (GetParam ()) == 0 ? 0.001 : 0.005;
  const auto c = makeCase (model (1), kSamplings[std::get<1> (GetParam ())], noise, false, true);
  const Outcome o = fillCase (c);
  const double sigma = noise * corpus::diagonal (c.shape);
  EXPECT_EQ (o.detection.found, o.detection.cut);
  EXPECT_TRUE (o.fill.kept_unchanged);
  EXPECT_GE (o.fill.coverage, 0.98);           // reached: 99.8 % to 100 %
  EXPECT_LE (o.fill.max_error, 1.5 * sigma);  // reached: 0.63 to 1.1 sigma
}

INSTANTIATE_TEST_SUITE_P (
    Sphere, NoisyPointsExactNormals, testing::Combine (testing::Values (0, 1), testing::Range (0, 6)),
    [] (const testing::TestParamInfo<std::tuple<int, int>> &info) {
      return std::string (std::get<0> (info.param) == 0 ? "noise01_" : "noise05_") +
             corpus::toString (kSamplings[std::get<1> (info.param)]);
    });

// Normals estimated by PCL (k = 16) on clean random samples.
TEST (EstimatedNormals, RandomSamplesFoundAndCovered)
{
  for (const int m : {0, 1, 3})
  {
    const auto c = makeCase (model (m), Sampling::kRandom, 0.0, true, true);
    const Outcome o = fillCase (c);
    const double p = corpus::pitch (c.shape, c.points);
    EXPECT_EQ (o.detection.found, o.detection.cut) << c.shape.name;
    EXPECT_EQ (o.detection.false_holes, 0u) << c.shape.name;
    // reached: 99.7 % (L-block) to 100 %; 97.8 % before the normals along
    // edges were refitted, 96.8 % before openings across edges were taken up again
    EXPECT_GE (o.fill.coverage, 0.99) << c.shape.name;
    // reached: 0.05 pitch (L-block); 1.95 pitches (cube) before the refit
    EXPECT_LE (o.fill.max_error, 0.5 * p) << c.shape.name;
  }
}

// Noise of 0.5 % of the diagonal (0.7 pitch) on random samples, PCA normals:
// at a rim they tilt by up to 1.4 rad. The empty-disc test unfolded the
// neighbours along those normals into the disc (14 of 26 rim points of the
// face's hole passed; 24 with the plain view of the fitted plane), and the
// loop tracing would not link two rim points of the ridge's hole whose
// oriented normals came out 137 degrees apart. Seed 1: one of the two holes
// found, 75.8 % covered.
TEST (EstimatedNormals, NoisyRandomSamplesOfARidgeGiveBothHoles)
{
  const double noise = 0.005;
  for (const unsigned seed : {1u, 2u, 3u, 4u})
  {
    auto c = makeCase (pcl_holefill::shapes::dihedral (), Sampling::kRandom, noise, true, true);
    c.seed = seed;
    const Outcome o = fillCase (c);
    EXPECT_EQ (o.detection.found, o.detection.cut) << "seed " << seed;
    EXPECT_EQ (o.detection.false_holes, 0u) << "seed " << seed;
    EXPECT_TRUE (o.fill.kept_unchanged) << "seed " << seed;
    EXPECT_GE (o.fill.coverage, 0.93) << "seed " << seed;  // reached: 95.3 % (seed 1) to 99.7 %
    // reached: 1.7 to 2.8 sigma, and 6.8 sigma on seed 2 (a spike on the
    // ridge: over the 3 sigma + 0.0034); margin 1.2 sigma
    EXPECT_LE (o.fill.max_error, 8.0 * noise * corpus::diagonal (c.shape)) << "seed " << seed;
  }
}

// PCA normals tilt towards the other face near a crease; the combination
// constraint read their tangent planes as exact and stopped the fronts short
// of the pyramid's apex: 86.8 % covered, one of two holes open. Its tolerance
// now grows with distance by the rim's normal spread.
TEST (EstimatedNormals, TheApexOfARandomSampledPyramidCloses)
{
  const auto c = makeCase (pcl_holefill::shapes::openPyramid (), Sampling::kRandom, 0.0, true, true);
  const Outcome o = fillCase (c);
  const double p = corpus::pitch (c.shape, c.points);
  EXPECT_EQ (o.detection.found, o.detection.cut);
  EXPECT_EQ (o.closed, o.reported);                   // reached: 2 of 2 (was 1)
  // reached: 100 %, 0.0016 (0.15 pitch) with the normals along the edges
  // refitted; 98.2 % and 0.0097 before; 86.8 % before the slope
  EXPECT_GE (o.fill.coverage, 0.99);
  EXPECT_LE (o.fill.max_error, 0.5 * p);
}

// A rim about one link in radius (a pyramid's apex, a hole on a ridge, at
// noise 0.3-0.5 %) came within a link of its start a quarter of the way
// round, zigzagging between two rows of rim points, and that quarter closed
// as a loop of its own: too small for a hole, so the rest was filled as a
// hole missing a quarter of its rim (90.5 % and 94.7 % covered, one hole
// reported open). A walk now closes only once it has been well away from home.
TEST (EstimatedNormals, ASmallRimAtNoiseIsOneLoopNotAPieceOfIt)
{
  const struct
  {
    pcl_holefill::shapes::Shape shape;
    Sampling sampling;
    double noise;
    bool estimated;
  } cases[] = {{pcl_holefill::shapes::openPyramid (), Sampling::kJittered, 0.003, false},
               {pcl_holefill::shapes::dihedral (), Sampling::kVoxel, 0.005, true}};
  for (const auto &k : cases)
  {
    const auto c = makeCase (k.shape, k.sampling, k.noise, k.estimated, true);
    const Outcome o = fillCase (c);
    const double sigma = k.noise * corpus::diagonal (c.shape);
    EXPECT_EQ (o.detection.found, o.detection.cut) << k.shape.name;
    EXPECT_EQ (o.closed, o.reported) << k.shape.name;  // reached: 2 of 2 (was 1)
    EXPECT_TRUE (o.fill.kept_unchanged) << k.shape.name;
    EXPECT_GE (o.fill.coverage, 0.99) << k.shape.name;  // reached: 100 % both (was 90.5 %, 94.7 %)
    // reached: 0.0035 (0.67 sigma) and 0.0088 (1.17 sigma); a margin of a quarter over the larger
    EXPECT_LE (o.fill.max_error, 1.5 * sigma) << k.shape.name;
  }
}

// PCA normals turn across every edge within ~2 pitches of it, and the fill
// continued them: edges came back rounded, with slits left along them
// (clean random samples: 96.8-98.9 % covered, max errors 0.009-0.030).
// Refitted to their faces for the fill (detail::refitCreaseNormal), the
// edges come back sharp.
TEST (EstimatedNormals, EdgesComeBackSharp)
{
  std::vector<pcl_holefill::shapes::Shape> shapes = {pcl_holefill::shapes::openPyramid (),
                                                     pcl_holefill::shapes::dihedral (), corpus::cylinder ()};
  pcl_holefill::shapes::Shape fandisk;
  std::string error;
  if (corpus::fandisk (fandisk, error))
    shapes.push_back (fandisk);
  for (const auto &shape : shapes)
  {
    const auto c = makeCase (shape, Sampling::kRandom, 0.0, true, true);
    const Outcome o = fillCase (c);
    const double p = corpus::pitch (c.shape, c.points);
    EXPECT_EQ (o.detection.found, o.detection.cut) << c.shape.name;
    EXPECT_EQ (o.closed, o.reported) << c.shape.name;
    EXPECT_GE (o.fill.coverage, 0.995) << c.shape.name;    // reached: 100 %
    EXPECT_LE (o.fill.max_error, 0.5 * p) << c.shape.name;  // reached: 0.04 (dihedral) to 0.2 pitch (fandisk)
    EXPECT_TRUE (o.fill.kept_unchanged) << c.shape.name;
  }
}

// A PCA normal of the wrong sign (the orientation failed at fandisk's noisy
// corner) 4 pitches from the corner hole and 1.5 above the face: nearly all
// its neighbours faced away, the empty-disc test left them out as the other
// side, and the point joined the rim; the loop ended there, open, and the
// hole went unfound (66.8 % covered). Detection now turns such a normal over.
TEST (EstimatedNormals, ANormalOfTheWrongSignDoesNotBreakARim)
{
  pcl_holefill::shapes::Shape fandisk;
  std::string error;
  // The test command installs libcgal-demo: without fandisk this case is not run, and says so.
  ASSERT_TRUE (corpus::fandisk (fandisk, error)) << error;
  const auto c = makeCase (fandisk, Sampling::kRandom, 0.005, true, true);
  const Outcome o = fillCase (c);
  EXPECT_EQ (o.detection.found, o.detection.cut);
  EXPECT_EQ (o.detection.false_holes, 0u);
  EXPECT_TRUE (o.fill.kept_unchanged);
  EXPECT_GE (o.fill.coverage, 0.95);  // reached: 96.3 %
}

// The refits read every estimated normal before they write one: the output
// is the same for any number of threads. Clean: the crease and quadric
// refits; sphere at 0.3 % noise: the smoothing of rough normals.
TEST (EstimatedNormals, RefittedNormalsGiveTheSameOutputOnOneOrTwoThreads)
{
  for (const auto &[shape, noise] : {std::pair (pcl_holefill::shapes::cube (), 0.0),
                                     std::pair (pcl_holefill::shapes::sphere (), 0.003)})
  {
    const auto c = makeCase (shape, Sampling::kRandom, noise, true, true);
    const Cloud::Ptr kept (new Cloud (corpus::build (c).kept));
    Cloud outputs[2];
    std::size_t refitted = 0;
    for (int run = 0; run < 2; ++run)
    {
      pcl_holefill::HoleFilling<pcl::PointNormal> filler;
      filler.setInputCloud (kept);
      filler.setNumberOfThreads (run + 1);
      filler.filter (outputs[run]);
      for (const auto &r : filler.getReports ())
        refitted += run == 0 ? r.refitted_normals : 0;
    }
    EXPECT_GT (refitted, 0u) << shape.name;  // reached: 265 over the cube's three holes, 836 on the sphere's two
    ASSERT_EQ (outputs[1].size (), outputs[0].size ()) << shape.name;
    EXPECT_EQ (std::memcmp (outputs[1].data (), outputs[0].data (), sizeof (pcl::PointNormal) * outputs[0].size ()), 0)
        << shape.name;
  }
}

// Noise of 0.3 % of the diagonal and normals estimated from the noisy points:
// the automatic sigma_n widens g2 to the spread of the rim's normals, so eq.
// (1) keeps enough neighbours to average the noise out. With the former fixed
// 0.1 the sphere's holes reached 0.0234 to 0.0427 (4.5 to 8.2 sigma) on four
// of these samplings. Rough normals on rims without a crease are now smoothed
// first (smoothNoisyNormals), and the spread measured on them is small: those
// holes get the sharp 0.1, creased ones up to 0.3.
class NoisyEstimatedNormals : public testing::TestWithParam<std::tuple<int, int>>
{};

TEST_P (NoisyEstimatedNormals, SigmaNFollowsTheNormalsAndTheFillStaysWithinTheNoise)
{
  const double noise = 0.003;
  const auto c = makeCase (model (std::get<0> (GetParam ())), kSamplings[std::get<1> (GetParam ())], noise, true, true);
  const Outcome o = fillCase (c);
  const double sigma = noise * corpus::diagonal (c.shape);
  EXPECT_EQ (o.detection.found, o.detection.cut);
  EXPECT_EQ (o.detection.false_holes, 0u);
  EXPECT_TRUE (o.fill.kept_unchanged);
  EXPECT_GE (o.min_sigma_n, 0.1f);  // reached: 0.1 to 0.3 (2 x the normals' spread, at most 0.3)
  EXPECT_LE (o.max_sigma_n, 0.3f);
  EXPECT_GE (o.fill.coverage, 0.98);           // reached: 99.8 % to 100 %
  EXPECT_LE (o.fill.max_error, 3.5 * sigma);  // reached: 0.9 to 2.9 sigma (L-block, random; was up to 3.7)
}

// Scan lines are left out: their estimated normals are rougher across the
// lines; coverage there is 98.5-100 %, but the cube's corner reaches 7.3
// sigma (doc/robustness.md).
INSTANTIATE_TEST_SUITE_P (EverySampling, NoisyEstimatedNormals,
                          testing::Combine (testing::Values (0, 1, 3), testing::Values (0, 1, 2, 3, 5)),
                          samplingName);

// Normals estimated at noise 0.1 % of the diagonal on a sphere: not linear
// enough to extrapolate near a crease, but the rim has none, so the
// first-order extension stays on and the caps stay round. Off, they came out
// flat: max error 0.016-0.021 (9-12 sigma).
TEST (SmoothRimEstimatedNormals, CapsStayRound)
{
  const double noise = 0.001;
  for (const int s : {0, 1, 2, 3, 5})
  {
    const auto c = makeCase (model (1), kSamplings[s], noise, true, true);
    const Outcome o = fillCase (c);
    const double sigma = noise * corpus::diagonal (c.shape);
    EXPECT_TRUE (o.fill.kept_unchanged) << corpus::toString (kSamplings[s]);
    EXPECT_GE (o.fill.coverage, 0.98) << corpus::toString (kSamplings[s]);         // reached: 99.8 % to 100 %
    // reached: 0.63 to 0.92 sigma (1.1 to 2.2 before the quadric ran on smoothed rims over up to 768
    // neighbours, 2.4 to 5.2 before it took more than 24)
    EXPECT_LE (o.fill.max_error, 1.5 * sigma) << corpus::toString (kSamplings[s]);
  }
}

// Clean rims with exact normals keep the sharp sigma_n (0.1) that recovers creases.
TEST (AutomaticSigmaN, StaysSharpOnCleanRims)
{
  for (const int m : {0, 3})
  {
    const Outcome o = fillCase (makeCase (model (m), Sampling::kPoisson, 0.0, false, true));
    EXPECT_FLOAT_EQ (o.min_sigma_n, 0.1f);
    EXPECT_FLOAT_EQ (o.max_sigma_n, 0.1f);
  }
}

/** The share of the case's estimated normals that point out (agree with
  * the exact ones) after orientNormalsConsistently, their signs first
  * scrambled: \a flip (called once per point, in order) says which to turn. */
template <typename Flip> double
outwardAfterOrienting (corpus::Case c, Flip flip)
{
  c.estimated = false;
  const Cloud exact = corpus::build (c).kept;
  c.estimated = true;
  Cloud cloud = corpus::build (c).kept;
  EXPECT_EQ (cloud.size (), exact.size ());
  if (cloud.empty () || cloud.size () != exact.size ())
    return 0.0;
  for (std::size_t i = 0; i < cloud.size (); ++i)
    if (flip (i))
      cloud[i].getNormalVector3fMap () *= -1.f;
  pcl_holefill::orientNormalsConsistently (cloud);
  std::size_t outward = 0;
  for (std::size_t i = 0; i < cloud.size (); ++i)
    outward += cloud[i].getNormalVector3fMap ().dot (exact[i].getNormalVector3fMap ()) > 0.f ? 1 : 0;
  return static_cast<double> (outward) / static_cast<double> (cloud.size ());
}

// Normals estimated by PCL from noisy random samples come with arbitrary
// signs; orientNormalsConsistently must make them agree with each other and
// point out of the closed model. Before every reached neighbour voted and
// the whole part decided its sign, one wrong step near the seed turned a
// third of a cube (or all of it) inside out, and detection found no hole.
TEST (NormalOrientation, NoisyRandomSamplesComeOutConsistentAndOutward)
{
  for (const int m : {0, 1, 2, 3})
    for (const double noise : {0.003, 0.005})
    {
      std::mt19937 random (7);
      const auto c = makeCase (model (m), Sampling::kRandom, noise, false, false);
      // reached: 99.7 % to 100 % (the rest sit on edges, where PCA normals are
      // blended); before: 40 % to 97 %
      EXPECT_GE (outwardAfterOrienting (c, [&] (std::size_t) { return random () % 2 != 0; }), 0.99)
          << c.shape.name << " noise " << noise;
    }
}

// A thin closed part: round a plate the faces' normals point away from and
// towards its centroid about as often, so that test does not decide, and
// the upward rule that decided instead was a coin toss (the sum of a closed
// surface's n_z is 0): it turned such parts inside out, and every convex
// edge then read as concave. The sign is now the enclosed volume's
// (partFacesInward). Before, the fin came out inward in all 6 cases.
// (A sheet 3 pitches thick is not oriented consistently at all: the k
// nearest neighbours of one face reach the other.)
TEST (NormalOrientation, ThinClosedPartsComeOutOutward)
{
  const pcl_holefill::shapes::Shape shape = corpus::fin ();
  for (const Sampling sampling : {Sampling::kRandom, Sampling::kPoisson, Sampling::kVoxel})
    for (const double noise : {0.0, 0.003})
    {
      const auto c = makeCase (shape, sampling, noise, false, false);
      // reached: 99.9 % (random, 0.3 %) and 100 % in the other cases
      EXPECT_GE (outwardAfterOrienting (c, [] (std::size_t i) { return i % 2 == 0; }), 0.99)
          << corpus::toString (sampling) << " noise " << noise;
    }
}

// Across an acute edge (a star's tips, 44 degrees) the faces' normals are
// 136 degrees apart, and a pair with one point on the edge and the other on
// the far face lies about in that face's plane: neither the dot product nor
// the tangent-plane sides tell a flipped face from a gently bent one, and
// those pairs voted for the flip. Once a neighbour on the point's own sheet
// has voted, only such neighbours do now (OrientationWalk::voteOn). Exact
// normals, signs scrambled.
TEST (NormalOrientation, AcuteEdgesDoNotTurnFacesOver)
{
  for (const Sampling sampling : {Sampling::kRandom, Sampling::kPoisson})
    for (const double noise : {0.0, 0.003})
    {
      const auto c = makeCase (corpus::starPrism (), sampling, noise, false, false);
      Cloud cloud = corpus::build (c).kept;
      const Cloud exact = cloud;
      for (std::size_t i = 0; i < cloud.size (); i += 2)
        cloud[i].getNormalVector3fMap () *= -1.f;
      pcl_holefill::orientNormalsConsistently (cloud);
      std::size_t inward = 0;
      for (std::size_t i = 0; i < cloud.size (); ++i)
        inward += cloud[i].getNormalVector3fMap ().dot (exact[i].getNormalVector3fMap ()) < 0.f ? 1 : 0;
      EXPECT_LE (inward, 20u) << corpus::toString (sampling) << " noise " << noise;  // reached: 0 (before: 342-1,422)
    }
}

// Where a front was cut (its candidates overshot on rough normals) while the
// rest closed, the hole is taken up again from the opening's own boundary:
// scan lines leave such openings (2-5 spacings) on a cube's face next to its
// corner and on an L-block's concave edge. On the sphere's scan lines the
// cut came from gaps of the rim itself (up to 3 spacings between scan
// lines); since those are bridged (ElasticSampler::controlCurve) its front
// is no longer cut. Since the closure test's gate counts the near
// neighbours only away from corners (HoleFilling::emptyDiscAt) it finds one
// small opening inside the sphere's cap (3 points, 0.67 of the disc across)
// and takes it up once; coverage is 100 % with and without.
TEST (Resume, AbandonedPartsOfAHoleAreFilledAndTheReportTellsTheTruth)
{
  for (const int m : {0, 1, 3})
  {
    const auto c = makeCase (model (m), Sampling::kScan, 0.0, false, true);
    const Outcome o = fillCase (c);
    const double p = corpus::pitch (c.shape, c.points);
    if (m == 1)
      EXPECT_LE (o.resumed, 1u) << c.name;  // was 1 before the rim's gaps were bridged, then 0
    else
      EXPECT_GE (o.resumed, 1u) << c.name;
    EXPECT_EQ (o.closed, o.reported) << c.name;
    EXPECT_EQ (o.closed_but_open, 0u) << c.name;
    // reached: 99.4 % (cube), 100 % (sphere, L-block); without taking holes
    // up again 97.9 % and 97.4 % (cube, sphere), with one hole reported open
    EXPECT_GE (o.fill.coverage, 0.985) << c.name;
    // reached: 0.0 (cube), 0.003 (sphere), 0.001 pitch (L-block)
    EXPECT_LE (o.fill.max_error, 0.25 * p) << c.name;
    EXPECT_TRUE (o.fill.kept_unchanged) << c.name;
  }
}

// A hole on a bored cube's bottom face that takes a sliver of a side face
// and a strip of the bore's wall. Each face's front moves along its own
// inward direction, parallel to the edges where the loop crosses them, and
// leaves a strip 2-3 spacings wide along an edge; the opening is found, but
// its boundary had 9 points on one face and 4 on the other, and their mean
// normal lay 67 degrees from the smaller face's: it was not taken up. The
// narrowest cone around them is 45 degrees wide (a right-angled edge).
TEST (Resume, AnOpeningAlongAnEdgeIsTakenUpWhateverEachFacesShare)
{
  struct Sampled
  {
    Sampling sampling;
    unsigned seed;
    double coverage;  //!< bound: reached less a margin (before: 98.0, 94.0, 92.2 %)
  };
  // reached 99.7, 99.7, 97.7 % (99.5, 98.3, 97.1 % before the closure
  // test's gate counted the near neighbours only: the strip's rest is found)
  for (const Sampled &s : {Sampled{Sampling::kRandom, 2, 0.99},
                           Sampled{Sampling::kScan, 2, 0.99},
                           Sampled{Sampling::kVoxel, 3, 0.97}})
  {
    auto c = makeCase (corpus::boredCube (), s.sampling, 0.0, false, false);
    c.seed = s.seed;
    const double p = corpus::pitch (c.shape, c.points);
    c.holes = {{Eigen::Vector3d (0.16, 0.35, 0.0), 10.4 * p}};
    const Outcome o = fillCase (c);
    const std::string name = corpus::toString (s.sampling);
    EXPECT_EQ (o.detection.found, 1u) << name;
    EXPECT_EQ (o.detection.false_holes, 0u) << name;
    EXPECT_TRUE (o.fill.kept_unchanged) << name;
    EXPECT_GE (o.resumed, 1u) << name;
    EXPECT_GE (o.fill.coverage, s.coverage) << name;
    EXPECT_LE (o.fill.max_error, 0.4 * p) << name;  // reached: 0.06 to 0.32 pitch
  }
}
