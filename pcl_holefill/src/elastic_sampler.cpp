/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/elastic_sampler.h>
#include <pcl_holefill/detail/elastic_sampler.hpp>
#include <pcl_holefill/instantiation.h>

#ifndef PCL_NO_PRECOMPILE
PCL_HOLEFILL_INSTANTIATE (ElasticSampler)
#endif
