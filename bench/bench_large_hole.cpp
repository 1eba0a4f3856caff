/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 *
 * bench_large_hole [lattice|random|poisson] [points ...]
 *
 * One large hole, the polar cap of a sphere (radius 0.5) inside a ball
 * around the pole, cut from clouds of the given sizes (default 100,000,
 * 250,000, 1,000,000 and 4,000,000) so that 1,000, 4,000, 16,000, 64,000 and
 * 100,000 samples go missing (as long as that is at most a quarter of the
 * cloud). Samplings: the jittered Fibonacci lattice of shapes::sphere
 * (default), uniformly random or Poisson-disk (corpus samplers, up to
 * 1,000,000 points).
 *
 * Each row: points added, whether the hole was reported closed, the largest
 * distance of a filled point to the sphere, HoleFilling's seconds with 1 and
 * 2 threads and whether both outputs are byte-identical, PCL
 * NormalEstimationOMP (k = 16, 2 threads) on the same cloud in the same run
 * and the ratio of the two, the peak memory of the 2-thread fill above the
 * cloud itself (also in units of the cloud's size), and points added per
 * second. Every operation runs in a process of its own (bench::inChildProcess)
 * so that its peak memory is its own (and the parent never runs OpenMP),
 * kRepeats times, the thread counts alternating, and its least time counts:
 * on a shared 2-core machine one run of the same fill took from 3.6 to 4.4 s,
 * and the least time is the one other work disturbed least.
 * Last, the whole command on a 250,000-point file with 25,000 samples cut,
 * as a process, against a process that reads the file and runs
 * NormalEstimationOMP (this program, started with --normals FILE).
 * Cost linear in the hole shows as a steady "added / s" down the rows of
 * one cloud size.
 */
#include "bench_clouds.h"
#include "corpus.h"

#include <pcl_holefill/hole_filling.h>
#include "shapes.h"

#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using Cloud = pcl_holefill::shapes::Cloud;

namespace
{
constexpr unsigned kTimeLimit = 600;  // seconds per operation
constexpr int kRepeats = 3;            // runs of each operation; the least time counts
const Eigen::Vector3d kPole (0.5, 0.5, 1.0);

/** What one fill of the hole gave, beside its cost. */
struct FillOutcome
{
  bench::Measured cost;
  std::string digest;  //!< of the output's bytes
  std::size_t added = 0;
  bool closed = false;
  double max_error = 0.0;
};

/** HoleFilling with default options on \a cloud, in a child process: its
  * cost, and what it gave (points added, closure, the largest distance of a
  * filled point to the sphere, a digest of the output). */
FillOutcome
fillInChild (const Cloud::Ptr &cloud, unsigned threads)
{
  FillOutcome outcome;
  outcome.cost = bench::inChildProcess ([&] {
    pcl_holefill::HoleFilling<pcl::PointNormal> filler;
    filler.setInputCloud (cloud);
    filler.setNumberOfThreads (threads);
    Cloud output;
    // Only the filter is timed: the checks below (a digest of the whole
    // output among them) are the bench's, not the user's, and serial.
    const auto start = std::chrono::steady_clock::now ();
    filler.filter (output);
    const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
    const bool closed = filler.getReports ().size () == 1 && filler.getReports ()[0].closed;
    double max_error = 0.0;
    const auto sphere = pcl_holefill::shapes::sphere ();
    for (std::size_t i = cloud->size (); i < output.size (); ++i)
      max_error = std::max (max_error, sphere.distance (output[i].getVector3fMap ().cast<double> ()));
    char line[192];
    std::snprintf (line, sizeof (line), "%.6f %zu %d %.9g %llu", seconds, output.size () - cloud->size (),
                   closed ? 1 : 0, max_error,
                   static_cast<unsigned long long> (
                       bench::digest (output.data (), output.size () * sizeof (pcl::PointNormal))));
    return std::string (line);
  }, kTimeLimit);
  int closed = 0;
  char digest[32] = "";
  double seconds = 0.0;
  if (std::sscanf (outcome.cost.result.c_str (), "%lf %zu %d %lf %31s", &seconds, &outcome.added, &closed,
                   &outcome.max_error, digest) == 5)
    outcome.cost.seconds = seconds;
  outcome.closed = closed != 0;
  outcome.digest = digest;
  return outcome;
}

/** The run of the two that took less time (both gave the same output when
  * the fill is deterministic; the caller checks). */
FillOutcome
leastTime (const FillOutcome &a, const FillOutcome &b)
{
  if (!a.cost.finished)
    return a;
  return b.cost.finished && b.cost.seconds < a.cost.seconds ? b : a;
}

Cloud
sample (const std::string &sampling, std::size_t points)
{
  const auto sphere = pcl_holefill::shapes::sphere ();
  if (sampling == "lattice")
    return sphere.sample (points);
  return corpus::sampleSurface (sphere, points,
                                sampling == "random" ? corpus::Sampling::kRandom : corpus::Sampling::kPoisson, 1);
}

void
printRow (const Cloud &kept, std::size_t cut, const FillOutcome &one, const FillOutcome &two,
          const bench::Measured &normals, bool repeats_identical)
{
  const double cloud_mb = kept.size () * sizeof (pcl::PointNormal) / (1024.0 * 1024.0);
  if (!one.cost.finished || !two.cost.finished)
  {
    std::printf ("| %zu | %zu | - | - | - | > %u s | | | | | | | | |\n", kept.size (), cut, kTimeLimit);
    return;
  }
  const double t1 = one.cost.seconds, t2 = two.cost.seconds;
  std::printf ("| %zu | %zu | %zu | %s | %.5f | %.2f | %.2f | %.2f | %s | %.2f | %.2f | %.0f | %.2f | %.0f |\n",
               kept.size (), cut, two.added, two.closed ? "yes" : "no", two.max_error, t1, t2, t1 / t2,
               one.digest == two.digest && repeats_identical ? "yes" : "NO", normals.seconds, t2 / normals.seconds, two.cost.extra_mb,
               two.cost.extra_mb / cloud_mb, two.added / t2);
  std::fflush (stdout);
}
#ifdef PCL_HOLEFILL_TOOL
/** Wall seconds of the shell command \a line, and its exit status. */
bench::Measured
timeProcess (const std::string &line)
{
  return bench::inChildProcess ([&] { return std::to_string (std::system (line.c_str ())); }, kTimeLimit);
}

/** The yardstick for the command, process against process: the
  * whole command on a binary PCD file (start, read, detect, fill, write)
  * against this program started again to read the same file and run
  * NormalEstimationOMP (both load PCL's libraries). */
void
printCommandRow (const Cloud &kept, std::size_t cut)
{
  const std::string input = "/tmp/pcl_holefill_bench_large_hole.pcd";
  const std::string output = "/tmp/pcl_holefill_bench_large_hole_filled.pcd";
  pcl::io::savePCDFileBinary (input, kept);
  const bench::Measured command = timeProcess (std::string (PCL_HOLEFILL_TOOL) + " " + input + " " + output + " -q");
  char self[4096] = "";
  const ssize_t length = readlink ("/proc/self/exe", self, sizeof (self) - 1);
  const bench::Measured normals =
      timeProcess (std::string (self, length > 0 ? static_cast<std::size_t> (length) : 0) + " --normals " + input);
  std::remove (input.c_str ());
  std::remove (output.c_str ());
  std::printf ("| %zu | %zu | %.2f | %s | %.2f | %s | %.2f |\n", kept.size (), cut, command.seconds,
               command.result.c_str (), normals.seconds, normals.result.c_str (), command.seconds / normals.seconds);
}
#endif
}  // namespace

int
main (int argc, char **argv)
{
  pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
  if (argc == 3 && std::string (argv[1]) == "--normals")
  {
    // The yardstick process of printCommandRow.
    Cloud::Ptr cloud (new Cloud);
    if (pcl::io::loadPCDFile (argv[2], *cloud) != 0 || cloud->empty ())
    {
      std::fprintf (stderr, "%s: no points read from '%s'\n", argv[0], argv[2]);
      return 1;
    }
    bench::pclNormals (cloud, 2);
    return 0;
  }
  const std::string sampling = argc > 1 ? argv[1] : "lattice";
  std::vector<std::size_t> sizes;
  for (int i = 2; i < argc; ++i)
    sizes.push_back (std::strtoul (argv[i], nullptr, 10));
  if (sizes.empty ())
    sizes = {100000, 250000, 1000000, 4000000};
  const std::size_t cuts[] = {1000, 4000, 16000, 64000, 100000};

  std::printf ("%s sampling\n\n", sampling.c_str ());
  std::printf ("| input points | cut samples | points added | closed | max error | 1 thread (s) | 2 threads (s) "
               "| 1 / 2 threads | identical | NormalEstimationOMP (s) | ratio (2 threads) | peak MB | x cloud "
               "| added / s |\n");
  std::printf ("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const std::size_t n : sizes)
  {
    const Cloud full = sample (sampling, n);
    for (const std::size_t wanted : cuts)
    {
      if (4 * wanted > n)
        break;
      // The cap inside a ball of radius rho around the pole has area pi rho^2,
      // a share rho^2 of the sphere's (radius 0.5).
      const double rho = std::sqrt (static_cast<double> (wanted) / n);
      const auto cut = pcl_holefill::shapes::cutHoles (full, {{kPole, rho}});
      const Cloud::Ptr kept (new Cloud (cut.kept));
      FillOutcome one, two;
      bench::Measured normals;
      bool identical = true;
      for (int run = 0; run < kRepeats; ++run)
      {
        const FillOutcome one_now = fillInChild (kept, 1), two_now = fillInChild (kept, 2);
        const bench::Measured normals_now = bench::inChildProcess ([&] {
          bench::pclNormals (kept, 2);
          return std::string ();
        }, kTimeLimit);
        if (run > 0)
          identical = identical && one_now.digest == one.digest && two_now.digest == two.digest;
        one = run == 0 ? one_now : leastTime (one, one_now);
        two = run == 0 ? two_now : leastTime (two, two_now);
        normals = run == 0 || normals_now.seconds < normals.seconds ? normals_now : normals;
      }
      printRow (*kept, cut.removed.size (), one, two, normals, identical);
    }
  }
#ifdef PCL_HOLEFILL_TOOL
  // The target case: 25,000 of 250,000 samples cut, whole command on a file.
  const Cloud full = sample (sampling, 250000);
  const auto cut = pcl_holefill::shapes::cutHoles (full, {{kPole, std::sqrt (25000.0 / 250000.0)}});
  std::printf ("\nWhole command on a binary PCD file (start, read, detect, fill, write; 2 threads) against a\n"
               "process that starts, reads the same file and runs NormalEstimationOMP (k = 16, 2 threads):\n\n");
  std::printf ("| input points | cut samples | pcl_holefill command (s) | exit status | read + NormalEstimationOMP "
               "process (s) | exit status | ratio |\n| --- | --- | --- | --- | --- | --- | --- |\n");
  printCommandRow (cut.kept, cut.removed.size ());
#endif
  return 0;
}
