/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/impl/normal_orientation.hpp>
#include <pcl_holefill/instantiation.h>
#include <pcl_holefill/normal_orientation.h>

#ifndef PCL_NO_PRECOMPILE
PCL_HOLEFILL_INSTANTIATE (orientNormalsConsistently)
PCL_HOLEFILL_INSTANTIATE (flippedNeighbourShare)
#endif
