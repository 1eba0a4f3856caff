/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/impl/voxel_hash_search.hpp>
#include <pcl_holefill/instantiation.h>
#include <pcl_holefill/voxel_hash_search.h>

#ifndef PCL_NO_PRECOMPILE
PCL_HOLEFILL_INSTANTIATE (VoxelHashSearch)
#endif
