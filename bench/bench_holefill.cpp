/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 *
 * bench_holefill [points]: speed of detection and filling, each next to PCL
 * operations on the same cloud in the same run. Prints tables; exits 0.
 */
#include "bench_clouds.h"

#include <pcl_holefill/hole_boundary_estimation.h>
#include <pcl_holefill/hole_filling.h>
#include "shapes.h"

#include <pcl/features/boundary.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <thread>

namespace shapes = pcl_holefill::shapes;
using Cloud = shapes::Cloud;

namespace
{
using bench::pclNormals;
using bench::seconds;

void
detectionTable (std::size_t points, int threads)
{
  const auto holes = bench::sphereHoles (10, 0.06, 3);
  const auto cut = bench::sphereWithTenHoles (points);
  Cloud::Ptr cloud (new Cloud (cut.kept));
  std::printf ("\n== Detection: sphere, %zu points, %zu holes, %d threads\n", cloud->size (), holes.size (), threads);

  std::vector<pcl_holefill::BoundaryLoop> loops;
  const double ours = seconds (
      [&] {
        pcl_holefill::HoleBoundaryEstimation<pcl::PointNormal> estimation;
        estimation.setInputCloud (cloud);
        estimation.setNumberOfThreads (threads);
        estimation.compute (loops);
      },
      3);
  const std::size_t found = std::count_if (loops.begin (), loops.end (), [] (const auto &l) { return l.is_hole; });

  const double normals = pclNormals (cloud, threads);
  pcl::BoundaryEstimation<pcl::PointNormal, pcl::PointNormal, pcl::Boundary> boundary;
  boundary.setInputCloud (cloud);
  boundary.setInputNormals (cloud);
  boundary.setSearchMethod (pcl::search::KdTree<pcl::PointNormal>::Ptr (new pcl::search::KdTree<pcl::PointNormal>));
  boundary.setKSearch (16);
  pcl::PointCloud<pcl::Boundary> flags;
  const double pcl_boundary = seconds ([&] { boundary.compute (flags); }, 1);

  std::printf ("%-52s %10s %10s\n", "operation", "seconds", "ratio");
  std::printf ("%-52s %10.3f %10s\n", "pcl_holefill HoleBoundaryEstimation (loops incl.)", ours, "1.00");
  std::printf ("%-52s %10.3f %10.2f\n", "PCL NormalEstimationOMP (k = 16)", normals, normals / ours);
  std::printf ("%-52s %10.3f %10.2f\n", "PCL BoundaryEstimation (k = 16, flags only)", pcl_boundary, pcl_boundary / ours);
  std::printf ("holes found: %zu of %zu (%zu loops in all)\n", found, holes.size (), loops.size ());
}

void
fillTable (int threads)
{
  const auto cases = shapes::paperCases ();
  std::printf ("\n== Filling one hole per shape, %d threads\n", threads);
  std::printf ("%-24s %8s %8s %10s %10s %12s %12s\n", "case", "points", "filled", "fill s", "normals s",
               "fill/normals", "max error");
  for (const auto &c : cases)
  {
    const auto cut = shapes::cutHoles (c.shape.sample (c.points), {c.hole});
    Cloud::Ptr cloud (new Cloud (cut.kept));
    Cloud output;
    const double fill = seconds (
        [&] {
          pcl_holefill::HoleFilling<pcl::PointNormal> filler;
          filler.setInputCloud (cloud);
          filler.setSigmaN (c.smooth ? pcl_holefill::kSup : 0.1f);
          filler.setNumberOfThreads (threads);
          filler.filter (output);
        },
        5);
    const double normals = pclNormals (cloud, threads);
    const auto q = shapes::evaluateFill (c.shape, cut, {c.hole}, output, shapes::meanSpacing (cut.kept));
    std::printf ("%-24s %8zu %8zu %10.4f %10.4f %12.2f %12.5f\n", c.name, cloud->size (), q.filled, fill, normals,
                 fill / normals, q.max_error);
  }
}

void
pipelineTable (std::size_t points, int threads)
{
  const auto holes = bench::sphereHoles (10, 0.06, 3);
  const auto cut = bench::sphereWithTenHoles (points);
  Cloud::Ptr cloud (new Cloud (cut.kept));
  std::printf ("\n== Full pipeline (detection + filling): sphere, %zu points, %zu holes, %d threads\n",
               cloud->size (), holes.size (), threads);
  Cloud output;
  std::vector<pcl_holefill::HoleReport> reports;
  const double ours = seconds (
      [&] {
        pcl_holefill::HoleFilling<pcl::PointNormal> filler;
        filler.setInputCloud (cloud);
        filler.setSigmaN (pcl_holefill::kSup);
        filler.setNumberOfThreads (threads);
        filler.filter (output);
        reports = filler.getReports ();
      },
      3);
  const double normals = pclNormals (cloud, threads);
  const auto q = shapes::evaluateFill (shapes::sphere (), cut, holes, output, shapes::meanSpacing (cut.kept));
  const std::size_t closed = std::count_if (reports.begin (), reports.end (), [] (const auto &r) { return r.closed; });
  std::printf ("%-52s %10s %10s\n", "operation", "seconds", "ratio");
  std::printf ("%-52s %10.3f %10s\n", "pcl_holefill HoleFilling (all holes)", ours, "1.00");
  std::printf ("%-52s %10.3f %10.2f\n", "PCL NormalEstimationOMP (k = 16)", normals, normals / ours);
  std::printf ("holes closed: %zu of %zu, points added %zu, max error %.5f, coverage %.4f\n", closed, reports.size (),
               q.filled, q.max_error, q.coverage);
}
}  // namespace

int
main (int argc, char **argv)
{
  const std::size_t points = argc > 1 ? std::strtoul (argv[1], nullptr, 10) : 1000000;
  const int threads = std::max (1u, std::thread::hardware_concurrency ());
  if (points < 1000 || points > 50000000)
  {
    std::fprintf (stderr, "usage: %s [points, 1000..50000000 (default 1000000)]\n", argv[0]);
    return 2;
  }
  detectionTable (points, threads);
  fillTable (threads);
  pipelineTable (points, threads);
  return 0;
}
