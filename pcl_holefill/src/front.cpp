/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/front.h>

namespace pcl_holefill::detail
{
float
frontLength (const Front &front)
{
  float length = 0.f;
  for (const auto &chain : front)
  {
    const auto &v = chain.vertices;
    for (std::size_t i = 1; i < v.size (); ++i)
      length += (v[i].position - v[i - 1].position).norm ();
    if (chain.closed && v.size () > 2)
      length += (v.front ().position - v.back ().position).norm ();
  }
  return length;
}

}  // namespace pcl_holefill::detail
