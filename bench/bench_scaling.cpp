/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 *
 * bench_scaling [largest, default 4000000] [time limit s, default 300]
 *
 * The scaling table: clouds of 100,000, 1,000,000 and 4,000,000 points with
 * 10 holes; for each, pcl_holefill's whole pipeline next to PCL's
 * NormalEstimationOMP, BoundaryEstimation, MovingLeastSquares
 * (VOXEL_GRID_DILATION) and Poisson (depth 9), each in a process of its own
 * so that its peak memory can be read: seconds, peak memory above the
 * cloud itself, and that peak in units of the cloud's size.
 */
#include "bench_clouds.h"

#include <pcl_holefill/hole_filling.h>

#include <pcl/features/boundary.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/search/kdtree.h>
#include <pcl/surface/mls.h>
#include <pcl/surface/poisson.h>

#include <cstdio>
#include <string>
#include <thread>

using Cloud = pcl_holefill::shapes::Cloud;

namespace
{
template <typename Search>
typename Search::Ptr
kdtree ()
{
  return typename Search::Ptr (new Search);
}

/** The operation \a name on \a cloud (what each child process runs). */
void
runOperation (const std::string &name, const Cloud::Ptr &cloud, int threads)
{
  if (name == "pcl_holefill")
  {
    pcl_holefill::HoleFilling<pcl::PointNormal> filler;
    filler.setInputCloud (cloud);
    filler.setSigmaN (pcl_holefill::kSup);
    filler.setNumberOfThreads (threads);
    Cloud out;
    filler.filter (out);
  }
  else if (name == "NormalEstimationOMP")
  {
    pcl::NormalEstimationOMP<pcl::PointNormal, pcl::Normal> estimation (threads);
    estimation.setInputCloud (cloud);
    estimation.setSearchMethod (kdtree<pcl::search::KdTree<pcl::PointNormal>> ());
    estimation.setKSearch (16);
    pcl::PointCloud<pcl::Normal> normals;
    estimation.compute (normals);
  }
  else if (name == "BoundaryEstimation")
  {
    pcl::BoundaryEstimation<pcl::PointNormal, pcl::PointNormal, pcl::Boundary> boundary;
    boundary.setInputCloud (cloud);
    boundary.setInputNormals (cloud);
    boundary.setSearchMethod (kdtree<pcl::search::KdTree<pcl::PointNormal>> ());
    boundary.setKSearch (16);
    pcl::PointCloud<pcl::Boundary> flags;
    boundary.compute (flags);
  }
  else if (name == "MLS dilation")
  {
    const double h = pcl_holefill::shapes::meanSpacing (*cloud);
    pcl::MovingLeastSquares<pcl::PointNormal, pcl::PointNormal> mls;
    mls.setInputCloud (cloud);
    mls.setSearchMethod (kdtree<pcl::search::KdTree<pcl::PointNormal>> ());
    mls.setSearchRadius (6.0 * h);
    mls.setPolynomialOrder (2);
    mls.setUpsamplingMethod (pcl::MovingLeastSquares<pcl::PointNormal, pcl::PointNormal>::VOXEL_GRID_DILATION);
    mls.setDilationVoxelSize (static_cast<float> (1.5 * h));
    mls.setDilationIterations (static_cast<int> (0.06 / (1.5 * h)) + 1);
    mls.setNumberOfThreads (threads);
    Cloud out;
    mls.process (out);
  }
  else if (name == "Poisson depth 9")
  {
    pcl::Poisson<pcl::PointNormal> poisson;
    poisson.setInputCloud (cloud);
    poisson.setDepth (9);
    poisson.setThreads (threads);
    pcl::PolygonMesh mesh;
    poisson.reconstruct (mesh);
  }
}

/** \a name on a fresh cloud of \a points, in a child process killed after \a limit seconds. */
bench::Measured
measure (const std::string &name, std::size_t points, int threads, unsigned limit)
{
  const Cloud::Ptr cloud (new Cloud (bench::sphereWithTenHoles (points).kept));
  return bench::inChildProcess ([&] {
    runOperation (name, cloud, threads);
    return std::string ();
  }, limit);
}
}  // namespace

int
main (int argc, char **argv)
{
  const std::size_t largest = argc > 1 ? std::strtoul (argv[1], nullptr, 10) : 4000000;
  const unsigned limit = argc > 2 ? static_cast<unsigned> (std::strtoul (argv[2], nullptr, 10)) : 300;
  const int threads = std::max (1u, std::thread::hardware_concurrency ());
  const std::vector<std::size_t> sizes{100000, 1000000, 4000000};
  const char *operations[] = {"NormalEstimationOMP", "pcl_holefill", "BoundaryEstimation", "MLS dilation",
                              "Poisson depth 9"};
  std::printf ("Sphere with 10 holes, %d threads, each operation in its own process (limit %u s).\n", threads, limit);
  std::printf ("'extra MB' is the peak resident memory above the cloud itself; 'x cloud' divides it by the\n"
               "cloud's size (points x %zu bytes).\n\n", sizeof (pcl::PointNormal));
  std::printf ("%10s  %-22s %10s %14s %10s %9s\n", "points", "operation", "seconds", "vs normals", "extra MB",
               "x cloud");
  std::vector<double> pipeline_seconds;
  for (const std::size_t n : sizes)
  {
    if (n > largest)
      break;
    const double cloud_mb = n * sizeof (pcl::PointNormal) / (1024.0 * 1024.0);
    double normals = 0.0;
    for (const char *op : operations)
    {
      const bench::Measured o = measure (op, n, threads, limit);
      if (std::string (op) == "NormalEstimationOMP")
        normals = o.seconds;
      if (std::string (op) == "pcl_holefill")
        pipeline_seconds.push_back (o.finished ? o.seconds : 0.0);
      if (!o.finished)
      {
        std::printf ("%10zu  %-22s %10s\n", n, op, "> limit");
        continue;
      }
      char ratio[32] = "";
      if (normals > 0.0)
        std::snprintf (ratio, sizeof (ratio), "%.2f", o.seconds / normals);
      std::printf ("%10zu  %-22s %10.3f %14s %10.1f %9.2f\n", n, op, o.seconds, ratio, o.extra_mb,
                   o.extra_mb / cloud_mb);
      std::fflush (stdout);
    }
  }
  if (pipeline_seconds.size () == 3 && pipeline_seconds[1] > 0.0)
    std::printf ("\npcl_holefill, 4,000,000 / 1,000,000 points: %.2f times the time (linear: 4)\n",
                 pipeline_seconds[2] / pipeline_seconds[1]);
  return 0;
}
