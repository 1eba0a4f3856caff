/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 *
 * bench_robustness [POINTS] [FILTER] [fast] [strays]: every model of the corpus x
 * every sampling x noise (0, 0.1, 0.3, 0.5 % of the diagonal) x normals
 * (exact; estimated on noisy clouds and on clean random ones), holes cut
 * with known ground truth; prints one row per case: holes found / cut, false
 * holes, coverage, max and mean error to the true surface, points added
 * outside the holes, seconds, and beside them PCL MovingLeastSquares and PCL
 * Poisson on the same input with exact normals (left out with "fast": they
 * take 5 s a case, pcl_holefill 0.05 s). With "strays", the clean cases
 * instead, each with 0.5 % of its points moved 1 to 4 pitches off the surface
 * (corpus::addStrays), exact and estimated normals. With "corners", the fin
 * alone with a hole at each of its 8 corners (corpus::finCornerHoles), every
 * sampling, noise and normals as the corpus.
 */
#include "corpus.h"
#include "reference_methods.h"

#include <pcl/console/print.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
/** "coverage / max error" of PCL's MLS and Poisson on the case, or dashes. */
std::string
referenceColumns (const corpus::Case &c, bool run)
{
  if (!run)
    return "- | - | - | - |";
  const auto cut = corpus::build (c);
  const corpus::Cloud::Ptr kept (new corpus::Cloud (cut.kept));
  const double p = corpus::pitch (c.shape, c.points);
  double largest = 0.0, mls_seconds = 0.0, poisson_seconds = 0.0;
  for (const auto &b : c.holes)
    largest = std::max (largest, b.radius);
  // MLS is local (radius 3.6 pitches): run on the points around the holes
  // it gives the same fill there as on the whole cloud, 20 times faster (its
  // dilation fills the whole bounding grid, 23 s a case at 20,000 points).
  const corpus::Cloud::Ptr near_holes (new corpus::Cloud);
  for (const auto &q : *kept)
    if (std::any_of (c.holes.begin (), c.holes.end (), [&] (const corpus::Ball &b) {
          return (q.getVector3fMap ().cast<double> () - b.centre).norm () <= b.radius + 8.0 * p;
        }))
      near_holes->push_back (q);
  // MLS on the pitch (not h, which is half of it on random samples); Poisson
  // on the whole cloud (it is global) at depth 8: cells of 1/256 of the
  // model, a fifth of the pitch at 20,000 points (depth 9 gives the same fill).
  const auto mls = corpus::scoreMethod (c, cut, bench::runMls (near_holes, 0.6 * p, largest, mls_seconds));
  const auto poisson = corpus::scoreMethod (c, cut, bench::runPoisson (kept, 8, poisson_seconds));
  char text[200];
  std::snprintf (text, sizeof (text), "%.1f%% | %.4f | %.1f%% | %.4f |", 100 * mls.coverage, mls.max_error,
                 100 * poisson.coverage, poisson.max_error);
  return text;
}
}  // namespace

int
main (int argc, char **argv)
{
  pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
  const std::size_t points = argc > 1 ? std::strtoul (argv[1], nullptr, 10) : 20000;
  const std::string filter = argc > 2 ? argv[2] : "";
  const bool references = !(argc > 3 && std::string (argv[3]) == "fast");
  const std::string mode = argc > 4 ? argv[4] : "";
  const double strays = mode == "strays" ? 0.005 : 0.0;
  const bool corners = mode == "corners";
  std::printf ("| model | sampling | noise | normals | holes found / cut | false holes | reported closed | closed but open | "
               "open but covered | coverage | density | NN spacing ratio | max error | mean error | added outside | seconds "
               "| MLS coverage | MLS max error | Poisson coverage | Poisson max error |\n");
  std::printf ("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- "
               "| --- | --- |\n");
  const std::vector<corpus::Shape> shapes = corners ? std::vector<corpus::Shape>{corpus::fin ()} : corpus::models ();
  for (const auto &shape : shapes)
    for (const auto sampling : corpus::allSamplings ())
      for (const double noise : {0.0, 0.001, 0.003, 0.005})
        for (const bool estimated : {false, true})
        {
          if (strays > 0.0 ? noise > 0.0 : estimated && noise == 0.0 && sampling != corpus::Sampling::kRandom)
            continue;
          corpus::Case c;
          c.shape = shape;
          c.points = points;
          c.sampling = sampling;
          c.noise = noise;
          c.estimated = estimated;
          c.strays = strays;
          c.holes = corners ? corpus::finCornerHoles (points) : corpus::holesOf (shape, points);
          c.name = shape.name + "/" + corpus::toString (sampling);
          if (!filter.empty () && c.name.find (filter) == std::string::npos)
            continue;
          const corpus::Outcome r = corpus::runCase (c);
          std::printf ("| %s | %s | %.1f%% | %s | %zu / %zu | %zu | %zu / %zu | %zu | %zu | %.1f%% | %.2f | %.2f | %.4f | "
                       "%.5f | %zu | %.2f | %s\n",
                       shape.name.c_str (), corpus::toString (sampling), 100 * noise,
                       estimated ? "estimated" : "exact", r.detection.found, r.detection.cut, r.detection.false_holes,
                       r.closed, r.reported, r.closed_but_open, r.open_but_covered, 100 * r.fill.coverage, r.density,
                       r.spacing_ratio, r.fill.max_error, r.fill.mean_error, r.fill.outside, r.seconds,
                       referenceColumns (c, references && !estimated).c_str ());
          std::fflush (stdout);
        }
  return 0;
}
