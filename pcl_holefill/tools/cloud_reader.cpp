/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "cloud_reader.h"
#include "ply_types.h"

#include <pcl/common/io.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

namespace pcl_holefill_tool
{
namespace
{
constexpr std::size_t kMaxHeader = 64 * 1024;
constexpr std::uint64_t kMaxPoints = 1ULL << 31;
constexpr std::uint64_t kMaxBytes = 16ULL << 30;

/** LZF decompression (the format of PCD's binary_compressed, Marc Lehmann's
  * liblzf): \a in of \a in_size bytes into \a out of \a out_size; the
  * number of bytes written, or 0 if the data is not LZF or does not fit. A
  * control byte under 32 starts a run of that many literal bytes plus one;
  * any other is a back reference, its top 3 bits the length less 2 (7:
  * one more byte follows, added), its low 5 bits and the next byte the
  * distance less 1. Every read and every copy is checked against the ends. */
std::size_t
lzfDecompress (const std::uint8_t *in, std::size_t in_size, std::uint8_t *out, std::size_t out_size)
{
  std::size_t ip = 0, op = 0;
  while (ip < in_size)
  {
    const unsigned control = in[ip++];
    if (control < 32)
    {
      const std::size_t literal = control + 1;
      if (ip + literal > in_size || op + literal > out_size)
        return 0;
      std::memcpy (out + op, in + ip, literal);
      ip += literal;
      op += literal;
      continue;
    }
    std::size_t length = control >> 5;
    if (length == 7)
    {
      if (ip >= in_size)
        return 0;
      length += in[ip++];
    }
    length += 2;
    if (ip >= in_size)
      return 0;
    const std::size_t distance = ((static_cast<std::size_t> (control & 0x1f) << 8) | in[ip++]) + 1;
    if (distance > op || op + length > out_size)
      return 0;
    for (std::size_t k = 0; k < length; ++k, ++op)
      out[op] = out[op - distance];  // byte by byte: a reference may overlap what it writes
  }
  return op;
}

/** The whole file (bounded by kMaxBytes). */
bool
slurp (const std::string &path, std::string &bytes, std::string &error)
{
  std::ifstream in (path, std::ios::binary | std::ios::ate);
  if (!in)
  {
    error = "cannot read '" + path + "'";
    return false;
  }
  const auto size = static_cast<std::uint64_t> (in.tellg ());
  if (size > kMaxBytes)
  {
    error = "'" + path + "' is larger than 16 GiB";
    return false;
  }
  bytes.resize (size);
  in.seekg (0);
  in.read (bytes.data (), static_cast<std::streamsize> (size));
  if (!in)
  {
    error = "cannot read '" + path + "'";
    return false;
  }
  return true;
}

/** Header lines up to and including the one that starts with \a last_key;
  * \a body is where the data begins. Printable ASCII only. */
bool
splitHeader (const std::string &bytes, const std::string &last_key, std::vector<std::string> &lines,
             std::size_t &body, std::string &reason)
{
  std::size_t at = 0;
  while (at < bytes.size () && at < kMaxHeader)
  {
    std::size_t end = bytes.find ('\n', at);
    if (end == std::string::npos)
      end = bytes.size ();
    std::string line = bytes.substr (at, end - at);
    if (!line.empty () && line.back () == '\r')
      line.pop_back ();
    for (const unsigned char c : line)
      if ((c < 0x20 && c != '\t') || c > 0x7e)
      {
        reason = "the header has bytes that are not printable ASCII";
        return false;
      }
    lines.push_back (line);
    at = end + 1;
    if (line.compare (0, last_key.size (), last_key) == 0)
    {
      body = std::min (at, bytes.size ());
      return true;
    }
  }
  reason = "no header end ('" + last_key + "') in the first 64 KiB";
  return false;
}

std::vector<std::string>
words (const std::string &line)
{
  std::istringstream in (line);
  return {std::istream_iterator<std::string> (in), std::istream_iterator<std::string> ()};
}

bool
toCount (const std::string &word, std::uint64_t &value)
{
  if (word.empty () || word.size () > 12 || word.find_first_not_of ("0123456789") != std::string::npos)
    return false;
  value = std::stoull (word);
  return true;
}

bool
plainName (const std::string &name)
{
  if (name.empty () || name.size () > 64 || std::isdigit (static_cast<unsigned char> (name[0])))
    return false;
  return std::all_of (name.begin (), name.end (), [] (unsigned char c) { return std::isalnum (c) || c == '_'; });
}

/** A number of an ascii body as the bytes of a field of type \a datatype. */
bool
storeNumber (const std::string &word, std::uint8_t datatype, std::uint8_t *out)
{
  char *end = nullptr;
  const double v = std::strtod (word.c_str (), &end);
  if (end == word.c_str () || *end != '\0')
    return false;
  return storeFieldValue (v, datatype, out);
}

std::uint8_t
pcdDatatype (const std::string &type, std::uint64_t size)
{
  if (type == "F")
    return size == 4 ? pcl::PCLPointField::FLOAT32 : size == 8 ? pcl::PCLPointField::FLOAT64 : 0;
  const bool is_signed = type == "I";
  if (!is_signed && type != "U")
    return 0;
  switch (size)
  {
  case 1: return is_signed ? pcl::PCLPointField::INT8 : pcl::PCLPointField::UINT8;
  case 2: return is_signed ? pcl::PCLPointField::INT16 : pcl::PCLPointField::UINT16;
  case 4: return is_signed ? pcl::PCLPointField::INT32 : pcl::PCLPointField::UINT32;
  case 8: return is_signed ? pcl::PCLPointField::INT64 : pcl::PCLPointField::UINT64;
  default: return 0;
  }
}

void
setShape (pcl::PCLPointCloud2 &cloud, std::uint64_t width, std::uint64_t height, std::uint32_t point_step)
{
  cloud.width = static_cast<std::uint32_t> (width);
  cloud.height = static_cast<std::uint32_t> (height);
  cloud.point_step = point_step;
  cloud.row_step = static_cast<std::uint32_t> (point_step * width);
  cloud.is_bigendian = false;
  cloud.is_dense = false;
}

using PcdEntries = std::map<std::string, std::vector<std::string>>;

/** The header's lines by keyword; each keyword known and given once. */
bool
pcdEntries (const std::vector<std::string> &lines, PcdEntries &entries, std::string &reason)
{
  static const char *const known[] = {"VERSION", "FIELDS", "SIZE", "TYPE", "COUNT", "WIDTH",
                                      "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
  for (const auto &line : lines)
  {
    const auto w = words (line);
    if (w.empty () || w[0][0] == '#')
      continue;
    if (std::none_of (std::begin (known), std::end (known), [&w] (const char *k) { return w[0] == k; }))
    {
      reason = "unknown header line '" + line.substr (0, 40) + "'";
      return false;
    }
    if (entries.count (w[0]))
    {
      reason = w[0] + " given twice";
      return false;
    }
    entries[w[0]].assign (w.begin () + 1, w.end ());
  }
  const auto &version = entries["VERSION"];
  if (version.size () != 1 || (version[0] != ".7" && version[0] != "0.7"))
  {
    reason = "VERSION must be 0.7";
    return false;
  }
  return true;
}

/** One FIELDS entry: its type and room in a point ("_" is padding). */
struct PcdField
{
  std::uint8_t datatype = 0;
  std::uint64_t size = 0;   //!< bytes of one value
  std::uint64_t count = 0;  //!< values
};

/** FIELDS, SIZE, TYPE and COUNT into the cloud's fields and their layout. */
bool
pcdFields (PcdEntries &entries, pcl::PCLPointCloud2 &cloud, std::vector<PcdField> &layout,
           std::uint64_t &point_step, std::string &reason)
{
  const auto &names = entries["FIELDS"], &sizes = entries["SIZE"], &types = entries["TYPE"];
  auto counts = entries["COUNT"];
  if (counts.empty ())
    counts.assign (names.size (), "1");
  if (names.empty () || sizes.size () != names.size () || types.size () != names.size () ||
      counts.size () != names.size ())
  {
    reason = "FIELDS, SIZE, TYPE and COUNT must name the same fields";
    return false;
  }
  cloud = pcl::PCLPointCloud2 ();
  point_step = 0;
  for (std::size_t i = 0; i < names.size (); ++i)
  {
    PcdField f;
    f.datatype = toCount (sizes[i], f.size) ? pcdDatatype (types[i], f.size) : 0;
    if (!f.datatype || !toCount (counts[i], f.count) || f.count == 0 || f.count > 100000 ||
        (names[i] != "_" && !plainName (names[i])))
    {
      reason = "field '" + names[i].substr (0, 20) + "' has a bad name, SIZE, TYPE or COUNT";
      return false;
    }
    if (names[i] != "_")  // "_" is padding: it takes room but is not a field
    {
      pcl::PCLPointField field;
      field.name = names[i];
      field.offset = static_cast<std::uint32_t> (point_step);
      field.datatype = f.datatype;
      field.count = static_cast<std::uint32_t> (f.count);
      cloud.fields.push_back (field);
    }
    layout.push_back (f);
    point_step += f.size * f.count;
  }
  return true;
}

/** WIDTH, HEIGHT, POINTS and VIEWPOINT: the number of points. */
bool
pcdShape (PcdEntries &entries, std::uint64_t point_step, std::uint64_t &width, std::uint64_t &height,
          std::string &reason)
{
  std::uint64_t points = 0;
  height = 1;
  const auto &w = entries["WIDTH"], &h = entries["HEIGHT"], &p = entries["POINTS"], &viewpoint = entries["VIEWPOINT"];
  if (w.size () != 1 || !toCount (w[0], width) || (h.size () == 1 && !toCount (h[0], height)) || h.size () > 1 ||
      (p.size () == 1 && (!toCount (p[0], points) || points != width * height)) || p.size () > 1 ||
      width * height > kMaxPoints || (!viewpoint.empty () && viewpoint.size () != 7) || point_step > 1000000)
  {
    reason = "WIDTH, HEIGHT, POINTS or VIEWPOINT are missing or disagree";
    return false;
  }
  return true;
}

/** DATA binary_compressed: LZF, stored field by field (all points' first
  * field, then the second ...). */
bool
readPcdCompressed (const std::string &bytes, std::size_t body, const std::vector<PcdField> &layout,
                   pcl::PCLPointCloud2 &cloud, std::uint64_t points, std::string &reason)
{
  const std::uint64_t available = bytes.size () - body, point_step = cloud.point_step;
  std::uint32_t packed[2] = {0, 0};  // compressed, uncompressed
  if (available < sizeof (packed))
  {
    reason = "the compressed data is missing";
    return false;
  }
  std::memcpy (packed, bytes.data () + body, sizeof (packed));
  if (available - sizeof (packed) < packed[0] || packed[1] != points * point_step)
  {
    reason = "the compressed data does not match the header";
    return false;
  }
  std::vector<char> plain (packed[1]);
  if (packed[1] > 0 &&
      lzfDecompress (reinterpret_cast<const std::uint8_t *> (bytes.data ()) + body + sizeof (packed), packed[0],
                     reinterpret_cast<std::uint8_t *> (plain.data ()), packed[1]) != packed[1])
  {
    reason = "the compressed data does not decompress";
    return false;
  }
  cloud.data.resize (points * point_step);
  std::uint64_t source = 0, offset = 0;
  for (const auto &field : layout)
  {
    const std::uint64_t bytes_of_field = field.size * field.count;
    for (std::uint64_t k = 0; k < points; ++k)
      std::memcpy (cloud.data.data () + k * point_step + offset, plain.data () + source + k * bytes_of_field,
                   bytes_of_field);
    source += points * bytes_of_field;
    offset += bytes_of_field;
  }
  return true;
}

/** DATA ascii: one line a point, every value of every field. */
bool
readPcdAscii (const std::string &bytes, std::size_t body, const std::vector<PcdField> &layout,
              pcl::PCLPointCloud2 &cloud, std::uint64_t points, std::string &reason)
{
  const std::uint64_t point_step = cloud.point_step;
  cloud.data.assign (points * point_step, 0);
  std::istringstream text (bytes.substr (body));
  std::string line;
  for (std::uint64_t k = 0; k < points; ++k)
  {
    if (!std::getline (text, line))
    {
      reason = "the file has fewer lines than the " + std::to_string (points) + " points its header announces";
      return false;
    }
    const auto values = words (line);
    std::size_t v = 0;
    std::uint64_t offset = 0;
    for (const auto &field : layout)
      for (std::uint64_t c = 0; c < field.count; ++c, ++v, offset += field.size)
        if (v >= values.size () || !storeNumber (values[v], field.datatype, cloud.data.data () + k * point_step + offset))
        {
          reason = "point " + std::to_string (k) + " has a missing or malformed value";
          return false;
        }
  }
  return true;
}

bool
parsePcd (const std::string &bytes, pcl::PCLPointCloud2 &cloud, std::string &reason)
{
  std::vector<std::string> lines;
  std::size_t body = 0;
  PcdEntries entries;
  std::vector<PcdField> layout;
  std::uint64_t point_step = 0, width = 0, height = 1;
  if (!splitHeader (bytes, "DATA", lines, body, reason) || !pcdEntries (lines, entries, reason) ||
      !pcdFields (entries, cloud, layout, point_step, reason) ||
      !pcdShape (entries, point_step, width, height, reason))
    return false;
  const std::uint64_t points = width * height;
  const auto &data = entries["DATA"];
  setShape (cloud, width, height, static_cast<std::uint32_t> (point_step));
  if (data.size () == 1 && data[0] == "binary")
  {
    if (bytes.size () - body < points * point_step)
    {
      reason = "the file is shorter than the " + std::to_string (points) + " points its header announces";
      return false;
    }
    cloud.data.assign (bytes.begin () + body, bytes.begin () + body + points * point_step);
    return true;
  }
  if (data.size () == 1 && data[0] == "binary_compressed")
    return readPcdCompressed (bytes, body, layout, cloud, points, reason);
  if (data.size () == 1 && data[0] == "ascii")
    return readPcdAscii (bytes, body, layout, cloud, points, reason);
  reason = "DATA must be ascii, binary or binary_compressed";
  return false;
}

// Bounds on what a PLY header may announce (beyond kMaxPoints records).
constexpr std::size_t kMaxPlyElements = 64;
constexpr double kMaxPlyListLength = 1000.0;

struct PlyProperty
{
  std::string name;
  std::uint8_t datatype = 0;  // of the value (or of a list's items)
  std::uint8_t count_type = 0;  // list length type, 0 for a scalar
};

std::uint8_t
plyDatatype (const std::string &type)
{
  for (const PlyType &t : kPlyTypes)
    if (type == t.name || type == t.sized_name)
      return t.datatype;
  return 0;
}

/** Reads one binary value as a double, swapping bytes for big-endian files. */
bool
readBinary (const std::string &bytes, std::size_t &at, std::uint8_t datatype, bool big_endian, double &value)
{
  const std::size_t size = pcl::getFieldSize (datatype);
  if (size == 0 || at + size > bytes.size ())
    return false;
  std::uint8_t raw[8];
  std::memcpy (raw, bytes.data () + at, size);
  if (big_endian)
    std::reverse (raw, raw + size);
  at += size;
  switch (datatype)
  {
  case pcl::PCLPointField::INT8: value = static_cast<std::int8_t> (raw[0]); break;
  case pcl::PCLPointField::UINT8: value = raw[0]; break;
  case pcl::PCLPointField::INT16: { std::int16_t v; std::memcpy (&v, raw, 2); value = v; break; }
  case pcl::PCLPointField::UINT16: { std::uint16_t v; std::memcpy (&v, raw, 2); value = v; break; }
  case pcl::PCLPointField::INT32: { std::int32_t v; std::memcpy (&v, raw, 4); value = v; break; }
  case pcl::PCLPointField::UINT32: { std::uint32_t v; std::memcpy (&v, raw, 4); value = v; break; }
  case pcl::PCLPointField::FLOAT32: { float v; std::memcpy (&v, raw, 4); value = v; break; }
  case pcl::PCLPointField::FLOAT64: { std::memcpy (&value, raw, 8); break; }
  default: return false;
  }
  return true;
}

struct PlyElement
{
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader
{
  bool ascii = false;
  bool big_endian = false;
  std::vector<PlyElement> elements;
  std::size_t body = 0;  //!< offset of the first record
};

/** A "property ..." line of the header. */
bool
parsePlyProperty (const std::vector<std::string> &w, PlyProperty &property)
{
  if (w.size () == 3 && plyDatatype (w[1]) && plainName (w[2]))
  {
    property.datatype = plyDatatype (w[1]);
    property.name = w[2];
    return true;
  }
  if (w.size () == 5 && w[1] == "list" && plyDatatype (w[2]) && plyDatatype (w[3]) && plainName (w[4]))
  {
    property.count_type = plyDatatype (w[2]);
    property.datatype = plyDatatype (w[3]);
    property.name = w[4];
    return true;
  }
  return false;
}

/** The header: format and every element with its properties, in file order. */
bool
parsePlyHeader (const std::string &bytes, PlyHeader &header, std::string &reason)
{
  std::vector<std::string> lines;
  if (!splitHeader (bytes, "end_header", lines, header.body, reason))
    return false;
  if (lines.empty () || lines[0] != "ply")
  {
    reason = "not a PLY file (no 'ply' line)";
    return false;
  }
  std::string format;
  for (std::size_t i = 1; i + 1 < lines.size (); ++i)
  {
    const auto w = words (lines[i]);
    PlyProperty property;
    if (w.empty () || w[0] == "comment" || w[0] == "obj_info")
      continue;
    if (w[0] == "format" && w.size () == 3 && w[2] == "1.0")
      format = w[1];
    else if (w[0] == "element" && w.size () == 3)
    {
      PlyElement element;
      element.name = w[1];
      if (!plainName (w[1]) || !toCount (w[2], element.count) || element.count > kMaxPoints ||
          header.elements.size () >= kMaxPlyElements)
      {
        reason = "bad element line '" + lines[i].substr (0, 40) + "'";
        return false;
      }
      header.elements.push_back (element);
    }
    else if (w[0] == "property" && !header.elements.empty () && parsePlyProperty (w, property))
      header.elements.back ().properties.push_back (property);
    else
    {
      reason = (w[0] == "property" ? "bad property line '" : "unknown header line '") + lines[i].substr (0, 40) + "'";
      return false;
    }
  }
  header.ascii = format == "ascii";
  header.big_endian = format == "binary_big_endian";
  if (!header.ascii && !header.big_endian && format != "binary_little_endian")
  {
    reason = "unknown format '" + format + "'";
    return false;
  }
  return true;
}

/** Reads a PLY body record by record: values from the bytes (binary) or
  * from the words of one line per record (ascii). */
class PlyBody
{
public:
  PlyBody (const std::string &bytes, const PlyHeader &header)
    : bytes_ (bytes), header_ (header), at_ (header.body)
  {
  }

  /** Starts the next record (ascii: reads its line). */
  bool
  nextRecord ()
  {
    if (!header_.ascii)
      return true;
    if (at_ >= bytes_.size ())
      return false;
    std::size_t end = bytes_.find ('\n', at_);
    if (end == std::string::npos)
      end = bytes_.size ();
    values_ = words (bytes_.substr (at_, end - at_));
    at_ = end + 1;
    next_word_ = 0;
    return true;
  }

  /** One value of the current record. */
  bool
  value (std::uint8_t datatype, double &out)
  {
    if (!header_.ascii)
      return readBinary (bytes_, at_, datatype, header_.big_endian, out);
    if (next_word_ >= values_.size ())
      return false;
    const std::string &word = values_[next_word_++];
    char *end = nullptr;
    out = std::strtod (word.c_str (), &end);
    return end != word.c_str () && *end == '\0';
  }

  /** Reads past a list property's items (\a length read already). */
  bool
  skipList (const PlyProperty &property, double length)
  {
    if (!(length >= 0.0 && length <= kMaxPlyListLength))
      return false;
    double ignored = 0.0;
    for (int item = 0; item < static_cast<int> (length); ++item)
      if (!value (property.datatype, ignored))
        return false;
    return true;
  }

  /** Reads past every record of \a element (one that comes before the vertices). */
  bool
  skip (const PlyElement &element)
  {
    for (std::uint64_t k = 0; k < element.count; ++k)
    {
      if (!nextRecord ())
        return false;
      for (const auto &property : element.properties)
      {
        double value_read = 0.0;
        if (!value (property.count_type ? property.count_type : property.datatype, value_read) ||
            (property.count_type && !skipList (property, value_read)))
          return false;
      }
    }
    return true;
  }

private:
  const std::string &bytes_;
  const PlyHeader &header_;
  std::size_t at_;
  std::vector<std::string> values_;
  std::size_t next_word_ = 0;
};

/** Where each vertex property goes in the cloud's point. */
struct PlyLayout
{
  std::vector<std::int64_t> offset;  //!< property -> byte offset in the point, -1 if not stored
  int colour[3] = {-1, -1, -1};
  bool packed_rgb = false;
  std::uint32_t rgb_offset = 0;
  std::uint32_t point_step = 0;
};

/** The cloud's fields: the vertex's scalar properties in their own types
  * (a double stays a double, an int an int), colours packed into rgb. */
bool
plyLayout (const std::vector<PlyProperty> &properties, pcl::PCLPointCloud2 &cloud, PlyLayout &layout,
           std::string &reason)
{
  auto index_of = [&properties] (const std::string &name) {
    for (std::size_t i = 0; i < properties.size (); ++i)
      if (properties[i].name == name && properties[i].count_type == 0)
        return static_cast<int> (i);
    return -1;
  };
  if (index_of ("x") < 0 || index_of ("y") < 0 || index_of ("z") < 0)
  {
    reason = "the vertex element has no x, y and z";
    return false;
  }
  const char *colours[3] = {"red", "green", "blue"};
  layout.packed_rgb = true;
  for (int c = 0; c < 3; ++c)
  {
    layout.colour[c] = index_of (colours[c]);
    layout.packed_rgb = layout.packed_rgb && layout.colour[c] >= 0 &&
                        properties[layout.colour[c]].datatype == pcl::PCLPointField::UINT8;
  }
  const auto add_field = [&cloud, &layout] (const std::string &name, std::uint8_t datatype) {
    pcl::PCLPointField field;
    field.name = name;
    field.offset = layout.point_step;
    field.datatype = datatype;
    field.count = 1;
    cloud.fields.push_back (field);
    layout.point_step += static_cast<std::uint32_t> (pcl::getFieldSize (datatype));
  };
  cloud = pcl::PCLPointCloud2 ();
  layout.offset.assign (properties.size (), -1);
  for (std::size_t i = 0; i < properties.size (); ++i)
  {
    const int self = static_cast<int> (i);
    if (properties[i].count_type != 0 ||
        (layout.packed_rgb && (self == layout.colour[0] || self == layout.colour[1] || self == layout.colour[2])))
      continue;
    std::string name = properties[i].name;
    if (name == "nx" || name == "ny" || name == "nz")
      name = std::string ("normal_") + name[1];
    if (std::any_of (cloud.fields.begin (), cloud.fields.end (), [&name] (const auto &f) { return f.name == name; }))
      continue;  // a repeated name: the first one counts
    layout.offset[i] = layout.point_step;
    add_field (name, properties[i].datatype);
  }
  if (layout.packed_rgb)
  {
    layout.rgb_offset = layout.point_step;
    add_field ("rgb", pcl::PCLPointField::FLOAT32);
  }
  return true;
}

/** One vertex record into \a point. */
bool
readPlyVertex (PlyBody &body, const std::vector<PlyProperty> &properties, const PlyLayout &layout,
               std::uint8_t *point)
{
  if (!body.nextRecord ())
    return false;
  std::uint8_t rgb[3] = {0, 0, 0};
  for (std::size_t i = 0; i < properties.size (); ++i)
  {
    double value = 0.0;
    if (!body.value (properties[i].count_type ? properties[i].count_type : properties[i].datatype, value))
      return false;
    if (properties[i].count_type)
    {
      if (!body.skipList (properties[i], value))  // a list on a vertex: read past its items
        return false;
      continue;
    }
    for (int c = 0; c < 3; ++c)
      if (layout.packed_rgb && static_cast<int> (i) == layout.colour[c])
        rgb[c] = static_cast<std::uint8_t> (std::min (255.0, std::max (0.0, value)));
    if (layout.offset[i] >= 0)
      storeFieldValue (value, properties[i].datatype, point + layout.offset[i]);
  }
  if (layout.packed_rgb)
  {
    const std::uint32_t packed = (static_cast<std::uint32_t> (rgb[0]) << 16) |
                                 (static_cast<std::uint32_t> (rgb[1]) << 8) | rgb[2];
    std::memcpy (point + layout.rgb_offset, &packed, 4);
  }
  return true;
}

bool
parsePly (const std::string &bytes, pcl::PCLPointCloud2 &cloud, std::string &reason)
{
  PlyHeader header;
  if (!parsePlyHeader (bytes, header, reason))
    return false;
  const auto vertex = std::find_if (header.elements.begin (), header.elements.end (),
                                    [] (const PlyElement &e) { return e.name == "vertex"; });
  if (vertex == header.elements.end ())
  {
    reason = "no 'vertex' element";
    return false;
  }
  PlyLayout layout;
  if (!plyLayout (vertex->properties, cloud, layout, reason))
    return false;
  // Every record takes at least its scalars' bytes (binary) or a character
  // and a separator per property (ascii): a header that announces more than
  // the file can hold is refused before anything is allocated.
  std::uint64_t least = 0;
  for (const auto &element : header.elements)
    for (const auto &property : element.properties)
      least += element.count *
               (header.ascii ? 2 : pcl::getFieldSize (property.count_type ? property.count_type : property.datatype));
  if (least > bytes.size () - header.body + (header.ascii ? 1 : 0))
  {
    reason = "the file is shorter than the " + std::to_string (vertex->count) + " vertices its header announces";
    return false;
  }
  // Elements before the vertices (PLY allows any order): read past them.
  PlyBody body (bytes, header);
  for (auto element = header.elements.begin (); element != vertex; ++element)
    if (!body.skip (*element))
    {
      reason = "the '" + element->name + "' element before the vertices is truncated or malformed";
      return false;
    }
  setShape (cloud, vertex->count, 1, layout.point_step);
  cloud.data.assign (vertex->count * layout.point_step, 0);
  for (std::uint64_t k = 0; k < vertex->count; ++k)
    if (!readPlyVertex (body, vertex->properties, layout, cloud.data.data () + k * layout.point_step))
    {
      reason = "vertex " + std::to_string (k) + " is truncated or malformed";
      return false;
    }
  return true;
}
}  // namespace

namespace
{
/** Reads the file and runs \a parse on its bytes; one line of error either way. */
bool
readWith (bool (*parse) (const std::string &, pcl::PCLPointCloud2 &, std::string &), const char *format,
          const std::string &path, pcl::PCLPointCloud2 &cloud, std::string &error)
{
  std::string bytes, reason;
  if (!slurp (path, bytes, error))
    return false;
  if (parse (bytes, cloud, reason))
    return true;
  error = "'" + path + "' is not a readable " + format + " point cloud: " + reason;
  return false;
}
}  // namespace

bool
storeFieldValue (double v, std::uint8_t datatype, std::uint8_t *out)
{
  auto put = [out] (auto value) { std::memcpy (out, &value, sizeof (value)); };
  auto integral = [&v] (double lo, double hi) { return std::isnan (v) ? 0.0 : std::min (hi, std::max (lo, v)); };
  switch (datatype)
  {
  case pcl::PCLPointField::INT8: put (static_cast<std::int8_t> (integral (-128, 127))); break;
  case pcl::PCLPointField::UINT8: put (static_cast<std::uint8_t> (integral (0, 255))); break;
  case pcl::PCLPointField::INT16: put (static_cast<std::int16_t> (integral (-32768, 32767))); break;
  case pcl::PCLPointField::UINT16: put (static_cast<std::uint16_t> (integral (0, 65535))); break;
  case pcl::PCLPointField::INT32: put (static_cast<std::int32_t> (integral (-2147483648.0, 2147483647.0))); break;
  case pcl::PCLPointField::UINT32: put (static_cast<std::uint32_t> (integral (0, 4294967295.0))); break;
  case pcl::PCLPointField::INT64: put (static_cast<std::int64_t> (integral (-9.2e18, 9.2e18))); break;
  case pcl::PCLPointField::UINT64: put (static_cast<std::uint64_t> (integral (0, 1.8e19))); break;
  case pcl::PCLPointField::FLOAT32: put (static_cast<float> (v)); break;
  case pcl::PCLPointField::FLOAT64: put (v); break;
  default: return false;
  }
  return true;
}

double
fieldValue (const std::uint8_t *at, std::uint8_t datatype)
{
  auto get = [at] (auto v) {
    std::memcpy (&v, at, sizeof (v));
    return static_cast<double> (v);
  };
  switch (datatype)
  {
  case pcl::PCLPointField::INT8: return get (std::int8_t ());
  case pcl::PCLPointField::UINT8: return get (std::uint8_t ());
  case pcl::PCLPointField::INT16: return get (std::int16_t ());
  case pcl::PCLPointField::UINT16: return get (std::uint16_t ());
  case pcl::PCLPointField::INT32: return get (std::int32_t ());
  case pcl::PCLPointField::UINT32: return get (std::uint32_t ());
  case pcl::PCLPointField::INT64: return get (std::int64_t ());
  case pcl::PCLPointField::UINT64: return get (std::uint64_t ());
  case pcl::PCLPointField::FLOAT32: return get (float ());
  case pcl::PCLPointField::FLOAT64: return get (double ());
  default: return std::numeric_limits<double>::quiet_NaN ();
  }
}

bool
readPcd (const std::string &path, pcl::PCLPointCloud2 &cloud, std::string &error)
{
  return readWith (parsePcd, "pcd", path, cloud, error);
}

bool
readPly (const std::string &path, pcl::PCLPointCloud2 &cloud, std::string &error)
{
  return readWith (parsePly, "ply", path, cloud, error);
}

}  // namespace pcl_holefill_tool
