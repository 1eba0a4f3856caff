/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "report_json.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace pcl_holefill_tool
{
namespace
{
std::string
quoted (const std::string &text)
{
  std::string out = "\"";
  for (const char c : text)
  {
    if (c == '"' || c == '\\')
      out += '\\';
    if (static_cast<unsigned char> (c) < 0x20)
      continue;  // control characters have no place in a file name
    out += c;
  }
  return out + "\"";
}

/** [i, j, ...] */
std::string
indexList (const pcl::Indices &indices)
{
  std::ostringstream out;
  out << '[';
  for (std::size_t k = 0; k < indices.size (); ++k)
    out << (k ? ", " : "") << indices[k];
  out << ']';
  return out.str ();
}
/** "[x, y, z]" of \a local + \a origin, to the digits map coordinates need. */
std::string
coordinates (const Eigen::Vector3f &local, const Eigen::Vector3d &origin)
{
  constexpr int kSignificantDigits = 12;  // 1 mm at 1e8 m
  const Eigen::Vector3d p = local.cast<double> () + origin;
  std::ostringstream out;
  out << std::setprecision (kSignificantDigits) << '[' << p.x () << ", " << p.y () << ", " << p.z () << ']';
  return out.str ();
}
}  // namespace

std::string
reportJson (const std::string &input, std::size_t input_points, const std::vector<pcl_holefill::HoleReport> &reports,
            const Eigen::Vector3d &origin)
{
  std::size_t filled = 0;
  for (const auto &r : reports)
    filled += r.points_added;
  std::ostringstream out;
  out << "{\n  \"input\": " << quoted (input) << ",\n  \"input_points\": " << input_points
      << ",\n  \"filled_points\": " << filled << ",\n  \"holes\": [";
  for (std::size_t i = 0; i < reports.size (); ++i)
  {
    const auto &r = reports[i];
    out << (i ? "," : "") << "\n    {\"boundary_points\": " << r.boundary_points << ", \"diameter\": " << r.diameter
        << ", \"passes\": " << r.passes << ", \"points_added\": " << r.points_added
        << ", \"first_output_index\": " << r.first_output_index << ", \"termination\": \""
        << pcl_holefill::toString (r.termination) << "\", \"closed\": " << (r.closed ? "true" : "false")
        << ", \"spacing\": " << r.spacing << ", \"equilibrium_distance\": " << r.equilibrium_distance
        << ", \"open_points\": " << r.open_points << ", \"open_diameter\": " << r.open_diameter
        << ", \"outside_bound\": " << r.outside_bound << ", \"beyond_rim\": " << r.beyond_rim
        << ", \"resumed\": " << r.resumed << ", \"refitted_normals\": " << r.refitted_normals << ", \"centre\": " << coordinates (r.centre, origin)
        << ", \"pitch\": " << r.pitch
        << ", \"radius\": " << r.radius << ", \"noise\": " << r.noise
        << ", \"first_order\": " << (r.first_order ? "true" : "false")
        << ", \"across_opening\": " << (r.across_opening ? "true" : "false")
        << ", \"withdrawn\": " << (r.withdrawn ? "true" : "false") << ", \"sigma_n\": ";
    if (std::isinf (r.sigma_n))
      out << "\"sup\"";  // JSON has no infinity
    else
      out << r.sigma_n;
    out << ", \"boundary\": " << indexList (r.boundary) << "}";
  }
  out << (reports.empty () ? "]" : "\n  ]") << "\n}\n";
  return out.str ();
}

std::string
loopsJson (const std::string &input, std::size_t input_points, const std::vector<pcl_holefill::BoundaryLoop> &loops,
           const DetectionSummary &summary)
{
  std::ostringstream out;
  out << "{\n  \"input\": " << quoted (input) << ",\n  \"input_points\": " << input_points
      << ",\n  \"sampling_evenness\": " << summary.sampling_evenness
      << ",\n  \"min_hole_size\": " << summary.min_hole_size << ",\n  \"loops\": [";
  for (std::size_t i = 0; i < loops.size (); ++i)
  {
    const auto &l = loops[i];
    out << (i ? "," : "") << "\n    {\"hole\": " << (l.is_hole ? "true" : "false")
        << ", \"closed\": " << (l.closed ? "true" : "false") << ", \"diameter\": " << l.diameter
        << ", \"length\": " << l.length << ", \"spacing\": " << l.mean_spacing << ", \"pitch\": " << l.pitch
        << ", \"indices\": " << indexList (l.indices) << "}";
  }
  out << (loops.empty () ? "]" : "\n  ]") << "\n}\n";
  return out.str ();
}

}  // namespace pcl_holefill_tool
