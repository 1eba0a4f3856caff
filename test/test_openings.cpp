/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 *
 * Openings: a closed model with a whole face taken away (a box without its
 * lid, a cylinder without its cap: the underside of a scanned object, the
 * opening of a part), so that the rim is a crease all round and the rim's
 * normals say nothing about the missing face. Ground truth: the model's
 * exact surface and the samples taken away.
 */
#include "corpus.h"

#include <pcl_holefill/hole_boundary_estimation.h>
#include <pcl_holefill/hole_filling.h>

#include <pcl/console/print.h>
#include <pcl/kdtree/kdtree_flann.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>

namespace
{
using corpus::Sampling;
using pcl_holefill::shapes::Cloud;
using pcl_holefill::shapes::Shape;

/** The model's samples, split into those on the face at z = \a lid (taken away) and the rest. */
pcl_holefill::shapes::CutCloud
withoutLid (const Shape &shape, std::size_t points, Sampling sampling, unsigned seed, double lid, bool estimated)
{
  const Cloud cloud = corpus::sampleSurface (shape, points, sampling, seed);
  pcl_holefill::shapes::CutCloud cut;
  for (const auto &p : cloud)
    (std::abs (p.z - lid) < 1e-6 && p.normal_z > 0.99f ? cut.removed : cut.kept).push_back (p);
  if (estimated)
    corpus::estimateNormals (cut.kept);
  return cut;
}

/** \a shape without its faces at z = \a lid: a model whose opening was never
  * sampled (a scan that never saw the underside), not one cut afterwards. */
Shape
withoutFace (const Shape &shape, double lid, bool keep_the_face)
{
  Shape out = shape;
  out.faces.clear ();
  out.closed = false;
  for (const auto &f : shape.faces)
  {
    const bool on_lid = std::all_of (f.corners.begin (), f.corners.end (),
                                     [lid] (const Eigen::Vector3d &c) { return std::abs (c.z () - lid) < 1e-9; });
    if (on_lid == keep_the_face)
      out.faces.push_back (f);
  }
  return out;
}

struct OpeningFill
{
  std::size_t holes = 0;
  bool across = false, closed = false, input_unchanged = false;
  double coverage = 0.0;        //!< samples taken away within 1.5 pitches of an output point
  double max_error = 0.0;       //!< filled point to the true surface
  double off_lid = 0.0;         //!< farthest filled point from the lid's plane
  std::size_t filled = 0;
};

/** One report, filled across the opening and closed, the input untouched. */
void
expectClosedAcross (const OpeningFill &f, const std::string &what)
{
  EXPECT_EQ (f.holes, 1u) << what;
  EXPECT_TRUE (f.across) << what;
  EXPECT_TRUE (f.closed) << what;
  EXPECT_TRUE (f.input_unchanged) << what;
}

OpeningFill
fillOpening (const Shape &shape, const pcl_holefill::shapes::CutCloud &cut, double lid, double pitch)
{
  pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
  pcl_holefill::HoleFilling<pcl::PointNormal> filler;  // no option at all
  filler.setInputCloud (Cloud::Ptr (new Cloud (cut.kept)));
  Cloud output;
  filler.filter (output);
  OpeningFill f;
  f.holes = filler.getReports ().size ();
  if (f.holes == 1)
  {
    f.across = filler.getReports ()[0].across_opening;
    f.closed = filler.getReports ()[0].closed;
  }
  f.input_unchanged = output.size () >= cut.kept.size () &&
                      std::equal (cut.kept.begin (), cut.kept.end (), output.begin (), [] (const auto &a, const auto &b) {
                        return std::memcmp (&a, &b, sizeof (a)) == 0;
                      });
  f.filled = output.size () - cut.kept.size ();
  for (std::size_t i = cut.kept.size (); i < output.size (); ++i)
  {
    const Eigen::Vector3d p = output[i].getVector3fMap ().cast<double> ();
    f.max_error = std::max (f.max_error, shape.distance (p));
    f.off_lid = std::max (f.off_lid, std::abs (p.z () - lid));
  }
  pcl::KdTreeFLANN<pcl::PointNormal> tree;
  tree.setInputCloud (Cloud::Ptr (new Cloud (output)));
  std::size_t near = 0;
  pcl::Indices nearest (1);
  std::vector<float> sqr (1);
  for (const auto &p : cut.removed)
    if (tree.nearestKSearch (p, 1, nearest, sqr) == 1 && std::sqrt (sqr[0]) <= 1.5 * pitch)
      ++near;
  f.coverage = cut.removed.empty () ? 0.0 : static_cast<double> (near) / cut.removed.size ();
  return f;
}
}  // namespace

// Before: the fronts carried the four walls on past the rim, up to 0.97
// away (16,900 points added, 7.6 % of the lid covered, reported open).
// Random and Poisson-disk samples, exact and estimated normals.
TEST (Openings, ABoxWithoutItsLidIsClosedAcrossIt)
{
  const Shape cube = pcl_holefill::shapes::cube ();
  const std::size_t points = 30000;
  const double p = corpus::pitch (cube, points);
  // Not voxel-grid samples: their centroids along the crease lie inside
  // the cube and take the lid's normal (exact) or a blend (estimated), the
  // fill dives into the box rather than along its walls, and nothing yet
  // tells that from a fill closing in on an apex (left open, 0.90 of the
  // lid; see doc/parameters.md, "Openings").
  for (const auto sampling : {Sampling::kRandom, Sampling::kPoisson})
    for (const bool estimated : {false, true})
    {
      const auto cut = withoutLid (cube, points, sampling, 3, 1.0, estimated);
      const OpeningFill f = fillOpening (cube, cut, 1.0, p);
      const std::string what = std::string (corpus::toString (sampling)) + (estimated ? ", estimated" : ", exact");
      expectClosedAcross (f, what);
      // reached 100 %
      EXPECT_GE (f.coverage, 0.99) << what;
      // reached 0.20 pitch: the rim's copy is flattened onto its outermost
      // points, a row of samples from the crease (1.9 pitches before that);
      // the margin is 0.3 pitch
      EXPECT_LE (f.max_error, 0.5 * p) << what;
      EXPECT_LE (f.off_lid, 0.5 * p) << what;
      // about the input's density: 0.81-0.86 filled points per sample taken away
      EXPECT_LE (f.filled, cut.removed.size ()) << what;
    }
}

// A tube's end: the walls curve towards the loop's inside, so the vote
// "away from the existing neighbours" pointed the first ring outwards.
TEST (Openings, ACylinderWithoutItsCapIsClosedAcrossIt)
{
  const Shape cylinder = corpus::cylinder ();
  const std::size_t points = 20000;
  const double p = corpus::pitch (cylinder, points);
  for (const bool estimated : {false, true})
  {
    const auto cut = withoutLid (cylinder, points, Sampling::kRandom, 5, 0.9, estimated);
    const OpeningFill f = fillOpening (cylinder, cut, 0.9, p);
    EXPECT_EQ (f.holes, 1u);
    EXPECT_TRUE (f.across);
    EXPECT_TRUE (f.input_unchanged);
    EXPECT_GE (f.coverage, 0.99);  // reached 100 %
    // reached 0.30 pitch; the margin is 0.2 pitch
    EXPECT_LE (f.max_error, 0.5 * p);
    EXPECT_LE (f.off_lid, 0.5 * p);
    EXPECT_LE (f.filled, cut.removed.size ());
  }
}

// The gaps at an opening's rim point along the walls, across the loop's
// inside: a hole, every time (the sign of a vote of ~0 decided it before).
TEST (Openings, AreHolesNotBorders)
{
  const Shape cube = pcl_holefill::shapes::cube ();
  for (unsigned seed = 1; seed <= 3; ++seed)
  {
    const auto cut = withoutLid (cube, 20000, Sampling::kRandom, seed, 1.0, false);
    pcl_holefill::HoleBoundaryEstimation<pcl::PointNormal> estimation;
    estimation.setInputCloud (Cloud::Ptr (new Cloud (cut.kept)));
    std::vector<pcl_holefill::BoundaryLoop> loops;
    estimation.compute (loops);
    ASSERT_EQ (loops.size (), 1u) << seed;
    EXPECT_TRUE (loops[0].is_hole) << seed;
  }
}

// A box that was sampled without its lid (not cut from a closed box): the
// last row of samples lies up to a pitch short of the crease, and on scan
// lines, varying density and random samples the fronts stopped at the rim
// after 6-8 passes up the walls (the paper's ratio rule), too soon to count
// as run along them: 6-7 % of the lid covered, 0.10 off. With noise, the
// walls' own points, labelled concave by their noise, rejected every sample
// inwards of them (0.1 %: 10-11 % covered). Ground truth: the lid's surface
// (a jittered sampling of it, not the clouds' sampler) and the closed box.
TEST (Openings, ABoxSampledWithoutItsLidIsClosedAcrossIt)
{
  const Shape cube = pcl_holefill::shapes::cube ();
  const Shape open = withoutFace (cube, 1.0, false);
  const std::size_t points = 30000;
  const double p = corpus::pitch (open, points);
  pcl_holefill::shapes::CutCloud cut;
  cut.removed = corpus::sampleSurface (withoutFace (cube, 1.0, true), 12000, Sampling::kJittered, 9);
  const struct
  {
    Sampling sampling;
    double noise;
    bool estimated;
  } cases[] = {{Sampling::kScan, 0.0, false},
               {Sampling::kVarying, 0.0, false},
               {Sampling::kRandom, 0.0, false},
               {Sampling::kVoxel, 0.001, true},
               {Sampling::kRandom, 0.003, true}};
  for (const auto &c : cases)
  {
    cut.kept = corpus::sampleSurface (open, points, c.sampling, 3);
    corpus::addNoise (cut.kept, open, c.noise, 11);
    if (c.estimated)
      corpus::estimateNormals (cut.kept);
    const OpeningFill f = fillOpening (cube, cut, 1.0, p);
    const std::string what = std::string (corpus::toString (c.sampling)) + ", noise " + std::to_string (c.noise);
    expectClosedAcross (f, what);
    // reached 99.97-100 % (was 6-11 %)
    EXPECT_GE (f.coverage, 0.99) << what;
    // reached 0.09-0.32 pitch (was 7.7); the margin is 0.28 pitch
    EXPECT_LE (f.max_error, 0.6 * p) << what;
  }
}
