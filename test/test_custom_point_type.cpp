/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 *
 * Header-only use: with PCL_NO_PRECOMPILE the templates compile for a point
 * type the library was not built for (here pcl::PointXYZLNormal).
 */
#define PCL_NO_PRECOMPILE
#include <pcl_holefill/hole_boundary_estimation.h>
#include <pcl_holefill/hole_filling.h>
#include "shapes.h"

#include <pcl/common/io.h>

#include <gtest/gtest.h>

TEST (HeaderOnly, FillsACloudOfAnotherPointType)
{
  namespace shapes = pcl_holefill::shapes;
  const auto cut = shapes::cutHoles (shapes::dihedral ().sample (4000), {{{0.5, 0.5, 1}, 0.2}});
  pcl::PointCloud<pcl::PointXYZLNormal>::Ptr labelled (new pcl::PointCloud<pcl::PointXYZLNormal>);
  pcl::copyPointCloud (cut.kept, *labelled);
  for (auto &p : *labelled)
    p.label = 42;
  pcl_holefill::HoleFilling<pcl::PointXYZLNormal> filler;
  filler.setInputCloud (labelled);
  pcl::PointCloud<pcl::PointXYZLNormal> output;
  filler.filter (output);
  ASSERT_GT (output.size (), labelled->size ());
  for (std::size_t i = labelled->size (); i < output.size (); ++i)
  {
    EXPECT_LT (shapes::dihedral ().distance (output[i].getVector3fMap ().cast<double> ()), 0.0034);
    EXPECT_EQ (output[i].label, 42u);
  }
}
