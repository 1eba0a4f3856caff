/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/hole_filling.h>
#include <pcl_holefill/impl/hole_filling.hpp>
#include <pcl_holefill/instantiation.h>

namespace pcl_holefill
{
const char *
toString (Termination termination)
{
  switch (termination)
  {
  case Termination::kNotStarted: return "not_started";
  case Termination::kControlRatio: return "ratio";
  case Termination::kNoNewBoundary: return "no_new_boundary";
  case Termination::kDiverging: return "diverging";
  case Termination::kPassLimit: return "pass_limit";
  }
  return "unknown";
}
}  // namespace pcl_holefill

#ifndef PCL_NO_PRECOMPILE
PCL_HOLEFILL_INSTANTIATE (HoleFilling)
#endif
