/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/voxel_hash_search.h>
#include <pcl_holefill/detail/first_touch.h>
#include <pcl_holefill/detail/thread_count.h>

#include <pcl/common/point_tests.h>

namespace pcl_holefill
{
template <typename PointT>
VoxelHashSearch<PointT>::VoxelHashSearch (int neighbours_per_cell_block)
  : pcl::search::Search<PointT> ("VoxelHashSearch", true),
    neighbours_per_cell_block_ (neighbours_per_cell_block)
{
}

template <typename PointT> void
VoxelHashSearch<PointT>::setInputCloud (const PointCloudConstPtr &cloud,
                                        const pcl::IndicesConstPtr &indices)
{
  input_ = cloud;
  indices_ = indices;
  indexed_points_ = 0;
  if (!cloud)
  {
    grid_.reset (1.f);
    return;
  }
  const int threads = detail::resolveThreadCount (threads_);
  const std::vector<Eigen::Vector3f> positions = detail::gatherPositions (*cloud, indices.get (), threads);
  float cell = requested_cell_size_;
  if (!(cell > 0.f))
    cell = detail::PointGrid::suggestCellSize (positions, neighbours_per_cell_block_);
  grid_.reset (cell > 0.f ? cell : 1.f);
  // Ids are cloud indices, so results need no translation.
  if (indices)
  {
    const std::vector<int> ids (indices->begin (), indices->end ());
    grid_.build (positions, &ids, threads);
  }
  else
    grid_.build (positions, nullptr, threads);
  indexed_points_ = cloud->size ();
}

template <typename PointT> void
VoxelHashSearch<PointT>::indexNewPoints ()
{
  if (!input_ || indices_)
    return;
  for (std::size_t i = indexed_points_; i < input_->size (); ++i)
    grid_.insert ((*input_)[i].getVector3fMap (), static_cast<int> (i));
  indexed_points_ = input_->size ();
}

template <typename PointT> int
VoxelHashSearch<PointT>::toIndices (const std::vector<detail::PointGrid::Neighbour> &found,
                                    pcl::Indices &k_indices, std::vector<float> &k_sqr_distances) const
{
  k_indices.resize (found.size ());
  k_sqr_distances.resize (found.size ());
  for (std::size_t i = 0; i < found.size (); ++i)
  {
    k_indices[i] = found[i].id;
    k_sqr_distances[i] = found[i].sqr_distance;
  }
  return static_cast<int> (found.size ());
}

template <typename PointT> int
VoxelHashSearch<PointT>::nearestKSearch (const PointT &point, int k, pcl::Indices &k_indices,
                                         std::vector<float> &k_sqr_distances) const
{
  std::vector<detail::PointGrid::Neighbour> found;
  grid_.nearestK (point.getVector3fMap (), k, found);
  return toIndices (found, k_indices, k_sqr_distances);
}

template <typename PointT> int
VoxelHashSearch<PointT>::radiusSearch (const PointT &point, double radius, pcl::Indices &k_indices,
                                       std::vector<float> &k_sqr_distances, unsigned int max_nn) const
{
  thread_local std::vector<detail::PointGrid::Neighbour> found;  // kept from call to call
  grid_.withinRadius (point.getVector3fMap (), static_cast<float> (radius), found, max_nn);
  if (sorted_results_ && max_nn == 0)
    std::sort (found.begin (), found.end (), [] (const auto &a, const auto &b) {
      return a.sqr_distance < b.sqr_distance;
    });
  return toIndices (found, k_indices, k_sqr_distances);
}

}  // namespace pcl_holefill

#define PCL_INSTANTIATE_VoxelHashSearch(T) template class pcl_holefill::VoxelHashSearch<T>;
