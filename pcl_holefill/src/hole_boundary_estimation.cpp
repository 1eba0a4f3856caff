/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/hole_boundary_estimation.h>
#include <pcl_holefill/impl/hole_boundary_estimation.hpp>
#include <pcl_holefill/instantiation.h>

#ifndef PCL_NO_PRECOMPILE
PCL_HOLEFILL_INSTANTIATE (HoleBoundaryEstimation)
#endif
