/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "hole_pictures.h"

#include <algorithm>

namespace pcl_holefill_tool
{
namespace
{
constexpr int kOverviewSize = 480;   // pixels, each of the two views
constexpr int kCloseUpSize = 240;    // pixels
constexpr std::size_t kCloseUpsPerRow = 4;
// A close-up shows the points within this many hole radii of the rim's centre.
constexpr float kCloseUpReachInRadii = 1.6f;

/** Every point as a splat coloured by what it is: input, rim (closed or open) or fill. */
std::vector<Splat>
colouredSplats (const pcl::PointCloud<pcl::PointNormal> &output, std::size_t input_points,
                const std::vector<pcl_holefill::HoleReport> &reports)
{
  std::vector<Splat> splats;
  splats.reserve (output.size ());
  for (std::size_t i = 0; i < output.size (); ++i)
    splats.push_back ({output[i].getVector3fMap (), output[i].getNormalVector3fMap (),
                       i < input_points ? HoleColours::input () : HoleColours::fill ()});
  for (const auto &r : reports)
    for (const auto i : r.boundary)
      if (i >= 0 && static_cast<std::size_t> (i) < input_points)
        splats[i].colour = r.closed ? HoleColours::closedRim () : HoleColours::openRim ();
  return splats;
}

/** One hole seen from outside the surface: the splats near it, viewed
  * against the mean normal of its rim (normals point outwards). */
Image
closeUp (const std::vector<Splat> &splats, const pcl_holefill::HoleReport &report)
{
  Eigen::Vector3f outward = Eigen::Vector3f::Zero ();
  for (const auto i : report.boundary)
    if (i >= 0 && static_cast<std::size_t> (i) < splats.size () && splats[i].normal.allFinite ())
      outward += splats[i].normal.normalized ();
  // A rim around a thin part or a whole end has no outside: a corner view.
  const Eigen::Vector3f view =
      outward.norm () > 0.2f * static_cast<float> (report.boundary.size ()) ? Eigen::Vector3f (-outward)
                                                                             : Eigen::Vector3f (-1.f, -1.f, -0.8f);
  const float reach = kCloseUpReachInRadii * 0.5f * std::max (report.diameter, 4.f * report.spacing);
  std::vector<Splat> near;
  for (const auto &s : splats)
    if ((s.position - report.centre).norm () <= reach)
      near.push_back (s);
  return renderSplats (near, view, kCloseUpSize);
}
}  // namespace

Image
holePicture (const pcl::PointCloud<pcl::PointNormal> &output, std::size_t input_points,
             const std::vector<pcl_holefill::HoleReport> &reports)
{
  const std::vector<Splat> splats = colouredSplats (output, input_points, reports);
  std::vector<Image> rows{sideBySide ({renderSplats (splats, Eigen::Vector3f (-1.f, -1.f, -0.8f), kOverviewSize),
                                       renderSplats (splats, Eigen::Vector3f (1.f, 1.f, 0.8f), kOverviewSize)})};
  std::vector<Image> row;
  for (std::size_t h = 0; h < std::min (reports.size (), kMaxCloseUps); ++h)
  {
    row.push_back (closeUp (splats, reports[h]));
    if (row.size () == kCloseUpsPerRow || h + 1 == std::min (reports.size (), kMaxCloseUps))
    {
      rows.push_back (sideBySide (row));
      row.clear ();
    }
  }
  return aboveEachOther (rows);
}

}  // namespace pcl_holefill_tool
