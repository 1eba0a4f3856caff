/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "shapes.h"

#include <gtest/gtest.h>

using namespace pcl_holefill::shapes;

TEST (Shapes, SamplesLieOnTheirSurfaceWithUnitNormals)
{
  for (const Shape &s : {sphere (), cube (), openPyramid (), dihedral (), flatPatch ()})
  {
    const Cloud c = s.sample (3000);
    EXPECT_NEAR (static_cast<double> (c.size ()), 3000.0, 300.0) << s.name;
    for (const auto &p : c)
    {
      ASSERT_LT (s.distance (p.getVector3fMap ().cast<double> ()), 1e-6) << s.name;
      ASSERT_NEAR (p.getNormalVector3fMap ().norm (), 1.f, 1e-5f) << s.name;
      // The normal is the surface's: a step along it leaves the surface by that step.
      const Eigen::Vector3d off = (p.getVector3fMap () + 0.01f * p.getNormalVector3fMap ()).cast<double> ();
      ASSERT_NEAR (s.distance (off), 0.01, 1e-3) << s.name;
    }
  }
}

TEST (Shapes, DistanceIsExactOffTheSurface)
{
  EXPECT_NEAR (cube ().distance ({0.5, 0.5, 0.5}), 0.5, 1e-12);
  EXPECT_NEAR (cube ().distance ({1.2, 0.5, 0.5}), 0.2, 1e-12);
  EXPECT_NEAR (sphere ().distance ({0.5, 0.5, 0.5}), 0.5, 1e-12);
  EXPECT_NEAR (openPyramid ().distance ({0.5, 0.5, 0.0}), 0.5 * std::sin (std::atan (0.5)) * 2.0, 1e-9);
  EXPECT_NEAR (dihedral ().distance ({0.5, 0.5, 1.1}), 0.1, 1e-12);
}

TEST (Shapes, CutHolesKeepsTheGroundTruth)
{
  const Cloud c = cube ().sample (6000);
  const CutCloud cut = cutHoles (c, {{{1, 1, 1}, 0.2}});
  EXPECT_EQ (cut.kept.size () + cut.removed.size (), c.size ());
  EXPECT_GT (cut.removed.size (), 50u);
  for (const auto &p : cut.removed)
    EXPECT_LT ((p.getVector3fMap ().cast<double> () - Eigen::Vector3d (1, 1, 1)).norm (), 0.2);
  // The same seed gives the same cloud.
  const Cloud again = cube ().sample (6000);
  ASSERT_EQ (again.size (), c.size ());
  EXPECT_EQ (again[123].x, c[123].x);
}
