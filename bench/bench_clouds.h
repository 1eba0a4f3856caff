/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include "shapes.h"

#include <pcl/features/normal_3d_omp.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace bench
{
/** \brief \a count balls of radius \a radius centred on the unit-cube
  * sphere, at least 3 radii apart: the holes of the large benchmark clouds. */
inline std::vector<pcl_holefill::shapes::Ball>
sphereHoles (std::size_t count, double radius, unsigned seed)
{
  std::mt19937 rng (seed);
  std::normal_distribution<double> gauss;
  std::vector<pcl_holefill::shapes::Ball> balls;
  for (int attempt = 0; attempt < 10000 && balls.size () < count; ++attempt)
  {
    const Eigen::Vector3d d (gauss (rng), gauss (rng), gauss (rng));
    const Eigen::Vector3d c = Eigen::Vector3d::Constant (0.5) + 0.5 * d.normalized ();
    if (std::all_of (balls.begin (), balls.end (), [&] (const auto &b) { return (b.centre - c).norm () > 3 * radius; }))
      balls.push_back ({c, radius});
  }
  return balls;
}

/** \brief The benchmark cloud: a sphere of \a points samples with 10 holes. */
inline pcl_holefill::shapes::CutCloud
sphereWithTenHoles (std::size_t points)
{
  return pcl_holefill::shapes::cutHoles (pcl_holefill::shapes::sphere ().sample (points), sphereHoles (10, 0.06, 3));
}

using Cloud = pcl_holefill::shapes::Cloud;

/** Median wall time of \a runs calls. */
inline double
seconds (const std::function<void ()> &work, int runs)
{
  std::vector<double> times;
  for (int i = 0; i < runs; ++i)
  {
    const auto start = std::chrono::steady_clock::now ();
    work ();
    times.push_back (std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ());
  }
  std::sort (times.begin (), times.end ());
  return times[times.size () / 2];
}

/** PCL NormalEstimationOMP (k = 16) on \a cloud: the yardstick of every bench table. */
inline double
pclNormals (const Cloud::Ptr &cloud, int threads)
{
  pcl::NormalEstimationOMP<pcl::PointNormal, pcl::Normal> estimation (threads);
  estimation.setInputCloud (cloud);
  estimation.setSearchMethod (pcl::search::KdTree<pcl::PointNormal>::Ptr (new pcl::search::KdTree<pcl::PointNormal>));
  estimation.setKSearch (16);
  pcl::PointCloud<pcl::Normal> normals;
  return seconds ([&] { estimation.compute (normals); }, 1);
}

/** A field of /proc/self/status, in kB. */
inline long
statusKb (const char *key)
{
  std::ifstream in ("/proc/self/status");
  std::string line;
  while (std::getline (in, line))
    if (line.compare (0, std::strlen (key), key) == 0)
      return std::strtol (line.c_str () + std::strlen (key), nullptr, 10);
  return 0;
}

/** What one operation cost, measured in a process of its own. */
struct Measured
{
  bool finished = false;  //!< ran to the end within the time limit
  double seconds = 0.0;
  double extra_mb = 0.0;  //!< peak resident memory above what the process held before
  std::string result;     //!< what the operation returned (a digest of its output, figures)
};

/** Runs \a work in a forked child, killed after \a limit seconds, so that its
  * peak memory can be read on its own (the peak is reset when the child
  * starts: the data built before the fork do not count). The parent must not
  * have run OpenMP before: libgomp's threads do not survive a fork, and the
  * child would wait for them forever. */
inline Measured
inChildProcess (const std::function<std::string ()> &work, unsigned limit)
{
  int channel[2];
  if (pipe (channel) != 0)
    return {};
  std::fflush (stdout);
  const pid_t child = fork ();
  if (child == 0)
  {
    close (channel[0]);
    std::ofstream ("/proc/self/clear_refs") << "5";
    const long base = statusKb ("VmRSS:");
    alarm (limit);
    const auto start = std::chrono::steady_clock::now ();
    const std::string result = work ();
    const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
    const std::string message =
        std::to_string (seconds) + " " + std::to_string (statusKb ("VmHWM:") - base) + " " + result;
    _exit (write (channel[1], message.data (), message.size ()) == static_cast<ssize_t> (message.size ()) ? 0 : 1);
  }
  close (channel[1]);
  std::string message;
  char buffer[256];
  for (ssize_t got; (got = read (channel[0], buffer, sizeof (buffer))) > 0;)
    message.append (buffer, static_cast<std::size_t> (got));
  close (channel[0]);
  int status = 0;
  waitpid (child, &status, 0);
  Measured measured;
  long extra_kb = 0;
  int consumed = 0;
  if (WIFEXITED (status) && WEXITSTATUS (status) == 0 &&
      std::sscanf (message.c_str (), "%lf %ld %n", &measured.seconds, &extra_kb, &consumed) == 2)
  {
    measured.finished = true;
    measured.extra_mb = extra_kb / 1024.0;
    measured.result = message.substr (static_cast<std::size_t> (consumed));
  }
  return measured;
}

/** FNV-1a over \a size bytes: tells two outputs apart without keeping both. */
inline std::uint64_t
digest (const void *data, std::size_t size)
{
  std::uint64_t hash = 1469598103934665603ull;
  const auto *bytes = static_cast<const unsigned char *> (data);
  for (std::size_t i = 0; i < size; ++i)
    hash = (hash ^ bytes[i]) * 1099511628211ull;
  return hash;
}

}  // namespace bench
