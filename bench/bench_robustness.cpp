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

#include <pcl_holefill/hole_boundary_estimation.h>
#include <pcl_holefill/hole_filling.h>

#include <pcl/console/print.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
struct Row
{
  corpus::DetectionScore detection;
  pcl_holefill::shapes::FillQuality fill;
  double seconds = 0.0;
  std::size_t closed = 0, reported = 0;
};

Row
run (const corpus::Case &c)
{
  Row row;
  const auto cut = corpus::build (c);
  const auto kept = pcl_holefill::shapes::Cloud::Ptr (new pcl_holefill::shapes::Cloud (cut.kept));
  const double pitch = corpus::pitch (c.shape, c.points);

  pcl_holefill::HoleBoundaryEstimation<pcl::PointNormal> estimation;
  estimation.setInputCloud (kept);
  std::vector<pcl_holefill::BoundaryLoop> loops;
  estimation.compute (loops);
  std::vector<std::vector<Eigen::Vector3f>> hole_loops;
  for (const auto &l : loops)
    if (l.is_hole)
    {
      hole_loops.emplace_back ();
      for (const auto i : l.indices)
        hole_loops.back ().push_back ((*kept)[i].getVector3fMap ());
    }
  row.detection = corpus::scoreDetection (hole_loops, c.holes, pitch);

  const auto start = std::chrono::steady_clock::now ();
  pcl_holefill::HoleFilling<pcl::PointNormal> filler;
  filler.setInputCloud (kept);
  pcl::PointCloud<pcl::PointNormal> output;
  filler.filter (output);
  row.seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
  for (const auto &r : filler.getReports ())
  {
    ++row.reported;
    row.closed += r.closed ? 1 : 0;
  }
  row.fill = pcl_holefill::shapes::evaluateFill (c.shape, cut, c.holes, output, pitch);
  return row;
}
}  // namespace

int
main (int argc, char **argv)
{
  pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
  const std::size_t points = argc > 1 ? std::strtoul (argv[1], nullptr, 10) : 20000;
  const std::string filter = argc > 2 ? argv[2] : "";
  std::printf ("| model | sampling | noise | normals | holes found / cut | false holes | reported closed | coverage | "
               "max error | mean error | added outside | seconds |\n");
  std::printf ("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
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
          const Row r = run (c);
          std::printf ("| %s | %s | %.1f%% | %s | %zu / %zu | %zu | %zu / %zu | %.1f%% | %.4f | %.5f | %zu | %.2f |\n",
                       shape.name.c_str (), corpus::toString (sampling), 100 * noise,
                       estimated ? "estimated" : "exact", r.detection.found, r.detection.cut, r.detection.false_holes,
                       r.closed, r.reported, 100 * r.fill.coverage, r.fill.max_error, r.fill.mean_error,
                       r.fill.outside, r.seconds);
          std::fflush (stdout);
        }
  return 0;
}
