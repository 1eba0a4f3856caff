/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include "shapes.h"

#include <string>
#include <vector>

/** Holes at corners, on sharp edges and on smooth parts of each test shape,
  * far enough apart (and from open borders) that each leaves its own rim. */
namespace test_cases
{
using pcl_holefill::shapes::Ball;
using V = Eigen::Vector3d;

struct Case
{
  pcl_holefill::shapes::Shape shape;
  std::size_t points;
  std::vector<Ball> holes;  // the first 1, 2 or 5 are used
};

inline std::vector<Case>
detectionCases ()
{
  using namespace pcl_holefill::shapes;
  return {
      {cube (), 9192,
       {{V (1, 1, 1), 0.2}, {V (0, 0.5, 0), 0.18}, {V (0.5, 0.5, 1), 0.15}, {V (0, 0, 1), 0.15}, {V (1, 0, 0.5), 0.15}}},
      {sphere (), 4320,
       {{V (0.5, 0.5, 1.0), 0.2}, {V (0.5, 0.5, 0.0), 0.2}, {V (1.0, 0.5, 0.5), 0.2}, {V (0.0, 0.5, 0.5), 0.2},
        {V (0.5, 1.0, 0.5), 0.2}}},
      {openPyramid (), 4000,
       {{V (0.5, 0.5, 1.0), 0.2}, {V (0.75, 0.75, 0.5), 0.1}, {V (0.5, 1.0 / 6, 1.0 / 3), 0.1},
        {V (5.0 / 6, 0.5, 1.0 / 3), 0.1}, {V (1.0 / 6, 0.5, 1.0 / 3), 0.1}}},
      {dihedral (), 4000,
       {{V (0.5, 0.5, 1.0), 0.12}, {V (0.5, 0.22, 0.72), 0.12}, {V (0.2, 0.5, 1.0), 0.12},
        {V (0.8, 0.5, 1.0), 0.12}, {V (0.5, 0.78, 0.72), 0.12}}},
      {flatPatch (), 4000,
       {{V (0.5, 0.5, 0.5), 0.12}, {V (0.25, 0.25, 0.5), 0.1}, {V (0.75, 0.25, 0.5), 0.1},
        {V (0.25, 0.75, 0.5), 0.1}, {V (0.75, 0.75, 0.5), 0.1}}},
  };
}

}  // namespace test_cases
