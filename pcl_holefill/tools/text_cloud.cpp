/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "text_cloud.h"

#include "cloud_reader.h"

#include <pcl/common/io.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <vector>

namespace pcl_holefill_tool
{
namespace
{
constexpr std::size_t kMaxColumns = 64;
constexpr std::size_t kMaxRows = std::size_t (1) << 31;
// Three columns are normals when this share of the rows holds unit vectors.
constexpr double kUnitShare = 0.95;
constexpr double kUnitTolerance = 0.02;

/** The numbers of one line; false with the reason for a malformed one. */
bool
splitNumbers (const std::string &line, std::vector<double> &values, std::string &reason)
{
  values.clear ();
  const char *p = line.c_str ();
  while (*p)
  {
    while (*p == ' ' || *p == '\t' || *p == ',' || *p == '\r')
      ++p;
    if (!*p)
      break;
    char *end = nullptr;
    const double v = std::strtod (p, &end);
    if (end == p || (*end && *end != ' ' && *end != '\t' && *end != ',' && *end != '\r'))
    {
      reason = "'" + line.substr (0, 60) + "' is not a line of numbers";
      return false;
    }
    if (values.size () == kMaxColumns)
    {
      reason = "more than 64 columns";
      return false;
    }
    values.push_back (v);
    p = end;
  }
  return true;
}

bool
skipped (const std::string &line)
{
  const auto first = line.find_first_not_of (" \t\r");
  return first == std::string::npos || line[first] == '#' || line.compare (first, 2, "//") == 0;
}

/** Whether columns from..from+2 hold unit vectors on nearly every row. */
bool
unitColumns (const std::vector<double> &table, std::size_t columns, std::size_t from)
{
  const std::size_t rows = table.size () / columns;
  std::size_t unit = 0;
  for (std::size_t r = 0; r < rows; ++r)
  {
    const double *v = &table[r * columns + from];
    unit += std::abs (std::sqrt (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - 1.0) <= kUnitTolerance ? 1 : 0;
  }
  return rows > 0 && unit >= kUnitShare * rows;
}

/** The rows of the file as one table; false with the reason. */
bool
readTable (std::istream &in, std::vector<double> &table, std::size_t &columns, std::string &reason)
{
  std::string line;
  std::vector<double> values;
  std::size_t line_number = 0;
  bool first_data = true;
  columns = 0;
  while (std::getline (in, line))
  {
    ++line_number;
    if (skipped (line))
      continue;
    if (!splitNumbers (line, values, reason))
    {
      reason = "line " + std::to_string (line_number) + ": " + reason;
      return false;
    }
    // A leading point count (.pts): one whole number.
    if (first_data && values.size () == 1 && values[0] >= 0 && values[0] == std::floor (values[0]))
    {
      first_data = false;
      continue;
    }
    first_data = false;
    if (columns == 0)
      columns = values.size ();
    if (values.size () != columns || columns < 3)
    {
      reason = "line " + std::to_string (line_number) + " has " + std::to_string (values.size ()) +
               " numbers, " + (columns < 3 ? std::string ("fewer than x y z") : "not " + std::to_string (columns));
      return false;
    }
    if (table.size () / columns >= kMaxRows)
    {
      reason = "more than 2^31 points";
      return false;
    }
    table.insert (table.end (), values.begin (), values.end ());
  }
  if (table.empty ())
  {
    reason = "no point";
    return false;
  }
  return true;
}
}  // namespace

bool
readText (const std::string &path, pcl::PCLPointCloud2 &cloud, std::string &error)
{
  std::ifstream in (path);
  if (!in)
  {
    error = "cannot read '" + path + "'";
    return false;
  }
  std::vector<double> table;
  std::size_t columns = 0;
  std::string reason;
  if (!readTable (in, table, columns, reason))
  {
    error = "'" + path + "' is not a readable text point cloud: " + reason;
    return false;
  }
  // Which columns are what.
  std::vector<std::string> names (columns);
  names[0] = "x", names[1] = "y", names[2] = "z";
  std::size_t normals = 0;
  if (columns >= 6 && unitColumns (table, columns, 3))
    normals = 3;
  else if (columns >= 7 && unitColumns (table, columns, columns - 3))
    normals = columns - 3;
  for (std::size_t c = 3; c < columns; ++c)
    names[c] = "column_" + std::to_string (c + 1);
  if (normals)
    names[normals] = "normal_x", names[normals + 1] = "normal_y", names[normals + 2] = "normal_z";

  const std::size_t rows = table.size () / columns;
  cloud = pcl::PCLPointCloud2 ();
  for (std::size_t c = 0; c < columns; ++c)
  {
    pcl::PCLPointField field;
    field.name = names[c];
    field.offset = static_cast<std::uint32_t> (sizeof (double) * c);
    field.datatype = pcl::PCLPointField::FLOAT64;  // map coordinates need more than float's 7 digits
    field.count = 1;
    cloud.fields.push_back (field);
  }
  cloud.width = static_cast<std::uint32_t> (rows);
  cloud.height = 1;
  cloud.point_step = static_cast<std::uint32_t> (sizeof (double) * columns);
  cloud.row_step = cloud.point_step * cloud.width;
  cloud.is_dense = false;
  cloud.data.resize (rows * cloud.point_step);
  std::memcpy (cloud.data.data (), table.data (), table.size () * sizeof (double));
  return true;
}

namespace
{
/** Writes \a value with the fewest digits that read back to the same value
  * of its field's type: a float up to 9, a double up to 17, an integer all. */
void
printNumber (std::FILE *out, double value, std::uint8_t datatype, bool first)
{
  const bool is_float = datatype == pcl::PCLPointField::FLOAT32;
  const bool is_double = datatype == pcl::PCLPointField::FLOAT64;
  auto same = [&] (double back) {
    return std::isnan (value) || (is_float ? static_cast<float> (back) == static_cast<float> (value) : back == value);
  };
  char text[64];
  int digits = is_float ? 7 : is_double ? 15 : 17;
  const int most = is_float ? 9 : 17;
  std::snprintf (text, sizeof (text), "%.*g", digits, value);
  while (digits < most && !same (std::strtod (text, nullptr)))
    std::snprintf (text, sizeof (text), "%.*g", ++digits, value);
  std::fprintf (out, first ? "%s" : " %s", text);
}
}  // namespace

bool
writeText (const std::string &path, const pcl::PCLPointCloud2 &cloud, std::string &error)
{
  // x y z, the normals, the file's other columns, then what the command adds
  // (curvature of estimated normals, filled); padding fields ("_") are not data.
  const std::vector<std::string> first{"x", "y", "z", "normal_x", "normal_y", "normal_z"}, last{"curvature", "filled"};
  std::vector<int> order;
  for (const auto &name : first)
    if (pcl::getFieldIndex (cloud, name) >= 0)
      order.push_back (pcl::getFieldIndex (cloud, name));
  for (std::size_t f = 0; f < cloud.fields.size (); ++f)
  {
    const std::string &name = cloud.fields[f].name;
    if (cloud.fields[f].count == 1 && name != "_" && std::find (first.begin (), first.end (), name) == first.end () &&
        std::find (last.begin (), last.end (), name) == last.end ())
      order.push_back (static_cast<int> (f));
  }
  for (const auto &name : last)
    if (pcl::getFieldIndex (cloud, name) >= 0)
      order.push_back (pcl::getFieldIndex (cloud, name));
  std::unique_ptr<std::FILE, int (*) (std::FILE *)> out (std::fopen (path.c_str (), "w"), &std::fclose);
  if (!out)
  {
    error = "cannot write '" + path + "'";
    return false;
  }
  const std::size_t points = static_cast<std::size_t> (cloud.width) * cloud.height;
  for (std::size_t i = 0; i < points; ++i)
  {
    const std::uint8_t *row = cloud.data.data () + i * cloud.point_step;
    for (std::size_t k = 0; k < order.size (); ++k)
    {
      const auto &field = cloud.fields[order[k]];
      printNumber (out.get (), fieldValue (row + field.offset, field.datatype), field.datatype, k == 0);
    }
    std::fputc ('\n', out.get ());
  }
  if (std::ferror (out.get ()))
  {
    error = "cannot write '" + path + "'";
    return false;
  }
  return true;
}

}  // namespace pcl_holefill_tool
