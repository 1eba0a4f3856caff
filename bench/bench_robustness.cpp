/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 *
 * bench_robustness [POINTS] [FILTER]: every model of the corpus x every
 * sampling x noise x normals, holes cut with known ground truth; prints one
 * row per case: holes found / cut, false holes, coverage, max and mean error
 * to the true surface, points added outside the holes, seconds.
 */
#include "corpus.h"

#include <pcl/console/print.h>

#include <cstdio>
#include <cstdlib>
#include <string>


int
main (int argc, char **argv)
{
  pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
  const std::size_t points = argc > 1 ? std::strtoul (argv[1], nullptr, 10) : 20000;
  const std::string filter = argc > 2 ? argv[2] : "";
  std::printf ("| model | sampling | noise | normals | holes found / cut | false holes | reported closed | closed but open | "
               "open but covered | coverage | density | NN spacing ratio | max error | mean error | added outside | seconds |\n");
  std::printf ("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const auto &shape : corpus::models ())
    for (const auto sampling : corpus::allSamplings ())
      for (const double noise : {0.0, 0.003})
        for (const bool estimated : {false, true})
        {
          if (estimated && noise == 0.0 && sampling != corpus::Sampling::kRandom)
            continue;
          corpus::Case c;
          c.shape = shape;
          c.points = points;
          c.sampling = sampling;
          c.noise = noise;
          c.estimated = estimated;
          c.holes = corpus::holesOf (shape, points);
          c.name = shape.name + "/" + corpus::toString (sampling);
          if (!filter.empty () && c.name.find (filter) == std::string::npos)
            continue;
          const corpus::Outcome r = corpus::runCase (c);
          std::printf ("| %s | %s | %.1f%% | %s | %zu / %zu | %zu | %zu / %zu | %zu | %zu | %.1f%% | %.2f | %.2f | %.4f | %.5f | %zu | %.2f |\n",
                       shape.name.c_str (), corpus::toString (sampling), 100 * noise,
                       estimated ? "estimated" : "exact", r.detection.found, r.detection.cut, r.detection.false_holes,
                       r.closed, r.reported, r.closed_but_open, r.open_but_covered, 100 * r.fill.coverage, r.density, r.spacing_ratio, r.fill.max_error, r.fill.mean_error,
                       r.fill.outside, r.seconds);
          std::fflush (stdout);
        }
  return 0;
}
