/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 *
 * The pcl_holefill command: reads a PCD or PLY cloud, fills its holes, writes
 * the result in the style of PCL's own tools (pcl_mls_smoothing, ...).
 */
#include "cloud_assembly.h"
#include "cloud_file.h"
#include "demo.h"
#include "fill_options.h"
#include "hole_pictures.h"
#include "render.h"
#include "report_json.h"

#include <pcl_holefill/hole_boundary_estimation.h>
#include <pcl_holefill/hole_filling.h>

#include <pcl/console/print.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <utility>

#include <unistd.h>

using namespace pcl_holefill_tool;

namespace
{
int
fail (const std::string &message, int code = 1)
{
  std::fprintf (stderr, "pcl_holefill: %s\n", message.c_str ());
  return code;
}

bool
writePicture (const Options &options, const pcl::PointCloud<pcl::PointNormal> &output, std::size_t input_points,
              const std::vector<pcl_holefill::HoleReport> &reports, std::string &error)
{
  return savePng (holePicture (output, input_points, reports), options.png_file, error);
}

/** Whether \a path can be written (an existing file, or a new one in an
  * existing, writable folder), checked before any work. */
bool
writable (const std::string &path)
{
  if (::access (path.c_str (), F_OK) == 0)
    return ::access (path.c_str (), W_OK) == 0;
  const auto slash = path.find_last_of ('/');
  const std::string folder = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr (0, slash));
  return ::access (folder.c_str (), W_OK | X_OK) == 0;
}

/** -detect_only: the loops, as a cloud field, a report and a -holes file. */
int
detectOnly (const Options &options, const PreparedCloud &prepared)
{
  pcl_holefill::HoleBoundaryEstimation<pcl::PointNormal> estimation;
  estimation.setInputCloud (prepared.points);
  estimation.setMinHoleSize (options.min_hole_size);
  estimation.setMaxHoleDiameter (options.max_hole_size);
  estimation.setNumberOfThreads (static_cast<unsigned int> (options.threads));
  std::vector<pcl_holefill::BoundaryLoop> loops;
  estimation.compute (loops);
  std::string error;
  pcl::PCLPointCloud2 output;
  if (!assembleDetection (prepared, loops, static_cast<unsigned int> (options.threads), output, error) ||
      !saveCloud (options.output, output, error))
    return fail (error);
  const std::string holes_path = options.output + ".holes.txt";
  if (!writeHoles (holes_path, loops, error))
    return fail (error);
  if (!options.report_file.empty ())
  {
    std::ofstream report (options.report_file);
    report << loopsJson (options.input, prepared.points->size (), loops,
                         {estimation.getSamplingEvenness (), estimation.getMinHoleSizeUsed ()});
    if (!report)
      return fail ("cannot write '" + options.report_file + "'");
  }
  const auto holes = std::count_if (loops.begin (), loops.end (), [] (const auto &l) { return l.is_hole; });
  if (!options.quiet)
    std::fprintf (stderr,
                  "pcl_holefill: %ld holes (of at least %.2g sampling pitches) and %ld borders found; "
                  "wrote %s and %s\n",
                  static_cast<long> (holes), static_cast<double> (estimation.getMinHoleSizeUsed ()),
                  static_cast<long> (loops.size ()) - static_cast<long> (holes), options.output.c_str (),
                  holes_path.c_str ());
  return 0;
}

int
run (const Options &options)
{
  const auto start = std::chrono::steady_clock::now ();
  if (cloudFormat (options.output).empty ())
    return fail (unknownFormatMessage (options.output));
  const std::string holes_path = options.detect_only ? options.output + ".holes.txt" : std::string ();
  for (const std::string *path : {&options.output, &options.report_file, &options.png_file, &holes_path})
    if (!path->empty () && !writable (*path))
      return fail ("cannot write '" + *path + "' (no such folder, or no permission)");
  std::string error;
  pcl::PCLPointCloud2 file_cloud;
  if (!loadCloud (options.input, file_cloud, error))
    return fail (error);
  PreparedCloud prepared;
  if (!prepareCloud (std::move (file_cloud), static_cast<unsigned int> (options.threads), prepared, error))
    return fail (options.input + ": " + error);
  if (!options.quiet)
  {
    std::fprintf (stderr, "pcl_holefill: %s: %zu points (%zu finite)\n", options.input.c_str (),
                  prepared.points->size (), prepared.finite_points);
    if (prepared.normals_unusable)
      std::fprintf (stderr, "pcl_holefill: note: most normals in the input are zero or not finite: estimated "
                            "(k = %d) and oriented for the fill; the input rows keep theirs\n",
                    prepared.normal_neighbours);
    else if (prepared.normals_estimated)
      std::fprintf (stderr, "pcl_holefill: note: no normals in the input: estimated (k = %d) and oriented\n",
                    prepared.normal_neighbours);
  }

  if (options.detect_only)
    return detectOnly (options, prepared);

  pcl_holefill::HoleFilling<pcl::PointNormal> filler;
  configure (options, filler);
  if (!options.holes_file.empty ())
  {
    std::vector<pcl_holefill::BoundaryLoop> holes;
    if (!readHoles (options.holes_file, prepared.points->size (), holes, error))
      return fail (error);
    filler.setHoles (holes);
  }
  if (!options.quiet)
    filler.setProgressCallback ([] (std::size_t hole, std::size_t holes, const pcl_holefill::HoleReport &r) {
      if (r.closed)
        std::fprintf (stderr, "pcl_holefill: hole %zu/%zu: %u passes, %zu points added, %s, closed\n", hole + 1,
                      holes, r.passes, r.points_added, pcl_holefill::toString (r.termination));
      else if (r.withdrawn)
        std::fprintf (stderr, "pcl_holefill: hole %zu/%zu: %u passes, %s, open (about %g across left): the patch "
                      "grew past the hole, withdrawn\n", hole + 1, holes, r.passes,
                      pcl_holefill::toString (r.termination), r.open_diameter);
      else
        std::fprintf (stderr, "pcl_holefill: hole %zu/%zu: %u passes, %zu points added, %s, open (about %g across "
                      "left)\n", hole + 1, holes, r.passes, r.points_added, pcl_holefill::toString (r.termination),
                      r.open_diameter);
    });
  filler.setInputCloud (prepared.points);
  pcl::PointCloud<pcl::PointNormal> filtered;
  filler.filter (filtered);
  if (filtered.size () < prepared.points->size ())
    return fail ("the parameters were refused (see the message above)");
  if (filler.getReports ().empty () && !options.quiet)
    std::fprintf (stderr, "pcl_holefill: note: no hole found: the cloud is copied through\n");

  pcl::PCLPointCloud2 output;
  if (!assembleOutput (prepared, filtered, filler.getReports (), static_cast<unsigned int> (options.threads), output,
                       error))
    return fail (error);
  if (!saveCloud (options.output, output, error))
    return fail (error);
  if (!options.report_file.empty ())
  {
    std::ofstream report (options.report_file);
    report << reportJson (options.input, prepared.points->size (), filler.getReports (), prepared.origin);
    if (!report)
      return fail ("cannot write '" + options.report_file + "'");
  }
  if (!options.png_file.empty () &&
      !writePicture (options, filtered, prepared.points->size (), filler.getReports (), error))
    return fail (error);
  if (!options.quiet)
    std::fprintf (stderr, "pcl_holefill: %zu holes, %zu points added, wrote %s in %.2f s\n",
                  filler.getReports ().size (), filtered.size () - prepared.points->size (), options.output.c_str (),
                  std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ());
  return 0;
}
}  // namespace

int
main (int argc, char **argv)
{
  Options options;
  std::string error;
  if (!parseOptions (argc, argv, options, error))
    return fail (error, 2);
  if (options.help)
  {
    std::fputs (usage (argv[0]).c_str (), stdout);
    return 0;
  }
  // The library's own warnings stay; its chatter does not.
  pcl::console::setVerbosityLevel (options.quiet     ? pcl::console::L_ERROR
                                   : options.verbose ? pcl::console::L_DEBUG
                                                     : pcl::console::L_WARN);
  if (!options.demo_dir.empty ())
    return runDemo (options.demo_dir, options.quiet);
  return run (options);
}
