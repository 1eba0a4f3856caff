/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include "shapes.h"

#include <string>

namespace bench
{
/** \brief Reads a triangle (or convex polygon) mesh in OFF format as a
  * shapes::Shape (faces with exact normals and distance), scaled uniformly
  * into the unit cube as the paper's protocol asks. */
bool
readOffMesh (const std::string &path, pcl_holefill::shapes::Shape &shape, std::string &error);

/** \brief A vertex where three or more faces with normals more than 30
  * degrees apart meet (a sharp corner), the one farthest from the centroid. */
Eigen::Vector3d
sharpCorner (const pcl_holefill::shapes::Shape &shape);

/** \brief The midpoint of a sharp edge (faces more than 30 degrees apart)
  * farthest from every sharp corner. */
Eigen::Vector3d
sharpEdgePoint (const pcl_holefill::shapes::Shape &shape);

}  // namespace bench
