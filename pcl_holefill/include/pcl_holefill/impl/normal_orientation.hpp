/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/normal_orientation.h>
#include <pcl_holefill/detail/boundary_point_test.h>
#include <pcl_holefill/detail/point_grid.h>
#include <pcl_holefill/detail/point_validity.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>

namespace pcl_holefill
{
namespace detail
{
// A closed surface's normals point away from its centroid nearly
// everywhere: their mean cosine with the way out is 1 on a sphere; an open
// patch's is about 0, either way.
constexpr float kClosedMeanOutward = 0.2f;
// A thin closed part is told by the normals' sum, weighted by each point's
// share of the surface: 0 over a closed surface, the area of the opening
// over an open one (a saddle: 0.95 of its area; closed parts, with three
// holes or a density varying 4 times: 0.002-0.02).
constexpr float kMaxOpenShare = 0.1f;
// Its sign is that of its volume, if the volume term is at least this share
// of its magnitude (a bowl whose wall is 4 % of its radius: 0.08; a sphere,
// or a plate 7 % as thick as it is wide: 1).
constexpr float kMinVolumeShare = 0.03f;
// Neighbours whose normals lie within 25 degrees of a point's (either way)
// are on its own sheet: PCA normals of noisy samples scatter by up to about
// that, a crease's faces turn further.
constexpr float kSameSheetCosine = 0.9f;

/** Should a consistently oriented part be turned over? Its sign is decided
  * by the whole part, not by the one seed it grew from (on noisy samples the
  * highest point is the noisiest, and a wrong start turned whole clouds
  * inside out): outward on a closed part, else upward (+z, as a scan seen
  * from above).
  *
  * Most closed parts have normals that point away from their centroid. A
  * thin one does not: round a plate, or across a bowl's shell, the faces'
  * normals point away from and towards the centroid about as often (mean
  * cosine 0.14 for a bowl, 0.17 for a plate), and the upward rule was a coin
  * toss that turned a bowl inside out (every convex edge then reads as
  * concave: a hole across its lip 85 % covered instead of 100 %). There the
  * divergence theorem decides: over a closed surface the sum of (p - c) . n
  * dA is three times the volume it encloses, positive when the normals
  * point out. \a areas: each point's share of the surface (any unit). */
template <typename Normal> bool
partFacesInward (const std::vector<int> &part, const std::vector<Eigen::Vector3f> &positions,
                 const std::vector<float> &areas, Normal normal)
{
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero ();
  for (const int i : part)
    centroid += positions[i];
  centroid /= static_cast<float> (part.size ());
  float outward = 0.f, upward = 0.f;
  double volume = 0.0, volume_magnitude = 0.0, area = 0.0;
  Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero ();
  for (const int i : part)
  {
    const Eigen::Vector3f n = normal (i).normalized ();
    const Eigen::Vector3f away = positions[i] - centroid;
    const float length = away.norm ();
    outward += length > 0.f ? n.dot (away) / length : 0.f;
    upward += n.z ();
    const double height = n.dot (away);
    volume += areas[i] * height;
    volume_magnitude += areas[i] * std::abs (height);
    normal_sum += static_cast<double> (areas[i]) * n.cast<double> ();
    area += areas[i];
  }
  if (std::abs (outward) > kClosedMeanOutward * part.size ())
    return outward < 0.f;
  const bool closed = normal_sum.norm () < kMaxOpenShare * area;
  if (closed && std::abs (volume) > kMinVolumeShare * volume_magnitude)
    return volume < 0.0;
  return upward < 0.f;
}

/** The walk of orientNormalsConsistently over one cloud: reaches points
  * from reached neighbours, best-agreeing link first, and flips those the
  * reached neighbours vote against. */
template <typename PointT>
class OrientationWalk
{
public:
  OrientationWalk (pcl::PointCloud<PointT> &cloud, std::vector<int> usable, std::vector<Eigen::Vector3f> positions,
                   int k)
    : cloud_ (cloud), usable_ (std::move (usable)), positions_ (std::move (positions)), k_ (k),
      grid_ (detail::PointGrid::suggestCellSize (positions_, k)), reached_ (usable_.size (), 0),
      areas_ (usable_.size (), 0.f)
  {
    grid_.build (positions_);
  }

  const std::vector<Eigen::Vector3f> &
  positions () const { return positions_; }

  /** Orients the part of the cloud connected to \a seed (usable index)
    * unless reached before; returns how many of its normals were flipped. */
  std::size_t
  orientPart (int seed)
  {
    if (reached_[seed])
      return 0;
    part_.clear ();
    std::size_t part_flipped = reach (seed, seed) ? 1 : 0;
    while (!links_.empty ())  // every point is reached once and queues at most k + 1 links
    {
      const auto [from, to] = links_.top ().second;
      links_.pop ();
      if (!reached_[to])
        part_flipped += reach (from, to) ? 1 : 0;
    }
    auto normal = [this] (int local) { return this->normal (local); };
    if (partFacesInward (part_, positions_, areas_, normal))
    {
      for (const int i : part_)
        this->normal (i) = -this->normal (i);
      part_flipped = part_.size () - part_flipped;  // the ones not flipped before are now
    }
    return part_flipped;
  }

private:
  using Link = std::pair<float, std::pair<int, int>>;  // (agreement, (from, to)), best first

  Eigen::Map<Eigen::Vector3f>
  normal (int local) { return cloud_[usable_[local]].getNormalVector3fMap (); }

  // How much two oriented points agree: the normals' dot product, plus, for
  // points across a sharp edge (dot near 0), whether each lies on the same
  // side of the other's tangent plane (both below on a convex edge, both
  // above on a concave one). Positive: consistent; negative: one is flipped.
  // The side test counts only as far as the normals are not parallel: for
  // close points on noisy samples it is mostly noise (it turned a fifth of
  // a noisy sphere inside out).
  float
  agreement (int a, int b)
  {
    const Eigen::Vector3f na = normal (a).normalized (), nb = normal (b).normalized ();
    const Eigen::Vector3f d = positions_[b] - positions_[a];
    const float length = d.norm ();
    const float side = length > 0.f ? (d.dot (na) / length) * (-d.dot (nb) / length) : 0.f;
    const float dot = na.dot (nb);
    return dot + 2.f * (1.f - std::abs (dot)) * side;
  }

  // How the reached neighbours vote on \a to's sign (positive: keep),
  // reached from \a from; near_ holds its neighbours. Every reached
  // neighbour votes, not only \a from (on noisy samples one close pair's
  // side test is a coin toss: noise of 0.3 % of the diagonal flipped whole
  // faces of a cube), and \a from always does (kNN is not symmetric). Once
  // a neighbour on its own sheet has voted (normals within
  // kSameSheetCosine, either way), only those count: across an acute edge
  // (a star's tips, 44 degrees) the faces' normals are 136 degrees apart,
  // and pairs with one point on the edge and the other on the far face, or
  // both along the edge, lie in each other's tangent planes: neither the
  // dot product nor the sides tell a flipped face from a gently bent one,
  // and they voted for the flip (exact normals, signs scrambled: 342-1,422
  // of 20,000 came out inward; 0 now). A point whose reached neighbours
  // all lie across an edge (the first one reached on a face) is decided
  // by them, as before. A part's seed (\a from = \a to) also votes upward.
  float
  voteOn (int from, int to)
  {
    const Eigen::Vector3f own = normal (to).normalized ();
    float vote = from == to ? own.z () : 0.f, same_sheet_vote = 0.f;
    bool same_sheet_voted = false;
    const auto count = [&] (int voter) {
      const float a = agreement (voter, to);
      vote += a;
      if (std::abs (normal (voter).normalized ().dot (own)) >= kSameSheetCosine)
      {
        same_sheet_vote += a;
        same_sheet_voted = true;
      }
    };
    bool from_voted = from == to;
    for (const auto &n : near_)
      if (reached_[n.id])
      {
        count (n.id);
        from_voted = from_voted || n.id == from;
      }
    if (!from_voted)
      count (from);
    return same_sheet_voted && from != to ? same_sheet_vote : vote;
  }

  // Reaches \a to from the reached \a from, flips it if voteOn says so,
  // then queues the links to its unreached neighbours; true if it was flipped.
  bool
  reach (int from, int to)
  {
    grid_.nearestK (positions_[to], k_ + 1, near_);
    const float vote = voteOn (from, to);
    reached_[to] = 1;
    part_.push_back (to);
    // Its share of the surface: that of a disc through its k-th neighbour.
    areas_[to] = near_.size () > 1 ? near_.back ().sqr_distance : 0.f;
    const bool flip = vote < 0.f;
    if (flip)
      normal (to) = -normal (to);
    for (const auto &n : near_)
      if (!reached_[n.id])
        links_.push ({std::abs (agreement (to, n.id)), {to, n.id}});
    return flip;
  }

  pcl::PointCloud<PointT> &cloud_;
  const std::vector<int> usable_;                   //!< cloud index of each oriented point
  const std::vector<Eigen::Vector3f> positions_;    //!< their positions
  const int k_;
  detail::PointGrid grid_;
  std::vector<char> reached_;
  std::vector<float> areas_;  //!< each point's share of the surface (partFacesInward)
  std::vector<detail::PointGrid::Neighbour> near_;
  std::priority_queue<Link> links_;
  std::vector<int> part_;
};
}  // namespace detail

template <typename PointT> std::size_t
orientNormalsConsistently (pcl::PointCloud<PointT> &cloud, int k)
{
  std::vector<Eigen::Vector3f> positions;
  std::vector<int> usable;
  for (std::size_t i = 0; i < cloud.size (); ++i)
    if (detail::isOrientedPoint (cloud[i]))
    {
      usable.push_back (static_cast<int> (i));
      positions.push_back (cloud[i].getVector3fMap ());
    }
  if (usable.empty ())
    return 0;
  detail::OrientationWalk<PointT> walk (cloud, std::move (usable), std::move (positions), k);
  // Seeds in order of decreasing z: each unreached one starts a new part.
  const auto &at = walk.positions ();
  std::vector<int> seeds (at.size ());
  std::iota (seeds.begin (), seeds.end (), 0);
  std::sort (seeds.begin (), seeds.end (), [&] (int a, int b) { return at[a].z () > at[b].z (); });
  std::size_t flipped = 0;
  for (const int seed : seeds)
    flipped += walk.orientPart (seed);
  return flipped;
}

template <typename PointT> float
flippedNeighbourShare (const pcl::PointCloud<PointT> &cloud, int k, std::size_t samples)
{
  // An even subsample of at most 25 x samples points is enough to see
  // orientation, and keeps this check small next to the cloud.
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
  const std::size_t keep_every = std::max<std::size_t> (1, cloud.size () / (25 * std::max<std::size_t> (samples, 1)));
  for (std::size_t i = 0; i < cloud.size (); i += keep_every)
    if (detail::isOrientedPoint (cloud[i]))
    {
      positions.push_back (cloud[i].getVector3fMap ());
      normals.push_back (cloud[i].getNormalVector3fMap ().normalized ());
    }
  if (positions.size () < 2 || samples == 0)
    return 0.f;
  detail::PointGrid grid (detail::PointGrid::suggestCellSize (positions, k));
  grid.build (positions);
  std::vector<detail::PointGrid::Neighbour> near;
  std::size_t pairs = 0, flipped = 0;
  const std::size_t stride = std::max<std::size_t> (1, positions.size () / samples);
  for (std::size_t i = 0; i < positions.size (); i += stride)
  {
    grid.nearestK (positions[i], k + 1, near);
    for (const auto &n : near)
      if (n.id != static_cast<int> (i) &&
          !detail::onOtherSideOfThinPart (positions[n.id] - positions[i], normals[i], normals[n.id]))
      {
        ++pairs;
        flipped += normals[i].dot (normals[n.id]) < -0.5f;
      }
  }
  return pairs ? static_cast<float> (flipped) / pairs : 0.f;
}

}  // namespace pcl_holefill

#define PCL_INSTANTIATE_flippedNeighbourShare(T) \
  template float pcl_holefill::flippedNeighbourShare<T> (const pcl::PointCloud<T> &, int, std::size_t);
#define PCL_INSTANTIATE_orientNormalsConsistently(T) \
  template std::size_t pcl_holefill::orientNormalsConsistently<T> (pcl::PointCloud<T> &, int);
