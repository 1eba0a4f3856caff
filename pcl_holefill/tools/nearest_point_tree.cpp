/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "nearest_point_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_holefill_tool
{
namespace
{
// Points per leaf: a leaf is read whole, so a few more than one cache line's worth.
constexpr int kLeafSize = 8;
// Median splits halve the entries: the depth stays under log2(points), far
// below this even for 2^31 points; the bound only guards against a bug.
constexpr int kMaxDepth = 64;
}  // namespace

NearestPointTree::NearestPointTree (const pcl::PointCloud<pcl::PointNormal> &cloud, const pcl::Indices *indices)
{
  const std::size_t count = indices ? indices->size () : cloud.size ();
  entries_.reserve (count);
  for (std::size_t k = 0; k < count; ++k)
  {
    const int i = indices ? (*indices)[k] : static_cast<int> (k);
    const pcl::PointNormal &p = cloud[i];
    if (std::isfinite (p.x) && std::isfinite (p.y) && std::isfinite (p.z))
      entries_.push_back ({{p.x, p.y, p.z}, i});
  }
  if (!entries_.empty ())
  {
    nodes_.reserve (4 * entries_.size () / kLeafSize + 1);
    build (0, static_cast<int> (entries_.size ()), 0);
  }
}

int
NearestPointTree::build (int begin, int end, int depth)
{
  const int node = static_cast<int> (nodes_.size ());
  nodes_.push_back ({});
  Node n;
  n.begin = begin;
  n.end = end;
  for (int d = 0; d < 3; ++d)
    n.lo[d] = n.hi[d] = entries_[begin].p[d];
  for (int k = begin + 1; k < end; ++k)
    for (int d = 0; d < 3; ++d)
    {
      n.lo[d] = std::min (n.lo[d], entries_[k].p[d]);
      n.hi[d] = std::max (n.hi[d], entries_[k].p[d]);
    }
  int axis = 0;
  for (int d = 1; d < 3; ++d)
    if (n.hi[d] - n.lo[d] > n.hi[axis] - n.lo[axis])
      axis = d;
  if (end - begin > kLeafSize && depth < kMaxDepth && n.hi[axis] > n.lo[axis])
  {
    const int middle = begin + (end - begin) / 2;
    std::nth_element (entries_.begin () + begin, entries_.begin () + middle, entries_.begin () + end,
                      [axis] (const Entry &a, const Entry &b) { return a.p[axis] < b.p[axis]; });
    n.axis = axis;
    n.split = entries_[middle].p[axis];
    n.below = build (begin, middle, depth + 1);
    n.above = build (middle, end, depth + 1);
  }
  nodes_[node] = n;
  return node;
}

float
NearestPointTree::boxSqrDistance (int node, const float *q) const
{
  const Node &n = nodes_[node];
  float sqr = 0.f;
  for (int d = 0; d < 3; ++d)
  {
    const float out = std::max ({n.lo[d] - q[d], q[d] - n.hi[d], 0.f});
    sqr += out * out;
  }
  return sqr;
}

void
NearestPointTree::search (int node, const float *q, float &best_sqr, int &best) const
{
  const Node &n = nodes_[node];
  if (n.axis < 0)
  {
    for (int k = n.begin; k < n.end; ++k)
    {
      const Entry &e = entries_[k];
      const float dx = e.p[0] - q[0], dy = e.p[1] - q[1], dz = e.p[2] - q[2];
      const float d2 = dx * dx + dy * dy + dz * dz;
      if (d2 < best_sqr)
      {
        best_sqr = d2;
        best = e.index;
      }
    }
    return;
  }
  // The nearer child first; a child only if its points' box is nearer than
  // the best so far. Tight boxes, not the split's half-spaces: a query deep
  // in a hole is far from every point, and the half-spaces around the rim
  // reach across the empty hole (most of the tree passed that test).
  const float to_below = boxSqrDistance (n.below, q), to_above = boxSqrDistance (n.above, q);
  const bool below_first = to_below <= to_above;
  const int first = below_first ? n.below : n.above, second = below_first ? n.above : n.below;
  if ((below_first ? to_below : to_above) < best_sqr)
    search (first, q, best_sqr, best);
  if ((below_first ? to_above : to_below) < best_sqr)
    search (second, q, best_sqr, best);
}

int
NearestPointTree::nearest (const Eigen::Vector3f &query, float &sqr_distance) const
{
  sqr_distance = std::numeric_limits<float>::infinity ();
  if (entries_.empty () || !query.allFinite ())
    return -1;
  int best = -1;
  const float q[3] = {query.x (), query.y (), query.z ()};
  search (0, q, sqr_distance, best);
  return best;
}

}  // namespace pcl_holefill_tool
