/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "cloud_assembly.h"

#include "cloud_reader.h"
#include "nearest_point_tree.h"

#include <pcl_holefill/detail/first_touch.h>
#include <pcl_holefill/detail/thread_count.h>
#include "normal_estimation.h"

#include <pcl/common/io.h>
#include <pcl/conversions.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace pcl_holefill_tool
{
namespace
{
// A normal shorter than this is "no normal".
constexpr float kMinNormalLength = 1e-3f;
// Fewer usable normals than this share of the finite points: estimate them all.
constexpr double kMinUsableNormalShare = 0.5;
// Up to this many filled points whose nearest input point may lie outside
// their hole's box are compared with every input point; more get a k-d tree
// of the whole cloud (its build reads the cloud about log2(n / 8), 15-20,
// times; a scan once). On a 225,000-point cap 12 of 20,499 were such.
constexpr std::size_t kMaxScansOfAll = 30;

/** The field \a name if it holds one float or double per point, else null. */
const pcl::PCLPointField *
realField (const pcl::PCLPointCloud2 &cloud, const std::string &name)
{
  const int i = pcl::getFieldIndex (cloud, name);
  if (i < 0 || cloud.fields[i].count != 1)
    return nullptr;
  const auto type = cloud.fields[i].datatype;
  return type == pcl::PCLPointField::FLOAT32 || type == pcl::PCLPointField::FLOAT64 ? &cloud.fields[i] : nullptr;
}

/** The three fields \a names (x, y, z or the normal's) if all are real. */
bool
realFields (const pcl::PCLPointCloud2 &cloud, const char *const names[3], const pcl::PCLPointField *fields[3])
{
  for (int d = 0; d < 3; ++d)
    if (!(fields[d] = realField (cloud, names[d])))
      return false;
  return true;
}

const char *const kPositionNames[3] = {"x", "y", "z"};
const char *const kNormalNames[3] = {"normal_x", "normal_y", "normal_z"};

/** Whether every field of \a cloud is a coordinate of the position or the
  * normal (or PCD padding, "_"): then a filled point's row owes nothing to
  * any input point's. */
bool
onlyPositionsAndNormals (const pcl::PCLPointCloud2 &cloud)
{
  return std::all_of (cloud.fields.begin (), cloud.fields.end (), [] (const pcl::PCLPointField &f) {
    const auto named = [&f] (const char *const names[3]) {
      return std::any_of (names, names + 3, [&f] (const char *n) { return f.name == n; });
    };
    return f.name == "_" || named (kPositionNames) || named (kNormalNames);
  });
}

/** The three \a fields of the point at \a row, as doubles. */
Eigen::Vector3d
readVector (const std::uint8_t *row, const pcl::PCLPointField *const fields[3])
{
  return {fieldValue (row + fields[0]->offset, fields[0]->datatype),
          fieldValue (row + fields[1]->offset, fields[1]->datatype),
          fieldValue (row + fields[2]->offset, fields[2]->datatype)};
}

/** One field named \a name of PCL type \a datatype, a value per point. */
template <typename T>
pcl::PCLPointCloud2
column (const std::string &name, std::uint8_t datatype, const std::vector<T> &values)
{
  pcl::PCLPointCloud2 column;
  pcl::PCLPointField field;
  field.name = name;
  field.offset = 0;
  field.datatype = datatype;
  field.count = 1;
  column.fields.push_back (field);
  column.height = 1;
  column.width = static_cast<std::uint32_t> (values.size ());
  column.point_step = sizeof (T);
  column.row_step = column.point_step * column.width;
  column.is_dense = true;
  column.data.resize (values.size () * sizeof (T));
  std::memcpy (column.data.data (), values.data (), column.data.size ());
  return column;
}

/** The header, fields and layout of \a cloud, without its rows. */
pcl::PCLPointCloud2
layoutOf (const pcl::PCLPointCloud2 &cloud)
{
  pcl::PCLPointCloud2 layout;
  layout.header = cloud.header;
  layout.fields = cloud.fields;
  layout.is_bigendian = cloud.is_bigendian;
  layout.point_step = cloud.point_step;
  layout.is_dense = cloud.is_dense;
  return layout;
}

/** The header, fields and layout of \a cloud with only its first row. */
pcl::PCLPointCloud2
firstRow (const pcl::PCLPointCloud2 &cloud)
{
  pcl::PCLPointCloud2 row = layoutOf (cloud);
  row.width = row.height = 1;
  row.row_step = row.point_step;
  const std::size_t bytes = std::min<std::size_t> (cloud.point_step, cloud.data.size ());
  row.data.assign (cloud.data.begin (), cloud.data.begin () + static_cast<std::ptrdiff_t> (bytes));
  return row;
}

/** A run of bytes copied into every output row: from the first cloud's row
  * or the second's. */
struct ByteRun
{
  bool from_second;
  std::size_t source, target, size;
};

/** pcl::concatenateFields (\a first, \a second, \a output), the same
  * layout (taken from PCL on one row of each: the second's fields first, and
  * they replace the first's of the same name), the rows copied side by side
  * in runs of adjacent fields. PCL copies field by field, point by point, on
  * one thread: a fifth of a second on a million points, for a column. */
bool
concatenateColumns (const pcl::PCLPointCloud2 &first, const pcl::PCLPointCloud2 &second, unsigned int threads,
                    pcl::PCLPointCloud2 &output)
{
  const std::size_t rows = static_cast<std::size_t> (first.width) * first.height;
  if (first.width != second.width || first.height != second.height || rows == 0 ||
      first.data.size () < rows * first.point_step || second.data.size () < rows * second.point_step)
    return pcl::concatenateFields (first, second, output);
  pcl::PCLPointCloud2 layout;
  if (!pcl::concatenateFields (firstRow (first), firstRow (second), layout))
    return false;
  std::vector<ByteRun> runs;
  for (const auto &field : layout.fields)
  {
    if (field.name == "_")
      continue;
    const int in_second = pcl::getFieldIndex (second, field.name);
    const int in_first = in_second >= 0 ? -1 : pcl::getFieldIndex (first, field.name);
    if (in_second < 0 && in_first < 0)
      return pcl::concatenateFields (first, second, output);  // not a layout this copy knows
    const bool from_second = in_second >= 0;
    const std::size_t source = from_second ? second.fields[in_second].offset : first.fields[in_first].offset;
    const std::size_t size = static_cast<std::size_t> (pcl::getFieldSize (field.datatype)) * field.count;
    if (!runs.empty () && runs.back ().from_second == from_second &&
        runs.back ().source + runs.back ().size == source && runs.back ().target + runs.back ().size == field.offset)
      runs.back ().size += size;
    else
      runs.push_back ({from_second, source, field.offset, size});
  }
  output = std::move (layout);
  output.width = first.width;
  output.height = first.height;
  output.row_step = output.point_step * output.width;
  output.data.clear ();
  const int workers = static_cast<int> (pcl_holefill::detail::resolveThreadCount (threads));
  pcl_holefill::detail::resizeTouched (output.data, rows * output.point_step, workers, std::uint8_t (0));
  const std::ptrdiff_t count = static_cast<std::ptrdiff_t> (rows);
#pragma omp parallel for num_threads(workers) schedule(static)
  for (std::ptrdiff_t i = 0; i < count; ++i)
    for (const ByteRun &run : runs)
    {
      const pcl::PCLPointCloud2 &from = run.from_second ? second : first;
      std::memcpy (output.data.data () + i * output.point_step + run.target,
                   from.data.data () + i * from.point_step + run.source, run.size);
    }
  return true;
}

/** Is the layout one PCL's conversions can trust: every field inside a
  * point, every point inside the data, float or double x, y, z (then in \a xyz)? */
bool
checkLayout (const pcl::PCLPointCloud2 &file_cloud, const pcl::PCLPointField *xyz[3], std::string &error)
{
  if (static_cast<std::size_t> (file_cloud.width) * file_cloud.height == 0)
  {
    error = "the cloud has no point";
    return false;
  }
  for (const auto &field : file_cloud.fields)
    if (static_cast<std::uint64_t> (field.offset) + pcl::getFieldSize (field.datatype) * std::max<std::uint64_t> (field.count, 1) >
        file_cloud.point_step)
    {
      error = "the field '" + field.name + "' lies outside its point";
      return false;
    }
  if (file_cloud.data.size () < static_cast<std::uint64_t> (file_cloud.point_step) * file_cloud.width * file_cloud.height)
  {
    error = "the cloud has less data than points";
    return false;
  }
  if (!realFields (file_cloud, kPositionNames, xyz))
  {
    error = "the cloud has no float or double x, y, z fields";
    return false;
  }
  return true;
}

/** Where the fill's frame lies. Float32 keeps about 7 digits: map
  * coordinates (x = 512345.678 m) would lose centimetres, and the fill would
  * run on rounded data. A cloud farther from (0, 0, 0) than its own size is
  * filled around the centre of its bounding box; one nearer, where it is (its
  * float coordinates lose nothing there, and its fill stays as it was). */
Eigen::Vector3d
localOrigin (const Eigen::AlignedBox3d &box)
{
  if (box.isEmpty () || box.center ().norm () <= box.diagonal ().norm ())
    return Eigen::Vector3d::Zero ();
  return box.center ();
}

/** The positions into prepared.points, in the local frame (prepared.origin);
  * counts the finite ones. Read twice (the box, then the local positions)
  * by every thread: one serial pass through a copy in doubles was a tenth of
  * the command on a 1,000,000-point cloud, most of it the copy's page faults. */
void
readPositions (const pcl::PCLPointCloud2 &file_cloud, const pcl::PCLPointField *const xyz[3], int threads,
               PreparedCloud &prepared)
{
  const auto points = static_cast<std::ptrdiff_t> (file_cloud.width) * file_cloud.height;
  const auto row = [&file_cloud] (std::ptrdiff_t i) { return file_cloud.data.data () + i * file_cloud.point_step; };
  constexpr double kInf = std::numeric_limits<double>::infinity ();
  double lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf};
  std::size_t finite = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(min : lo[:3]) reduction(max : hi[:3]) \
    reduction(+ : finite)
  for (std::ptrdiff_t i = 0; i < points; ++i)
  {
    const Eigen::Vector3d p = readVector (row (i), xyz);
    if (!p.allFinite ())
      continue;
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::min (lo[d], p[d]);
      hi[d] = std::max (hi[d], p[d]);
    }
    ++finite;
  }
  prepared.finite_points = finite;
  Eigen::AlignedBox3d box;  // empty
  if (finite > 0)
    box = Eigen::AlignedBox3d (Eigen::Vector3d (lo[0], lo[1], lo[2]), Eigen::Vector3d (hi[0], hi[1], hi[2]));
  prepared.origin = localOrigin (box);
  pcl_holefill::detail::reserveTouched (prepared.points->points, static_cast<std::size_t> (points), threads);
  prepared.points->resize (static_cast<std::size_t> (points));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::ptrdiff_t i = 0; i < points; ++i)
    (*prepared.points)[i].getVector3fMap () = (readVector (row (i), xyz) - prepared.origin).cast<float> ();
}

/** The file's normals into prepared.points, read field by field (PCL's
  * conversion to a point type with a curvature field prints a warning for
  * every cloud without one); returns how many are usable (finite, not 0). */
std::size_t
readNormals (const pcl::PCLPointCloud2 &file_cloud, const pcl::PCLPointField *const n[3], int threads,
             PreparedCloud &prepared)
{
  std::size_t usable_normals = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : usable_normals)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (prepared.points->size ()); ++i)
  {
    const Eigen::Vector3f v = readVector (file_cloud.data.data () + i * file_cloud.point_step, n).cast<float> ();
    (*prepared.points)[i].getNormalVector3fMap () = v;
    const float length = v.norm ();
    usable_normals += std::isfinite (length) && length > kMinNormalLength ? 1 : 0;
  }
  return usable_normals;
}

/** Adds the estimated normals of prepared.points to prepared.fields, for a
  * file that had none: its rows are written with them. */
bool
addNormalFields (PreparedCloud &prepared, unsigned int threads, std::string &error)
{
  pcl::PointCloud<pcl::Normal> normals;
  normals.resize (prepared.points->size ());
  for (std::size_t i = 0; i < normals.size (); ++i)
    normals[i].getNormalVector3fMap () = (*prepared.points)[i].getNormalVector3fMap ();
  pcl::PCLPointCloud2 normal_fields, merged;
  pcl::toPCLPointCloud2 (normals, normal_fields);
  normal_fields.width = prepared.fields.width;
  normal_fields.height = 1;
  if (!concatenateColumns (prepared.fields, normal_fields, threads, merged))
  {
    error = "could not add the estimated normals to the cloud's fields";
    return false;
  }
  prepared.fields = std::move (merged);
  return true;
}

/** Where the input points near a hole's fill lie: the box of its filled and
  * rim points, widened so that a filled point's nearest input point (no
  * farther than the rim, at most the box's size away) lies inside it. */
struct HoleBox
{
  Eigen::AlignedBox3f box;
  std::size_t first = 0, count = 0;  //!< the hole's filled points: filtered[first, first + count)
};

std::vector<HoleBox>
holeBoxes (const pcl::PointCloud<pcl::PointNormal> &filtered, const std::vector<pcl_holefill::HoleReport> &reports)
{
  std::vector<HoleBox> boxes;
  for (const auto &r : reports)
  {
    if (r.points_added == 0 || r.first_output_index + r.points_added > filtered.size ())
      continue;
    HoleBox hole{Eigen::AlignedBox3f (), r.first_output_index, r.points_added};
    for (std::size_t k = hole.first; k < hole.first + hole.count; ++k)
      hole.box.extend (filtered[k].getVector3fMap ());
    for (const auto i : r.boundary)
      if (i >= 0 && static_cast<std::size_t> (i) < filtered.size ())
        hole.box.extend (filtered[i].getVector3fMap ());
    const float margin = 0.5f * hole.box.sizes ().maxCoeff () + 2.f * r.pitch;
    hole.box.min ().array () -= margin;
    hole.box.max ().array () += margin;
    boxes.push_back (hole);
  }
  return boxes;
}

/** The input points inside any of \a boxes. The boxes are binned on a coarse
  * grid over their union first, so that each point is tested against the few
  * boxes of its bin: against all of them, 300 holes on 1,000,000 points took
  * 0.23 s. */
pcl::IndicesPtr
pointsInBoxes (const pcl::PointCloud<pcl::PointNormal> &input, const std::vector<HoleBox> &boxes)
{
  constexpr int kBins = 32;  // per axis
  Eigen::AlignedBox3f all;
  for (const HoleBox &b : boxes)
    all.extend (b.box);
  const Eigen::Array3f scale = kBins / all.sizes ().array ().max (1e-30f);
  const auto bin = [&] (const Eigen::Vector3f &p) {
    return ((p - all.min ()).array () * scale).floor ().cast<int> ().min (kBins - 1).max (0);
  };
  std::vector<std::vector<std::size_t>> bins (kBins * kBins * kBins);
  for (std::size_t j = 0; j < boxes.size (); ++j)
  {
    const Eigen::Array3i lo = bin (boxes[j].box.min ()), hi = bin (boxes[j].box.max ());
    for (int x = lo.x (); x <= hi.x (); ++x)
      for (int y = lo.y (); y <= hi.y (); ++y)
        for (int z = lo.z (); z <= hi.z (); ++z)
          bins[(x * kBins + y) * kBins + z].push_back (j);
  }
  pcl::IndicesPtr inside (new pcl::Indices);
  for (std::size_t i = 0; i < input.size (); ++i)
  {
    const Eigen::Vector3f p = input[i].getVector3fMap ();
    if (!all.contains (p))
      continue;
    const Eigen::Array3i c = bin (p);
    const auto &candidates = bins[(c.x () * kBins + c.y ()) * kBins + c.z ()];
    if (std::any_of (candidates.begin (), candidates.end (), [&] (std::size_t j) { return boxes[j].box.contains (p); }))
      inside->push_back (static_cast<int> (i));
  }
  return inside;
}

/** Distance from \a p (inside \a box) to the nearest face of it. */
float
depthInside (const Eigen::AlignedBox3f &box, const Eigen::Vector3f &p)
{
  return std::min ((p - box.min ()).minCoeff (), (box.max () - p).minCoeff ());
}

/** For each filled point of \a filtered (the input, then the fill), the index
  * of its nearest input point. */
std::vector<int>
nearestInputPoints (const pcl::PointCloud<pcl::PointNormal> &input, const pcl::PointCloud<pcl::PointNormal> &filtered,
                    const std::vector<pcl_holefill::HoleReport> &reports, unsigned int threads)
{
  // A k-d tree, because a filled point's nearest input point is up to a
  // hole's radius away (see NearestPointTree). Built on the input points in
  // the holes' boxes, not on the whole cloud (0.35 of 1.8 s on 1,000,000
  // points with 10 holes); a query whose answer could lie outside its box
  // goes to a tree of all.
  const std::size_t input_points = input.size ();
  const std::vector<HoleBox> boxes = holeBoxes (filtered, reports);
  const pcl::IndicesPtr near = pointsInBoxes (input, boxes);
  const NearestPointTree local (input, near.get ());
  std::vector<const Eigen::AlignedBox3f *> box_of (filtered.size () - input_points, nullptr);
  for (const HoleBox &b : boxes)
    for (std::size_t k = b.first; k < b.first + b.count && k >= input_points; ++k)
      box_of[k - input_points] = &b.box;
  const auto count = static_cast<std::ptrdiff_t> (box_of.size ());
  const int workers = pcl_holefill::detail::resolveThreadCount (threads);
  std::vector<int> nearest (box_of.size (), -1);
#pragma omp parallel for num_threads(workers) schedule(static, 256)
  for (std::ptrdiff_t k = 0; k < count; ++k)
  {
    if (!box_of[k])
      continue;
    const Eigen::Vector3f p = filtered[input_points + k].getVector3fMap ();
    float sqr_distance = 0.f;
    const int found = local.nearest (p, sqr_distance);
    if (found >= 0 && std::sqrt (sqr_distance) <= depthInside (*box_of[k], p))
      nearest[k] = found;
  }
  std::vector<std::ptrdiff_t> rest;
  for (std::ptrdiff_t k = 0; k < count; ++k)
    if (nearest[k] < 0)
      rest.push_back (k);
  if (rest.empty ())
    return nearest;
  // The rest (near their box's faces) against every point, unless a tree of
  // all is cheaper.
  const auto others = static_cast<std::ptrdiff_t> (rest.size ());
  if (rest.size () > kMaxScansOfAll)
  {
    const NearestPointTree all (input, nullptr);
#pragma omp parallel for num_threads(workers) schedule(static, 256)
    for (std::ptrdiff_t r = 0; r < others; ++r)
    {
      float sqr_distance = 0.f;
      nearest[rest[r]] = std::max (0, all.nearest (filtered[input_points + rest[r]].getVector3fMap (), sqr_distance));
    }
    return nearest;
  }
#pragma omp parallel for num_threads(workers) schedule(static, 1)
  for (std::ptrdiff_t r = 0; r < others; ++r)
  {
    const Eigen::Vector3f p = filtered[input_points + rest[r]].getVector3fMap ();
    float best = std::numeric_limits<float>::infinity ();
    int found = 0;
    for (std::size_t i = 0; i < input_points; ++i)
    {
      const float d2 = (input[i].getVector3fMap () - p).squaredNorm ();
      if (d2 < best)  // false for a non-finite point
      {
        best = d2;
        found = static_cast<int> (i);
      }
    }
    nearest[rest[r]] = found;
  }
  return nearest;
}
}  // namespace

bool
prepareCloud (pcl::PCLPointCloud2 file_cloud, unsigned int threads, PreparedCloud &prepared,
              std::string &error)
{
  const pcl::PCLPointField *xyz[3], *normal_fields[3];
  if (!checkLayout (file_cloud, xyz, error))
    return false;
  const int workers = pcl_holefill::detail::resolveThreadCount (threads);
  prepared.points.reset (new pcl::PointCloud<pcl::PointNormal>);
  readPositions (file_cloud, xyz, workers, prepared);
  if (prepared.finite_points == 0)
  {
    error = "the cloud has no finite point";
    return false;
  }
  const bool has_normals = realFields (file_cloud, kNormalNames, normal_fields);
  const std::size_t usable_normals = has_normals ? readNormals (file_cloud, normal_fields, workers, prepared) : 0;
  // The file's rows are the output's first rows: taken over, not copied
  // (xyz and normal_fields point into them: not read after this).
  prepared.fields = std::move (file_cloud);
  // The output gains points: it cannot stay organized.
  prepared.fields.width = prepared.fields.width * prepared.fields.height;
  prepared.fields.height = 1;
  prepared.fields.row_step = prepared.fields.point_step * prepared.fields.width;
  // Normals that are mostly 0 0 0 or not finite (how some tools write "no
  // normal") are estimated for the fill; the input rows keep theirs.
  prepared.normals_unusable = has_normals && usable_normals < kMinUsableNormalShare * prepared.finite_points;
  prepared.normals_estimated = !has_normals || prepared.normals_unusable;
  if (prepared.normals_estimated)
    prepared.normal_neighbours = estimateOrientedNormals (*prepared.points, threads);
  if (!has_normals && !addNormalFields (prepared, threads, error))
    return false;
  prepared.points->width = static_cast<std::uint32_t> (prepared.points->size ());
  prepared.points->height = 1;
  prepared.points->is_dense = prepared.finite_points == prepared.points->size ();
  return true;
}

bool
assembleOutput (const PreparedCloud &prepared, const pcl::PointCloud<pcl::PointNormal> &filtered,
                const std::vector<pcl_holefill::HoleReport> &reports, unsigned int threads,
                pcl::PCLPointCloud2 &output, std::string &error)
{
  const std::size_t input_points = prepared.points->size ();
  if (filtered.size () < input_points)
  {
    error = "the filter lost points";
    return false;
  }
  const pcl::PCLPointCloud2 &input = prepared.fields;
  const std::size_t step = input.point_step;
  const std::size_t added = filtered.size () - input_points;
  const pcl::PCLPointField *xyz[3], *nxyz[3];
  if (!realFields (input, kPositionNames, xyz) || !realFields (input, kNormalNames, nxyz))
  {
    error = "the cloud's position or normal fields are not float or double";
    return false;
  }
  // The other fields (colour, intensity, ...) of a filled point are its
  // nearest input point's; a cloud without any needs no search (on one
  // hole of 82,000 points in 910,000, the search was 0.3 of 3.5 s).
  const bool copy_fields = !onlyPositionsAndNormals (input);
  const std::vector<int> nearest =
      copy_fields ? nearestInputPoints (*prepared.points, filtered, reports, threads) : std::vector<int> ();
  pcl::PCLPointCloud2 rows = layoutOf (input);
  // Filled in one pass by every thread (a copy of the input's rows and a
  // larger buffer's copy of that were two serial passes over the cloud).
  const int workers = static_cast<int> (pcl_holefill::detail::resolveThreadCount (threads));
  pcl_holefill::detail::resizeTouched (rows.data, (input_points + added) * step, workers);
  const std::ptrdiff_t total = static_cast<std::ptrdiff_t> (input_points + added);
#pragma omp parallel for num_threads(workers) schedule(static)
  for (std::ptrdiff_t i = 0; i < total; ++i)
  {
    std::uint8_t *row = rows.data.data () + static_cast<std::size_t> (i) * step;
    const std::size_t k = static_cast<std::size_t> (i) - input_points;
    if (static_cast<std::size_t> (i) < input_points)
    {
      std::memcpy (row, input.data.data () + static_cast<std::size_t> (i) * step, step);
      continue;
    }
    if (copy_fields)
      std::memcpy (row, input.data.data () + static_cast<std::size_t> (nearest[k]) * step, step);
    else
      std::memset (row, 0, step);
    const pcl::PointNormal &p = filtered[static_cast<std::size_t> (i)];
    for (int d = 0; d < 3; ++d)
    {
      storeFieldValue (static_cast<double> (p.data[d]) + prepared.origin[d], xyz[d]->datatype, row + xyz[d]->offset);
      storeFieldValue (p.data_n[d], nxyz[d]->datatype, row + nxyz[d]->offset);
    }
  }
  rows.width = static_cast<std::uint32_t> (input_points + added);
  rows.height = 1;
  rows.row_step = static_cast<std::uint32_t> (step * rows.width);
  std::vector<float> marks (rows.width, 0.f);
  std::fill (marks.begin () + input_points, marks.end (), 1.f);
  const int existing = pcl::getFieldIndex (rows, "filled");
  if (existing >= 0)
  {
    if (rows.fields[existing].datatype != pcl::PCLPointField::FLOAT32)
    {
      error = "the input has a field 'filled' that is not a float";
      return false;
    }
    for (std::size_t i = 0; i < rows.width; ++i)
      std::memcpy (rows.data.data () + i * step + rows.fields[existing].offset, &marks[i], sizeof (float));
    output = std::move (rows);
    return true;
  }
  if (!concatenateColumns (rows, column ("filled", pcl::PCLPointField::FLOAT32, marks), threads, output))
  {
    error = "could not add the 'filled' field";
    return false;
  }
  return true;
}

bool
assembleDetection (const PreparedCloud &prepared, const std::vector<pcl_holefill::BoundaryLoop> &loops,
                   unsigned int threads, pcl::PCLPointCloud2 &output, std::string &error)
{
  if (pcl::getFieldIndex (prepared.fields, "hole_id") >= 0)
  {
    error = "the input already has a field 'hole_id'";
    return false;
  }
  std::vector<std::int32_t> ids (prepared.fields.width, -1);
  std::int32_t next = 0;
  for (const auto &loop : loops)
  {
    if (!loop.is_hole)
      continue;
    for (const auto i : loop.indices)
      ids[static_cast<std::size_t> (i)] = next;
    ++next;
  }
  if (!concatenateColumns (prepared.fields, column ("hole_id", pcl::PCLPointField::INT32, ids), threads, output))
  {
    error = "could not add the 'hole_id' field";
    return false;
  }
  return true;
}

}  // namespace pcl_holefill_tool
