/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include "shapes.h"

#include <string>
#include <vector>

/** \brief The robustness corpus: every model sampled in the ways users'
  * clouds are made, with noise and estimated normals, holes cut with known
  * ground truth. Deterministic (seeded). Test and bench code only: never
  * installed, never linked into the library. */
namespace corpus
{
using pcl_holefill::shapes::Ball;
using pcl_holefill::shapes::Cloud;
using pcl_holefill::shapes::CutCloud;
using pcl_holefill::shapes::Shape;

/** How the surface is turned into points. */
enum class Sampling
{
  kRandom,    //!< uniform random by area (white noise, as mesh-sampling tools)
  kPoisson,   //!< maximal Poisson-disk (blue noise)
  kJittered,  //!< a jittered grid per face (Fibonacci lattice on the sphere)
  kVoxel,     //!< dense random sampling, then PCL VoxelGrid (as pcl_mesh_sampling)
  kScan,      //!< points along parallel lines, 4 times denser along a line than across
  kVarying    //!< Poisson-disk whose density varies 4 times across the model
};

const char *
toString (Sampling s);

/** Every sampling, in a fixed order. */
std::vector<Sampling>
allSamplings ();

/** \brief About \a points samples of \a shape with exact unit normals. */
Cloud
sampleSurface (const Shape &shape, std::size_t points, Sampling sampling, unsigned seed);

/** \brief The sampling pitch sqrt(area / points): the spacing that the
  * corpus states hole sizes and errors in (independent of the sampler,
  * unlike the nearest-neighbour distance, which is 0.5 pitch for random
  * sampling and 0.9 for Poisson-disk). */
double
pitch (const Shape &shape, std::size_t points);

/** \brief Length of the diagonal of the shape's bounding box. */
double
diagonal (const Shape &shape);

/** \brief Moves each point along its exact normal by Gaussian noise of std
  * \a fraction times the bounding-box diagonal. */
void
addNoise (Cloud &cloud, const Shape &shape, double fraction, unsigned seed);

/** \brief Moves a \a fraction of the points, chosen at random, off the
  * surface along their exact normal by 1 to 4 pitches (either side, uniform),
  * as the stray returns of a scanner (mixed pixels, reflections); their
  * normals stay the surface's. */
void
addStrays (Cloud &cloud, double fraction, double pitch, unsigned seed);

/** \brief Replaces the normals by PCL's NormalEstimation (k = 16), each
  * oriented to agree with the exact normal it replaces. */
void
estimateNormals (Cloud &cloud);

// Shapes of the corpus beyond the paper's (all in the unit cube).
Shape cylinder ();  //!< closed, axis z, radius 0.3, height 0.8, meshed finely
Shape torus ();     //!< major radius 0.32, minor 0.14, axis z, meshed finely
Shape fin ();       //!< a thin plate 0.9 x 0.6 x 0.04: two faces close together
Shape sheet (double thickness);  //!< 0.9 x 0.6 x thickness, centred at z = 0.5: sheet metal
Shape lBlock ();    //!< an L-shaped solid: convex and concave edges
Shape boredCube (); //!< the unit cube with a bore of radius 0.22 along z through its middle
Shape starPrism (); //!< a five-pointed star (tips 0.45, notches 0.2 from the axis) 0.3 high: edges of 44 degrees

/** \brief fandisk from Debian's libcgal-demo (data.tar.gz), scaled into the
  * unit cube; false when the package is not installed. */
bool
fandisk (Shape &shape, std::string &error);

/** \brief \a mesh's vertices as the cloud (what a user who has only a mesh
  * passes), normals the area-weighted mean of the faces around each vertex:
  * a sampling the corpus's samplers do not make, dense along curved strips
  * and feature lines, sparse across flat faces. */
Cloud
meshVertices (const Shape &mesh);

/** \brief A test case: a model, a sampling, and holes to cut. */
struct Case
{
  std::string name;
  Shape shape;
  std::size_t points = 0;
  Sampling sampling = Sampling::kPoisson;
  double noise = 0.0;      //!< fraction of the bounding-box diagonal
  bool estimated = false;  //!< normals from NormalEstimation instead of exact
  double strays = 0.0;     //!< fraction of the points moved off the surface (addStrays)
  std::vector<Ball> holes;
  unsigned seed = 1;
};

/** \brief The case's cloud, cut: kept (the input to fill) and removed. */
CutCloud
build (const Case &c);

/** \brief How detection did on one case: a cut ball is found when a hole
  * loop lies around it (most loop points within its radius plus 3 pitches).*/
struct DetectionScore
{
  std::size_t cut = 0;
  std::size_t found = 0;
  std::size_t false_holes = 0;
};

DetectionScore
scoreDetection (const std::vector<std::vector<Eigen::Vector3f>> &hole_loops, const std::vector<Ball> &holes,
                double pitch);

/** \brief HoleBoundaryEstimation with no option on \a kept, its hole loops
  * scored against the cut \a holes (scoreDetection). */
DetectionScore
detectHoles (const Cloud::Ptr &kept, const std::vector<Ball> &holes, double pitch);

}  // namespace corpus

namespace corpus
{
/** \brief Holes on \a shape for the corpus: a corner or apex, an edge, a
  * smooth or flat part, as available, of diameters between 8 and 30 pitches
  * for a cloud of \a points. Empty for a hole-free model. */
std::vector<Ball>
holesOf (const Shape &shape, std::size_t points);

/** \brief A ball 20 pitches across at each of the 8 corners of fin () (a
  * plate 5.2 pitches thick at 20,000 points): each takes the corners of both
  * faces and the end and side strips between them, one loop round the plate. */
std::vector<Ball>
finCornerHoles (std::size_t points);

/** \brief The models of the corpus (fandisk when libcgal-demo is there). */
std::vector<Shape>
models ();
}  // namespace corpus

namespace corpus
{
/** \brief One case run as a user would (HoleFilling with no option), scored
  * against the ground truth: detection (HoleBoundaryEstimation's hole loops
  * against the cut balls) and the fill (evaluateFill, spacing = pitch). */
struct Outcome
{
  DetectionScore detection;
  /** Errors and spill of the fill; its coverage counts the removed samples
    * at their noise-free positions (the surface to cover). */
  pcl_holefill::shapes::FillQuality fill;
  std::size_t input = 0, output = 0;
  std::size_t reported = 0, closed = 0;  //!< holes in HoleFilling's reports, and of those reported closed
  /** Per cut ball, the reports about it (whose rim's centre is nearest to it). */
  std::vector<std::size_t> reports_per_ball;
  /** Cut balls whose removed samples are covered (>= 99 % within 1.5 pitches of an output point). */
  std::size_t covered_balls = 0;
  /** Reports claiming closed whose nearest cut ball is not covered, and the reverse. */
  std::size_t closed_but_open = 0, open_but_covered = 0;
  /** The lowest share of a cut ball's removed samples covered where a report about it claims closed. */
  double min_closed_coverage = 1.0;
  /** Holes whose fill was taken up again from what was left open. */
  std::size_t resumed = 0;
  /** Filled points per removed sample: 1 = the input's density (valid when covered). */
  double density = 0.0;
  /** Mean nearest-neighbour distance of the filled points over the kept points' near the holes. */
  double spacing_ratio = 0.0;
  /** Smallest and largest sigma_n the holes were filled with (chosen per hole by default). */
  float min_sigma_n = 0.f, max_sigma_n = 0.f;
  /** Smallest and largest noise the holes' rims were measured to have (HoleReport::noise). */
  float min_noise = 0.f, max_noise = 0.f;
  double seconds = 0.0;                  //!< HoleFilling::filter alone
};

Outcome
runCase (const Case &c);
}  // namespace corpus

namespace corpus
{
/** \brief Any method's output scored against a case's truth, for methods
  * that may move or resample every point (PCL's MLS, Poisson): its points
  * within a pitch of a cut ball that are not input points are its fill. */
struct MethodScore
{
  double coverage = 0.0;    //!< cut samples within 1.5 pitches of an output point
  double max_error = 0.0;   //!< fill to the true surface
  double mean_error = 0.0;
  std::size_t fill = 0;
};

MethodScore
scoreMethod (const Case &c, const CutCloud &cut, const Cloud &output);
}  // namespace corpus

