/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/normal_propagation.hpp>
#include <pcl_holefill/instantiation.h>
#include <pcl_holefill/detail/normal_propagation.h>

#ifndef PCL_NO_PRECOMPILE
PCL_HOLEFILL_INSTANTIATE (NormalPropagation)
#endif
