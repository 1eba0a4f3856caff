/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 *
 * evaluate_table2 OUTPUT_DIR [fandisk.off]
 *
 * The paper's Table 2 protocol, side by side with what a PCL user would
 * otherwise pick: each model in the unit cube, a hole cut at a sharp feature,
 * error = distance from a point to the true surface. Writes
 * OUTPUT_DIR/results.md and OUTPUT_DIR/results/<case>.png (points coloured by
 * their error, as the paper's Fig. 16).
 */
#include "off_mesh.h"
#include "reference_methods.h"

#include "../pcl_holefill/tools/render.h"

#include <pcl_holefill/hole_filling.h>
#include <pcl_holefill/detail/point_grid.h>
#include "shapes.h"

#include <pcl/search/kdtree.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

namespace shapes = pcl_holefill::shapes;
using Cloud = shapes::Cloud;
using pcl_holefill::detail::PointGrid;
using pcl_holefill_tool::Splat;

namespace
{
struct Case
{
  std::string name;
  shapes::Shape shape;
  std::size_t points;
  shapes::Ball hole;
  bool smooth;       //!< the smooth setting is the one to judge here
  double paper_max;  //!< the paper's Table 2 max error for its method (0: none)
};

struct Score
{
  std::string method;
  bool ran = false;
  std::size_t fill = 0;
  double max_error = 0.0, mean_error = 0.0;
  double gap_mean = 0.0, gap_max = 0.0, covered = 0.0;
  double unchanged = 0.0;      //!< share of input points found as they were
  std::size_t outside = 0;     //!< new points away from the hole and from the input
  double seconds = 0.0;
  std::vector<Splat> splats;
};

PointGrid
gridOf (const std::vector<Eigen::Vector3f> &points)
{
  PointGrid grid (PointGrid::suggestCellSize (points, 8));
  grid.build (points);
  return grid;
}

std::vector<Eigen::Vector3f>
positionsOf (const Cloud &cloud)
{
  std::vector<Eigen::Vector3f> out;
  for (const auto &p : cloud)
    if (p.getVector3fMap ().allFinite ())
      out.push_back (p.getVector3fMap ());
  return out;
}

/** Scores any method's output: points that are not input points are "new";
  * new points inside the hole ball are its fill. */
Score
score (const std::string &method, const Case &c, const shapes::CutCloud &cut, const Cloud &output, double h,
       double seconds, double error_scale)
{
  Score s;
  s.method = method;
  s.ran = true;
  s.seconds = seconds;
  const auto input = positionsOf (cut.kept);
  const auto out = positionsOf (output);
  if (out.empty ())
    return s;
  const PointGrid input_grid = gridOf (input), output_grid = gridOf (out);
  std::vector<PointGrid::Neighbour> near;
  std::size_t unchanged = 0;
  for (const auto &p : input)
  {
    output_grid.nearestK (p, 1, near);
    unchanged += !near.empty () && near[0].sqr_distance == 0.f;
  }
  s.unchanged = static_cast<double> (unchanged) / input.size ();
  for (const auto &p : out)
  {
    input_grid.nearestK (p, 1, near);
    const bool is_input = !near.empty () && near[0].sqr_distance == 0.f;
    const bool in_hole = (p.cast<double> () - c.hole.centre).norm () <= c.hole.radius + h;
    Eigen::Vector3f colour (0.78f, 0.78f, 0.8f);
    if (!is_input && in_hole)
    {
      const double e = c.shape.distance (p.cast<double> ());
      s.max_error = std::max (s.max_error, e);
      s.mean_error += e;
      ++s.fill;
      colour = pcl_holefill_tool::heatColour (static_cast<float> (e / error_scale));
    }
    else if (!is_input && std::sqrt (near[0].sqr_distance) > h)
    {
      ++s.outside;
      colour = Eigen::Vector3f (0.6f, 0.2f, 0.8f);
    }
    s.splats.push_back ({p, Eigen::Vector3f::Zero (), colour});
  }
  s.mean_error = s.fill ? s.mean_error / s.fill : 0.0;
  std::size_t covered = 0;
  for (const auto &r : cut.removed)
  {
    output_grid.nearestK (r.getVector3fMap (), 1, near);
    const double gap = std::sqrt (near[0].sqr_distance);
    s.gap_mean += gap;
    s.gap_max = std::max (s.gap_max, gap);
    covered += gap <= 1.5 * h;
  }
  s.gap_mean /= std::max<std::size_t> (1, cut.removed.size ());
  s.covered = static_cast<double> (covered) / std::max<std::size_t> (1, cut.removed.size ());
  return s;
}

/** Normals for the splats: from the output where it has them, else pointing away from the model's centre. */
void
attachNormals (Score &s, const Cloud &output)
{
  std::size_t k = 0;
  for (const auto &p : output)
  {
    if (!p.getVector3fMap ().allFinite ())
      continue;
    Eigen::Vector3f n = p.getNormalVector3fMap ();
    if (!n.allFinite () || n.norm () < 0.5f)
      n = (p.getVector3fMap () - Eigen::Vector3f::Constant (0.5f)).normalized ();
    s.splats[k++].normal = n;
  }
}

template <typename Work>
double
timed (Work work)
{
  const auto start = std::chrono::steady_clock::now ();
  work ();
  return std::chrono::duration<double> (std::chrono::steady_clock::now () - start).count ();
}

Cloud
runHoleFill (const Cloud::Ptr &input, float sigma_n, double &seconds)
{
  Cloud output;
  pcl_holefill::HoleFilling<pcl::PointNormal> filler;
  filler.setInputCloud (input);
  filler.setSigmaN (sigma_n);
  seconds = timed ([&] { filler.filter (output); });
  return output;
}

std::string
row (const std::string &case_name, const Score &s)
{
  char line[512];
  std::snprintf (line, sizeof (line),
                 "| %s | %s | %zu | %.4f | %.5f | %.4f | %.4f | %.1f %% | %.0f %% | %zu | %.2f |\n", case_name.c_str (),
                 s.method.c_str (), s.fill, s.max_error, s.mean_error, s.gap_mean, s.gap_max, 100.0 * s.covered,
                 100.0 * s.unchanged, s.outside, s.seconds);
  return line;
}
}  // namespace

int
main (int argc, char **argv)
{
  if (argc < 2 || argc > 3)
  {
    std::fprintf (stderr, "usage: %s OUTPUT_DIR [fandisk.off]\n", argv[0]);
    return 2;
  }
  const std::filesystem::path out_dir = argv[1];
  std::filesystem::create_directories (out_dir / "results");
  std::vector<Case> cases;
  for (const auto &c : shapes::paperCases ())
    cases.push_back ({c.name, c.shape, c.points, c.hole, c.smooth, c.paper_max_error});
  if (argc == 3)
  {
    shapes::Shape fandisk;
    std::string error;
    if (!bench::readOffMesh (argv[2], fandisk, error))
    {
      std::fprintf (stderr, "evaluate_table2: %s\n", error.c_str ());
      return 1;
    }
    cases.push_back ({"fandisk (corner)", fandisk, 30000, {bench::sharpCorner (fandisk), 0.08}, false, 0.0049});
    cases.push_back ({"fandisk (edge)", fandisk, 30000, {bench::sharpEdgePoint (fandisk), 0.08}, false, 0.0049});
  }

  std::ostringstream md;
  md << "# The paper's Table 2, side by side\n\n"
     << "Generated by `build/bench/evaluate_table2 doc " << (argc == 3 ? "fandisk.off" : "") << "` (see README).\n"
     << "Each model is in the unit cube, sampled with exact normals; one ball is cut at a sharp feature (or a\n"
     << "large cap of the sphere). **fill**: output points inside the hole ball that are not input points;\n"
     << "**max / mean error**: their distance to the true surface; **gap mean / max**: distance from each\n"
     << "removed sample to the nearest output point; **covered**: removed samples within 1.5 spacings of an\n"
     << "output point; **unchanged**: input points found exactly as they were; **outside**: new points away\n"
     << "from the hole and farther than one spacing from the input (surface invented elsewhere);\n"
     << "**s**: seconds. pcl_holefill sharp is sigma_n = 0.1, smooth is sigma_n = sup, all else default. MLS is\n"
     << "PCL's MovingLeastSquares with VOXEL_GRID_DILATION (radius 6 h, order 2, voxel 1.5 h, dilated to the\n"
     << "hole's middle); Poisson is PCL's Poisson at depth 9, its mesh vertices taken as points.\n\n"
     << "| case | method | fill | max error | mean error | gap mean | gap max | covered | unchanged | outside | s |\n"
     << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  std::ostringstream verdicts;
  for (const auto &c : cases)
  {
    const auto cut = shapes::cutHoles (c.shape.sample (c.points), {c.hole});
    Cloud::Ptr input (new Cloud (cut.kept));
    const double h = shapes::meanSpacing (cut.kept);
    const double scale = 0.02;  // errors of 0.02 and more are red
    std::vector<Score> scores;
    double seconds = 0.0;
    Cloud sharp = runHoleFill (input, 0.1f, seconds);
    scores.push_back (score ("pcl_holefill sharp", c, cut, sharp, h, seconds, scale));
    attachNormals (scores.back (), sharp);
    Cloud smooth = runHoleFill (input, pcl_holefill::kSup, seconds);
    scores.push_back (score ("pcl_holefill smooth", c, cut, smooth, h, seconds, scale));
    attachNormals (scores.back (), smooth);
    Cloud mls = bench::runMls (input, h, c.hole.radius, seconds);
    scores.push_back (score ("PCL MLS", c, cut, mls, h, seconds, scale));
    attachNormals (scores.back (), mls);
    Cloud poisson = bench::runPoisson (input, 9, seconds);
    scores.push_back (score ("PCL Poisson", c, cut, poisson, h, seconds, scale));
    attachNormals (scores.back (), poisson);
    for (const auto &s : scores)
      md << row (c.name, s);

    // The verdict the issue asks for: ours below the paper and both baselines, covered >= 99 %.
    const Score &ours = c.smooth ? scores[1] : scores[0];
    const bool below_paper = c.paper_max <= 0.0 || ours.max_error < c.paper_max;
    const bool below_baselines = ours.max_error < scores[2].max_error && ours.max_error < scores[3].max_error;
    char verdict[400];
    std::snprintf (verdict, sizeof (verdict), "| %s | %s | %.4f | %s | %.4f / %.4f | %.1f %% | %s |\n", c.name.c_str (),
                   ours.method.c_str (), ours.max_error, c.paper_max > 0 ? std::to_string (c.paper_max).substr (0, 6).c_str () : "-",
                   scores[2].max_error, scores[3].max_error, 100.0 * ours.covered,
                   below_paper && below_baselines && ours.covered >= 0.99 ? "met" : "**missed**");
    verdicts << verdict;

    // The picture: input (error-free), then each method, looking at the hole.
    const Eigen::Vector3f towards =
        (Eigen::Vector3f::Constant (0.5f) - c.hole.centre.cast<float> ()).normalized () + Eigen::Vector3f (0.2f, 0.3f, -0.2f);
    std::vector<pcl_holefill_tool::Image> panels;
    std::vector<Splat> before;
    for (const auto &p : cut.kept)
      before.push_back ({p.getVector3fMap (), p.getNormalVector3fMap (), Eigen::Vector3f (0.78f, 0.78f, 0.8f)});
    panels.push_back (pcl_holefill_tool::renderSplats (before, towards, 260));
    for (const auto &s : scores)
      panels.push_back (pcl_holefill_tool::renderSplats (s.splats, towards, 260));
    std::string file = c.name;
    for (char &ch : file)
      if (!std::isalnum (static_cast<unsigned char> (ch)))
        ch = '_';
    std::string error;
    pcl_holefill_tool::savePng (pcl_holefill_tool::sideBySide (panels), (out_dir / "results" / (file + ".png")).string (),
                                error);
    md.flush ();
    std::fprintf (stderr, "evaluate_table2: %s done\n", c.name.c_str ());
  }
  md << "\n## Target: pcl_holefill's max error below the paper's and both baselines, covered >= 99 %\n\n"
     << "| case | setting | max error | paper | MLS / Poisson max | covered | verdict |\n"
     << "| --- | --- | --- | --- | --- | --- | --- |\n"
     << verdicts.str ()
     << "\n## The paper's Table 2 (max / mean error)\n\n"
     << "| method | cube | pyramid | dihedral | Planck | fandisk |\n| --- | --- | --- | --- | --- | --- |\n"
     << "| Screened Poisson | 0.2048 / 0.0070 | 0.1266 / 0.0070 | 0.0532 / 0.0048 | 0.0221 / 0.0016 | 0.0276 / 0.0008 |\n"
     << "| Volfill | 0.0729 / 0.0063 | 0.0975 / 0.0050 | 0.0982 / 0.0051 | 0.0248 / 0.0017 | 0.0153 / 0.0008 |\n"
     << "| MPU | 0.0619 / 0.0047 | 0.0828 / 0.0059 | 0.0495 / 0.0022 | 0.0830 / 0.0051 | 0.0141 / 0.0008 |\n"
     << "| the paper | 0.0046 / 0.0031 | 0.0114 / 0.0027 | 0.0034 / 0.0019 | 0.0099 / 0.0012 | 0.0049 / 0.0001 |\n"
     << "\n## Pictures\n\nColumns: input with the hole, pcl_holefill sharp, pcl_holefill smooth, PCL MLS, PCL Poisson.\n"
     << "Hole points coloured by error (blue 0, red >= 0.02), points invented away from the hole purple.\n\n";
  for (const auto &c : cases)
  {
    std::string file = c.name;
    for (char &ch : file)
      if (!std::isalnum (static_cast<unsigned char> (ch)))
        ch = '_';
    md << "**" << c.name << "**\n\n![" << c.name << "](results/" << file << ".png)\n\n";
  }
  std::ofstream (out_dir / "results.md") << md.str ();
  std::fputs (md.str ().c_str (), stdout);
  return 0;
}
