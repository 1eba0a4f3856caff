/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/bilateral_preprocessor.h>
#include <pcl_holefill/impl/bilateral_preprocessor.hpp>
#include <pcl_holefill/instantiation.h>

#ifndef PCL_NO_PRECOMPILE
PCL_HOLEFILL_INSTANTIATE (BilateralPreprocessor)
#endif
