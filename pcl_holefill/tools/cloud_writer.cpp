/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "cloud_writer.h"
#include "ply_types.h"

#include <pcl/PCLPointField.h>
#include <pcl/common/io.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

namespace pcl_holefill_tool
{
namespace
{
std::size_t
sizeOf (std::uint8_t datatype)
{
  return static_cast<std::size_t> (std::max (pcl::getFieldSize (datatype), 0));
}

/** The fields in the order of their offsets, unknown types and '_' padding left out. */
std::vector<pcl::PCLPointField>
storedFields (const pcl::PCLPointCloud2 &cloud)
{
  std::vector<pcl::PCLPointField> fields;
  for (const auto &f : cloud.fields)
    if (f.name != "_" && sizeOf (f.datatype) > 0 && f.count > 0)
      fields.push_back (f);
  std::stable_sort (fields.begin (), fields.end (), [] (const auto &a, const auto &b) { return a.offset < b.offset; });
  return fields;
}

/** Whether every field lies within a point and no two overlap. */
bool
fieldsFit (const std::vector<pcl::PCLPointField> &fields, std::uint32_t point_step)
{
  std::uint64_t end = 0;
  for (const auto &f : fields)
  {
    if (f.offset < end)
      return false;
    end = static_cast<std::uint64_t> (f.offset) + sizeOf (f.datatype) * f.count;
  }
  return end <= point_step;
}

bool
checkCloud (const pcl::PCLPointCloud2 &cloud, const std::vector<pcl::PCLPointField> &fields, std::string &error)
{
  const std::uint64_t points = static_cast<std::uint64_t> (cloud.width) * cloud.height;
  if (!fieldsFit (fields, cloud.point_step) || cloud.data.size () < points * cloud.point_step)
  {
    error = "the cloud's fields do not fit its points";
    return false;
  }
  return true;
}

bool
writeFile (const std::string &path, const std::string &header, const std::uint8_t *body, std::uint64_t bytes,
           std::string &error)
{
  std::ofstream out (path, std::ios::binary);
  out.write (header.data (), static_cast<std::streamsize> (header.size ()));
  out.write (reinterpret_cast<const char *> (body), static_cast<std::streamsize> (bytes));
  out.close ();
  if (!out)
  {
    error = "cannot write '" + path + "'";
    return false;
  }
  return true;
}

/** PLY's name of \a datatype; null for the types PLY lacks. */
const char *
plyType (std::uint8_t datatype)
{
  for (const PlyType &t : kPlyTypes)
    if (t.datatype == datatype)
      return t.name;
  return nullptr;
}

bool
isPackedColour (const pcl::PCLPointField &f)
{
  return (f.name == "rgb" || f.name == "rgba") && f.count == 1 && sizeOf (f.datatype) == 4;
}

bool
bigEndianMachine ()
{
  const std::uint16_t one = 1;
  std::uint8_t first = 0;
  std::memcpy (&first, &one, 1);
  return first == 0;
}
}  // namespace

bool
writePcd (const std::string &path, const pcl::PCLPointCloud2 &cloud, std::string &error)
{
  const std::vector<pcl::PCLPointField> fields = storedFields (cloud);
  if (!checkCloud (cloud, fields, error))
    return false;
  std::ostringstream names, sizes, types, counts;
  std::uint64_t at = 0;
  const auto padding = [&] (std::uint64_t bytes) {
    names << " _";
    sizes << " 1";
    types << " U";
    counts << " " << bytes;
  };
  for (const auto &f : fields)
  {
    if (f.offset > at)
      padding (f.offset - at);
    names << " " << f.name;
    sizes << " " << sizeOf (f.datatype);
    types << " " << pcl::getFieldType (f.datatype);
    counts << " " << f.count;
    at = f.offset + sizeOf (f.datatype) * f.count;
  }
  if (cloud.point_step > at)
    padding (cloud.point_step - at);
  const std::uint64_t points = static_cast<std::uint64_t> (cloud.width) * cloud.height;
  std::ostringstream header;
  header << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS" << names.str () << "\nSIZE"
         << sizes.str () << "\nTYPE" << types.str () << "\nCOUNT" << counts.str () << "\nWIDTH " << cloud.width
         << "\nHEIGHT " << cloud.height << "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << points << "\nDATA binary\n";
  return writeFile (path, header.str (), cloud.data.data (), points * cloud.point_step, error);
}

bool
writePly (const std::string &path, const pcl::PCLPointCloud2 &cloud, std::string &error)
{
  std::vector<pcl::PCLPointField> fields = storedFields (cloud);
  if (!checkCloud (cloud, fields, error))
    return false;
  fields.erase (std::remove_if (fields.begin (), fields.end (),
                                [] (const auto &f) { return !isPackedColour (f) && !plyType (f.datatype); }),
                fields.end ());
  const std::uint64_t points = static_cast<std::uint64_t> (cloud.width) * cloud.height;
  std::ostringstream header;
  header << "ply\nformat " << (bigEndianMachine () ? "binary_big_endian" : "binary_little_endian")
         << " 1.0\ncomment written by pcl_holefill\nelement vertex " << points << "\n";
  std::uint64_t record = 0;
  for (const auto &f : fields)
  {
    if (isPackedColour (f))
    {
      for (const char *c : {"red", "green", "blue"})
        header << "property uchar " << c << "\n";
      if (f.name == "rgba")
        header << "property uchar alpha\n";
      record += f.name == "rgba" ? 4 : 3;
      continue;
    }
    std::string name = f.name;
    if (name == "normal_x" || name == "normal_y" || name == "normal_z")
      name = std::string ("n") + name.back ();
    if (f.count == 1)
      header << "property " << plyType (f.datatype) << " " << name << "\n";
    else
      header << "property list uint " << plyType (f.datatype) << " " << name << "\n";
    record += (f.count == 1 ? 0 : 4) + sizeOf (f.datatype) * f.count;
  }
  header << "end_header\n";
  std::vector<std::uint8_t> body (points * record);
  std::uint8_t *out = body.data ();
  for (std::uint64_t i = 0; i < points; ++i)
  {
    const std::uint8_t *point = cloud.data.data () + i * cloud.point_step;
    for (const auto &f : fields)
    {
      if (isPackedColour (f))
      {
        std::uint32_t packed = 0;  // 0xAARRGGBB, as PCL packs it
        std::memcpy (&packed, point + f.offset, 4);
        *out++ = static_cast<std::uint8_t> (packed >> 16);
        *out++ = static_cast<std::uint8_t> (packed >> 8);
        *out++ = static_cast<std::uint8_t> (packed);
        if (f.name == "rgba")
          *out++ = static_cast<std::uint8_t> (packed >> 24);
        continue;
      }
      if (f.count != 1)
      {
        const std::uint32_t count = f.count;
        std::memcpy (out, &count, 4);
        out += 4;
      }
      const std::size_t bytes = sizeOf (f.datatype) * f.count;
      std::memcpy (out, point + f.offset, bytes);
      out += bytes;
    }
  }
  return writeFile (path, header.str (), body.data (), body.size (), error);
}

}  // namespace pcl_holefill_tool
