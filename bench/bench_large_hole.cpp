/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 *
 * bench_large_hole [poisson|random|lattice] [points ...]: one large hole (a
 * polar cap of a sphere, cut by a ball of radius 0.3 around the pole of a
 * 0.5 sphere) on samplings of the given sizes (default 63,000, 125,000,
 * 250,000, 500,000, 1,000,000): Poisson-disk (default), uniformly random
 * (corpus samplers) or the jittered Fibonacci lattice of shapes::sphere. For each: points added, HoleFilling's seconds (1 and 2
 * threads), PCL NormalEstimationOMP (k = 16, 2 threads) on the same cloud in
 * the same run, the ratio of the two, and points added per second. Cost
 * linear in the hole shows as a constant "added / s" down the table.
 */
#include "bench_clouds.h"
#include "corpus.h"

#include <pcl_holefill/hole_filling.h>
#include "shapes.h"

#include <pcl/console/print.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/search/kdtree.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using Cloud = pcl_holefill::shapes::Cloud;

int
main (int argc, char **argv)
{
  pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
  const std::string sampling = argc > 1 ? argv[1] : "poisson";
  std::vector<std::size_t> sizes;
  for (int i = 2; i < argc; ++i)
    sizes.push_back (std::strtoul (argv[i], nullptr, 10));
  if (sizes.empty ())
    sizes = {63000, 125000, 250000, 500000, 1000000};
  const auto sample = [&] (std::size_t n) {
    const auto sphere = pcl_holefill::shapes::sphere ();
    if (sampling == "lattice")
      return sphere.sample (n);
    return corpus::sampleSurface (sphere, n, sampling == "random" ? corpus::Sampling::kRandom
                                                                  : corpus::Sampling::kPoisson, 1);
  };
  std::printf ("%s sampling\n\n", sampling.c_str ());
  std::printf ("| input points | cut samples | points added | closed | holefill 1 thread (s) | holefill 2 threads (s) "
               "| 1 / 2 threads | identical | NormalEstimationOMP (s) | ratio (2 threads) | added / s |\n");
  std::printf ("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const std::size_t n : sizes)
  {
    const auto cut = pcl_holefill::shapes::cutHoles (sample (n), {{Eigen::Vector3d (0.5, 0.5, 1.0), 0.3}});
    const Cloud::Ptr kept (new Cloud (cut.kept));
    double t[2] = {0.0, 0.0};
    Cloud outputs[2];
    bool closed = false;
    for (const unsigned threads : {1u, 2u})
    {
      pcl_holefill::HoleFilling<pcl::PointNormal> filler;
      filler.setInputCloud (kept);
      filler.setNumberOfThreads (threads);
      t[threads - 1] = bench::seconds ([&] { filler.filter (outputs[threads - 1]); }, 1);
      closed = filler.getReports ().size () == 1 && filler.getReports ()[0].closed;
    }
    const Cloud &output = outputs[1];
    const bool identical = outputs[0].size () == outputs[1].size () &&
                           std::memcmp (outputs[0].data (), outputs[1].data (),
                                        outputs[0].size () * sizeof (pcl::PointNormal)) == 0;
    const double ne = bench::pclNormals (kept, 2);
    const std::size_t added = output.size () - kept->size ();
    std::printf ("| %zu | %zu | %zu | %s | %.2f | %.2f | %.2f | %s | %.2f | %.2f | %.0f |\n", kept->size (),
                 cut.removed.size (), added, closed ? "yes" : "no", t[0], t[1], t[0] / t[1], identical ? "yes" : "NO",
                 ne, t[1] / ne, added / t[1]);
    std::fflush (stdout);
  }
  return 0;
}
