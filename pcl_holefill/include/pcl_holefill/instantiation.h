/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/impl/instantiate.hpp>
#include <pcl/point_types.h>

/** \brief The point types the library is compiled for: every PCL type with
  * xyz and a normal that a scan pipeline commonly carries. Other types work
  * header-only (define PCL_NO_PRECOMPILE before including the headers). */
#define PCL_HOLEFILL_POINT_TYPES (pcl::PointNormal)(pcl::PointXYZRGBNormal)(pcl::PointXYZINormal)

#define PCL_HOLEFILL_INSTANTIATE(TEMPLATE) PCL_INSTANTIATE (TEMPLATE, PCL_HOLEFILL_POINT_TYPES)
