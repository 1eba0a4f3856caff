/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <thread>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace pcl_holefill::detail
{
/** \brief PCL's meaning of a thread count: 0 is every core. */
inline int
resolveThreadCount (unsigned int requested)
{
  if (requested > 0)
    return static_cast<int> (requested);
  const unsigned int cores = std::thread::hardware_concurrency ();
  return cores > 0 ? static_cast<int> (cores) : 1;
}

/** \brief The calling thread's number in its OpenMP team (0 outside one,
  * or without OpenMP): an index into per-thread stores. */
inline int
threadNumber ()
{
#if defined(_OPENMP)
  return omp_get_thread_num ();
#else
  return 0;
#endif
}

}  // namespace pcl_holefill::detail
