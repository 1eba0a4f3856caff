/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "file_check.h"

#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace pcl_holefill_tool
{
namespace
{
constexpr std::size_t kMaxHeader = 64 * 1024;
constexpr std::uint64_t kMaxPoints = 1ULL << 31;

/** Reads header lines until \a last_key starts a line (inclusive). False if
  * none within kMaxHeader bytes. \a header_bytes counts what was read. */
bool
readHeader (std::ifstream &in, const std::string &last_key, std::vector<std::string> &lines,
            std::uint64_t &header_bytes)
{
  std::string line;
  header_bytes = 0;
  while (header_bytes < kMaxHeader && std::getline (in, line))
  {
    header_bytes += line.size () + 1;
    if (!line.empty () && line.back () == '\r')
      line.pop_back ();
    lines.push_back (line);
    if (line.compare (0, last_key.size (), last_key) == 0)
      return true;
  }
  return false;
}

bool
toCount (const std::string &word, std::uint64_t &value)
{
  if (word.empty () || word.find_first_not_of ("0123456789") != std::string::npos || word.size () > 12)
    return false;
  value = std::stoull (word);
  return true;
}

std::uint64_t
fileSize (const std::string &path)
{
  std::ifstream in (path, std::ios::binary | std::ios::ate);
  return in ? static_cast<std::uint64_t> (in.tellg ()) : 0;
}

bool
checkPcd (const std::string &path, std::string &error)
{
  std::ifstream in (path, std::ios::binary);
  std::vector<std::string> lines;
  std::uint64_t header_bytes = 0;
  if (!readHeader (in, "DATA", lines, header_bytes))
  {
    error = "no PCD header (no DATA line)";
    return false;
  }
  std::map<std::string, std::vector<std::string>> entries;
  for (const auto &line : lines)
  {
    if (line.empty () || line[0] == '#')
      continue;
    std::istringstream words (line);
    std::string key, word;
    words >> key;
    while (words >> word)
      entries[key].push_back (word);
  }
  const auto &fields = entries["FIELDS"];
  const auto &sizes = entries["SIZE"];
  const auto &types = entries["TYPE"];
  auto counts = entries["COUNT"];
  if (fields.empty () || sizes.size () != fields.size () || types.size () != fields.size ())
  {
    error = "PCD header: FIELDS, SIZE and TYPE must name the same number of fields";
    return false;
  }
  if (counts.empty ())
    counts.assign (fields.size (), "1");
  if (counts.size () != fields.size ())
  {
    error = "PCD header: COUNT does not match FIELDS";
    return false;
  }
  std::uint64_t point_size = 0;
  for (std::size_t i = 0; i < fields.size (); ++i)
  {
    std::uint64_t size = 0, count = 0;
    if (!toCount (sizes[i], size) || (size != 1 && size != 2 && size != 4 && size != 8) ||
        (types[i] != "F" && types[i] != "I" && types[i] != "U") || !toCount (counts[i], count) || count == 0 ||
        count > 100000 || (types[i] == "F" && size < 4))
    {
      error = "PCD header: field '" + fields[i] + "' has a bad SIZE, TYPE or COUNT";
      return false;
    }
    point_size += size * count;
  }
  std::uint64_t width = 0, height = 1, points = 0;
  const auto &w = entries["WIDTH"], &h = entries["HEIGHT"], &p = entries["POINTS"];
  if (w.size () != 1 || !toCount (w[0], width) || (h.size () == 1 && !toCount (h[0], height)) ||
      (p.size () == 1 && (!toCount (p[0], points) || points != width * height)) || width * height > kMaxPoints)
  {
    error = "PCD header: WIDTH, HEIGHT and POINTS are missing or disagree";
    return false;
  }
  points = width * height;
  const auto &data = entries["DATA"];
  if (data.size () != 1 || (data[0] != "ascii" && data[0] != "binary" && data[0] != "binary_compressed"))
  {
    error = "PCD header: DATA must be ascii, binary or binary_compressed";
    return false;
  }
  const std::uint64_t body = fileSize (path) - std::min (fileSize (path), header_bytes);
  if (data[0] == "binary" && body < points * point_size)
  {
    error = "the file is shorter than the " + std::to_string (points) + " points its header announces";
    return false;
  }
  if (data[0] == "binary_compressed")
  {
    std::uint32_t sizes_in_file[2] = {0, 0};
    in.read (reinterpret_cast<char *> (sizes_in_file), sizeof (sizes_in_file));
    if (!in || body < 8 + static_cast<std::uint64_t> (sizes_in_file[0]) ||
        sizes_in_file[1] != points * point_size)
    {
      error = "the compressed data does not match the header";
      return false;
    }
  }
  return true;
}

std::uint64_t
plyTypeSize (const std::string &type)
{
  static const std::map<std::string, std::uint64_t> sizes{
      {"char", 1},  {"uchar", 1},  {"int8", 1},  {"uint8", 1},   {"short", 2},  {"ushort", 2},  {"int16", 2},
      {"uint16", 2}, {"int", 4},   {"uint", 4},  {"int32", 4},   {"uint32", 4}, {"float", 4},   {"float32", 4},
      {"double", 8}, {"float64", 8}};
  const auto it = sizes.find (type);
  return it == sizes.end () ? 0 : it->second;
}

bool
checkPly (const std::string &path, std::string &error)
{
  std::ifstream in (path, std::ios::binary);
  std::vector<std::string> lines;
  std::uint64_t header_bytes = 0;
  if (!readHeader (in, "end_header", lines, header_bytes) || lines.empty () || lines[0] != "ply")
  {
    error = "no PLY header ('ply' ... 'end_header')";
    return false;
  }
  std::string format;
  struct Element
  {
    std::string name;
    std::uint64_t count = 0;
    std::uint64_t scalar_bytes = 0;
    bool has_list = false;
    int xyz = 0;
  };
  std::vector<Element> elements;
  for (std::size_t i = 1; i + 1 < lines.size (); ++i)
  {
    std::istringstream words (lines[i]);
    std::string key;
    words >> key;
    if (key == "format")
      words >> format;
    else if (key == "element")
    {
      Element e;
      std::string count;
      words >> e.name >> count;
      if (!toCount (count, e.count) || e.count > kMaxPoints)
      {
        error = "PLY header: bad count in '" + lines[i] + "'";
        return false;
      }
      elements.push_back (e);
    }
    else if (key == "property")
    {
      if (elements.empty ())
      {
        error = "PLY header: a property before any element";
        return false;
      }
      std::string type, name;
      words >> type;
      if (type == "list")
      {
        std::string count_type, item_type;
        words >> count_type >> item_type >> name;
        if (!plyTypeSize (count_type) || !plyTypeSize (item_type))
        {
          error = "PLY header: bad list property '" + lines[i] + "'";
          return false;
        }
        elements.back ().has_list = true;
        continue;
      }
      words >> name;
      if (!plyTypeSize (type) || name.empty ())
      {
        error = "PLY header: bad property '" + lines[i] + "'";
        return false;
      }
      elements.back ().scalar_bytes += plyTypeSize (type);
      elements.back ().xyz += name == "x" || name == "y" || name == "z";
    }
    else if (key != "comment" && key != "obj_info" && !key.empty ())
    {
      error = "PLY header: unknown line '" + lines[i] + "'";
      return false;
    }
  }
  if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
  {
    error = "PLY header: unknown format '" + format + "'";
    return false;
  }
  if (elements.empty () || elements[0].name != "vertex" || elements[0].xyz != 3)
  {
    error = "PLY header: the first element must be 'vertex' with x, y and z";
    return false;
  }
  if (format != "ascii" && !elements[0].has_list)
  {
    const std::uint64_t body = fileSize (path) - std::min (fileSize (path), header_bytes);
    if (body < elements[0].count * elements[0].scalar_bytes)
    {
      error = "the file is shorter than the " + std::to_string (elements[0].count) + " vertices its header announces";
      return false;
    }
  }
  return true;
}
}  // namespace

bool
checkCloudFile (const std::string &path, const std::string &format, std::string &error)
{
  std::string reason;
  const bool ok = format == "pcd" ? checkPcd (path, reason) : checkPly (path, reason);
  if (!ok)
    error = "'" + path + "' is not a readable " + format + " point cloud: " + reason;
  return ok;
}

}  // namespace pcl_holefill_tool
