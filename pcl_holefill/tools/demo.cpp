/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "demo.h"
#include "cloud_writer.h"

#include "render.h"

#include <pcl_holefill/hole_filling.h>
#include "shapes.h"

#include <pcl/common/io.h>
#include <pcl/conversions.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

namespace pcl_holefill_tool
{
namespace
{
const Eigen::Vector3f kInputColour (0.78f, 0.78f, 0.8f);
const Eigen::Vector3f kFilledColour (1.f, 0.55f, 0.1f);

std::vector<Splat>
splats (const pcl_holefill::shapes::Cloud &cloud, std::size_t first_filled)
{
  std::vector<Splat> out;
  for (std::size_t i = 0; i < cloud.size (); ++i)
    out.push_back ({cloud[i].getVector3fMap (), cloud[i].getNormalVector3fMap (),
                    i < first_filled ? kInputColour : kFilledColour});
  return out;
}
}  // namespace

int
runDemo (const std::string &directory, bool quiet)
{
  namespace shapes = pcl_holefill::shapes;
  std::error_code ec;
  std::filesystem::create_directories (directory, ec);
  if (ec)
  {
    std::fprintf (stderr, "pcl_holefill: cannot create '%s': %s\n", directory.c_str (), ec.message ().c_str ());
    return 1;
  }
  // Two of the paper's Table 2 cases, each seen from where it shows its hole.
  const std::pair<shapes::PaperCase, Eigen::Vector3f> cases[] = {
      {shapes::paperCase ("cube (corner)"), Eigen::Vector3f (-1.f, -0.8f, -0.7f)},
      {shapes::paperCase ("sphere (cap)"), Eigen::Vector3f (-0.5f, -1.f, -0.9f)},
  };
  const std::pair<const char *, float> settings[] = {{"sharp", 0.1f}, {"smooth", pcl_holefill::kSup}};
  std::printf ("%-7s %-7s %8s %8s %10s %10s %9s %6s %8s\n", "model", "setting", "removed", "filled", "max error",
               "mean error", "covered", "closed", "seconds");
  std::vector<Image> rows;
  for (const auto &[c, view] : cases)
  {
    const auto cut = shapes::cutHoles (c.shape.sample (c.points), {c.hole});
    const double spacing = shapes::meanSpacing (cut.kept);
    std::vector<Image> row{renderSplats (splats (cut.kept, cut.kept.size ()), view, 320)};
    for (const auto &[name, sigma_n] : settings)
    {
      pcl_holefill::HoleFilling<pcl::PointNormal> filler;
      filler.setInputCloud (cut.kept.makeShared ());
      filler.setSigmaN (sigma_n);
      shapes::Cloud output;
      const auto start = std::chrono::steady_clock::now ();
      filler.filter (output);
      const double seconds = std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
      const auto q = shapes::evaluateFill (c.shape, cut, {c.hole}, output, spacing);
      const bool closed = !filler.getReports ().empty () && filler.getReports ()[0].closed;
      std::printf ("%-7s %-7s %8zu %8zu %10.5f %10.6f %8.1f%% %6s %8.3f\n", c.shape.name.c_str (), name,
                   cut.removed.size (), q.filled, q.max_error, q.mean_error, 100.0 * q.coverage,
                   closed ? "yes" : "no", seconds);
      pcl::PointCloud<pcl::PointXYZRGBNormal> coloured;
      pcl::copyPointCloud (output, coloured);
      for (std::size_t i = 0; i < coloured.size (); ++i)
      {
        const Eigen::Vector3f col = 255.f * (i < cut.kept.size () ? kInputColour : kFilledColour);
        coloured[i].r = static_cast<std::uint8_t> (col.x ());
        coloured[i].g = static_cast<std::uint8_t> (col.y ());
        coloured[i].b = static_cast<std::uint8_t> (col.z ());
      }
      const std::string ply = directory + "/demo_" + c.shape.name + "_" + name + ".ply";
      pcl::PCLPointCloud2 columns;
      pcl::toPCLPointCloud2 (coloured, columns);
      std::string error;
      if (!writePly (ply, columns, error))
      {
        std::fprintf (stderr, "pcl_holefill: %s\n", error.c_str ());
        return 1;
      }
      row.push_back (renderSplats (splats (output, cut.kept.size ()), view, 320));
    }
    rows.push_back (sideBySide (row));
  }
  std::string error;
  const std::string png = directory + "/demo.png";
  if (!savePng (aboveEachOther (rows), png, error))
  {
    std::fprintf (stderr, "pcl_holefill: %s\n", error.c_str ());
    return 1;
  }
  if (!quiet)
    std::printf ("\nWrote %s (columns: before, sharp, smooth; filled points orange) and the filled clouds\n"
                 "%s/demo_*.ply (open them in CloudCompare or MeshLab). Errors are distances to the true\n"
                 "surface of models in the unit cube; 'covered' counts removed samples within 1.5 spacings.\n",
                 png.c_str (), directory.c_str ());
  return 0;
}

}  // namespace pcl_holefill_tool
