/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 *
 * The extension behind the Python package: numpy float32 arrays in the
 * library's frame, the command's options as command-line words (so names,
 * defaults, ranges and messages are the command's), plain arrays out. The
 * package's __init__.py checks the arrays, keeps float64 precision and shapes
 * the result.
 */
#include "fill_options.h"
#include "normal_estimation.h"
#include "report_json.h"

#include <pcl_holefill/hole_boundary_estimation.h>
#include <pcl_holefill/hole_filling.h>
#include <pcl/search/kdtree.h>

#include <pcl/console/print.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace py = pybind11;

namespace
{
using Cloud = pcl::PointCloud<pcl::PointNormal>;
using Rows = py::array_t<float, py::array::c_style | py::array::forcecast>;

/** The (N, 3) float32 rows as points; normals from \a normals or estimated. */
Cloud::Ptr
toCloud (const Rows &points, const py::object &normals, unsigned int threads, bool &estimated)
{
  const auto p = points.unchecked<2> ();
  Cloud::Ptr cloud (new Cloud);
  cloud->resize (static_cast<std::size_t> (p.shape (0)));
  for (py::ssize_t i = 0; i < p.shape (0); ++i)
    (*cloud)[i].getVector3fMap () = Eigen::Vector3f (p (i, 0), p (i, 1), p (i, 2));
  estimated = normals.is_none ();
  if (!estimated)
  {
    const Rows given = normals.cast<Rows> ();
    const auto n = given.unchecked<2> ();
    for (py::ssize_t i = 0; i < n.shape (0); ++i)
      (*cloud)[i].getNormalVector3fMap () = Eigen::Vector3f (n (i, 0), n (i, 1), n (i, 2));
  }
  cloud->width = static_cast<std::uint32_t> (cloud->size ());
  cloud->height = 1;
  cloud->is_dense = false;
  if (estimated)
  {
    py::gil_scoped_release release;
    pcl_holefill_tool::estimateOrientedNormals (*cloud, threads);
  }
  return cloud;
}

/** While alive, PCL prints errors only (the command's -q). */
class Quiet
{
public:
  explicit Quiet (bool quiet) : before_ (pcl::console::getVerbosityLevel ())
  {
    if (quiet)
      pcl::console::setVerbosityLevel (pcl::console::L_ERROR);
  }
  ~Quiet () { pcl::console::setVerbosityLevel (before_); }
  Quiet (const Quiet &) = delete;
  Quiet &operator= (const Quiet &) = delete;

private:
  pcl::console::VERBOSITY_LEVEL before_;
};

/** The command's options from \a words ("-radius", "0.1", ...); ValueError with its message. */
pcl_holefill_tool::Options
parse (const std::vector<std::string> &words)
{
  std::vector<std::string> argv_words{"pcl_holefill", "<array>", "<array>"};
  argv_words.insert (argv_words.end (), words.begin (), words.end ());
  std::vector<char *> argv;
  for (auto &w : argv_words)
    argv.push_back (&w[0]);
  pcl_holefill_tool::Options options;
  std::string error;
  if (!pcl_holefill_tool::parseOptions (static_cast<int> (argv.size ()), argv.data (), options, error))
    throw py::value_error (error);
  return options;
}

py::array_t<float>
columns (const Cloud &cloud, bool normals)
{
  py::array_t<float> out ({static_cast<py::ssize_t> (cloud.size ()), static_cast<py::ssize_t> (3)});
  auto o = out.mutable_unchecked<2> ();
  for (std::size_t i = 0; i < cloud.size (); ++i)
  {
    const Eigen::Vector3f v = normals ? cloud[i].getNormalVector3fMap () : cloud[i].getVector3fMap ();
    for (int k = 0; k < 3; ++k)
      o (static_cast<py::ssize_t> (i), k) = v[k];
  }
  return out;
}

/** For each filled point, the input row nearest to it (whose extra columns it takes). */
py::array_t<std::int64_t>
nearestInputRows (const Cloud::Ptr &input, const Cloud &output)
{
  const std::size_t added = output.size () - input->size ();
  py::array_t<std::int64_t> nearest (static_cast<py::ssize_t> (added));
  auto n = nearest.mutable_unchecked<1> ();
  // A k-d tree, because that point is up to a hole's radius away: a grid
  // tuned to the sampling pitch scanned the whole cloud for every point deep
  // in a large hole (a random sphere of 250,000 points, a cap of 20,000
  // filled points: 38 s of 40). Rows with a NaN coordinate are left out.
  pcl::IndicesPtr finite (new pcl::Indices);
  for (std::size_t i = 0; i < input->size (); ++i)
    if ((*input)[i].getVector3fMap ().allFinite ())
      finite->push_back (static_cast<int> (i));
  if (finite->empty ())
  {
    for (std::size_t k = 0; k < added; ++k)
      n (static_cast<py::ssize_t> (k)) = -1;
    return nearest;
  }
  pcl::search::KdTree<pcl::PointNormal> search;
  search.setInputCloud (input, finite);
  pcl::Indices found;
  std::vector<float> sqr_distances;
  for (std::size_t k = 0; k < added; ++k)
  {
    search.nearestKSearch (output[input->size () + k], 1, found, sqr_distances);
    n (static_cast<py::ssize_t> (k)) = found.empty () ? -1 : found[0];
  }
  return nearest;
}

py::dict
fill (const Rows &points, const py::object &normals, const std::vector<std::string> &words,
      const std::vector<std::vector<std::int64_t>> &holes)
{
  const pcl_holefill_tool::Options options = parse (words);
  const Quiet quiet (options.quiet);
  bool estimated = false;
  const Cloud::Ptr cloud = toCloud (points, normals, static_cast<unsigned int> (options.threads), estimated);
  pcl_holefill::HoleFilling<pcl::PointNormal> filler;
  pcl_holefill_tool::configure (options, filler);
  std::vector<pcl_holefill::BoundaryLoop> loops;
  for (const auto &hole : holes)
  {
    pcl_holefill::BoundaryLoop loop;
    loop.closed = true;
    loop.is_hole = true;
    for (const auto i : hole)
    {
      if (i < 0 || static_cast<std::size_t> (i) >= cloud->size ())
        throw py::value_error ("holes: index " + std::to_string (i) + " is not a row of points (0.." +
                               std::to_string (cloud->size () - 1) + ")");
      loop.indices.push_back (static_cast<pcl::index_t> (i));
    }
    if (loop.indices.size () < 3)
      throw py::value_error ("holes: a loop needs at least 3 points");
    loops.push_back (std::move (loop));
  }
  filler.setHoles (loops);
  filler.setInputCloud (cloud);
  Cloud output;
  {
    py::gil_scoped_release release;
    filler.filter (output);
  }
  if (output.size () < cloud->size ())
    throw py::value_error ("the parameters were refused (see the message above)");
  py::dict result;
  result["points"] = columns (output, false);
  result["normals"] = columns (output, true);
  result["nearest"] = nearestInputRows (cloud, output);
  result["report"] = pcl_holefill_tool::reportJson ("<array>", cloud->size (), filler.getReports ());
  result["normals_estimated"] = estimated;
  return result;
}

py::dict
detectHoles (const Rows &points, const py::object &normals, const std::vector<std::string> &words)
{
  const pcl_holefill_tool::Options options = parse (words);
  const Quiet quiet (options.quiet);
  bool estimated = false;
  const Cloud::Ptr cloud = toCloud (points, normals, static_cast<unsigned int> (options.threads), estimated);
  pcl_holefill::HoleBoundaryEstimation<pcl::PointNormal> estimation;
  estimation.setInputCloud (cloud);
  estimation.setMinHoleSize (options.min_hole_size);
  estimation.setMaxHoleDiameter (options.max_hole_size);
  estimation.setNumberOfThreads (static_cast<unsigned int> (options.threads));
  std::vector<pcl_holefill::BoundaryLoop> loops;
  {
    py::gil_scoped_release release;
    estimation.compute (loops);
  }
  py::list holes;
  for (const auto &loop : loops)
    if (loop.is_hole)
    {
      py::array_t<std::int64_t> indices (static_cast<py::ssize_t> (loop.indices.size ()));
      auto ix = indices.mutable_unchecked<1> ();
      for (std::size_t k = 0; k < loop.indices.size (); ++k)
        ix (static_cast<py::ssize_t> (k)) = loop.indices[k];
      holes.append (indices);
    }
  py::dict result;
  result["holes"] = holes;
  result["normals_estimated"] = estimated;
  return result;
}

/** The command's defaults, by option name: the package documents them. */
py::dict
defaults ()
{
  const pcl_holefill_tool::Options o;
  py::dict d;
  d["radius"] = o.radius;
  d["sigma_n"] = o.sigma_n;
  d["sigma_r"] = o.sigma_r;
  d["sigma_d"] = o.sigma_d;
  d["shrink"] = o.shrink;
  d["ratio"] = o.ratio;
  d["spacing"] = o.spacing;
  d["max_passes"] = o.max_passes;
  d["zero_order"] = o.zero_order;
  d["denoise"] = o.denoise;
  d["min_hole_size"] = o.min_hole_size;
  d["max_hole_size"] = o.max_hole_size;
  d["threads"] = o.threads;
  d["quiet"] = o.quiet;
  return d;
}
}  // namespace

PYBIND11_MODULE (_pcl_holefill, m)
{
  m.doc () = "The C++ side of pcl_holefill (use the package's fill and detect_holes).";
  m.def ("fill", &fill, py::arg ("points"), py::arg ("normals"), py::arg ("words"), py::arg ("holes"));
  m.def ("detect_holes", &detectHoles, py::arg ("points"), py::arg ("normals"), py::arg ("words"));
  m.def ("defaults", &defaults);
  m.def ("usage", [] () { return pcl_holefill_tool::usage ("pcl_holefill"); });
}
