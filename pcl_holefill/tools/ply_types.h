/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/PCLPointField.h>

#include <cstdint>

namespace pcl_holefill_tool
{
/** \brief A PLY scalar type and the PCL field type that holds it. */
struct PlyType
{
  const char *name;        //!< as PLY 1.0 names it, and as the command writes it
  const char *sized_name;  //!< the sized alias other writers use (read too)
  std::uint8_t datatype;   //!< pcl::PCLPointField's type
};

/** \brief Every PLY scalar type, for the reader (cloud_reader.cpp) and the
  * writer (cloud_writer.cpp) alike. PLY has no 64-bit integers and no bool:
  * fields of those types are not written to PLY. */
inline constexpr PlyType kPlyTypes[] = {
    {"char", "int8", pcl::PCLPointField::INT8},      {"uchar", "uint8", pcl::PCLPointField::UINT8},
    {"short", "int16", pcl::PCLPointField::INT16},   {"ushort", "uint16", pcl::PCLPointField::UINT16},
    {"int", "int32", pcl::PCLPointField::INT32},     {"uint", "uint32", pcl::PCLPointField::UINT32},
    {"float", "float32", pcl::PCLPointField::FLOAT32}, {"double", "float64", pcl::PCLPointField::FLOAT64}};

}  // namespace pcl_holefill_tool
