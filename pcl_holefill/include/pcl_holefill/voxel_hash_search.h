/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/detail/point_grid.h>

#include <pcl/point_cloud.h>
#include <pcl/search/search.h>

namespace pcl_holefill
{
/** \brief A pcl::search::Search backed by a hash grid (PointGrid).
  *
  * On clouds sampled from surfaces it answers kNN and radius queries several
  * times faster than a kd-tree, and it can index points appended to its cloud
  * after setInputCloud() without a rebuild (indexNewPoints()), which is what a
  * growing hole patch needs. Any other pcl::search::Search can be injected in
  * its place wherever this module takes a search method.
  */
template <typename PointT>
class VoxelHashSearch : public pcl::search::Search<PointT>
{
public:
  using Ptr = pcl::shared_ptr<VoxelHashSearch<PointT>>;
  using ConstPtr = pcl::shared_ptr<const VoxelHashSearch<PointT>>;
  using PointCloud = pcl::PointCloud<PointT>;
  using PointCloudConstPtr = typename PointCloud::ConstPtr;

  /** \param[in] neighbours_per_cell_block the k the cell size is tuned for
    * when no cell size is set (setCellSize). */
  explicit VoxelHashSearch (int neighbours_per_cell_block = 16);

  /** \brief Fixes the cell edge; 0 (default) derives it from the cloud. */
  void
  setCellSize (float cell_size) { requested_cell_size_ = cell_size; }

  float
  getCellSize () const { return grid_.cellSize (); }

  /** \brief Threads that build the grid in setInputCloud (); 1 (default),
    * 0 = all cores. The grid, and every answer, is the same for any count. */
  void
  setNumberOfThreads (unsigned int threads) { threads_ = threads; }
  unsigned int
  getNumberOfThreads () const { return threads_; }

  void
  setInputCloud (const PointCloudConstPtr &cloud,
                 const pcl::IndicesConstPtr &indices = pcl::IndicesConstPtr ()) override;

  /** \brief Indexes the points appended to the input cloud since the last
    * call (or setInputCloud). Only valid without an indices subset. */
  void
  indexNewPoints ();

  int
  nearestKSearch (const PointT &point, int k, pcl::Indices &k_indices,
                  std::vector<float> &k_sqr_distances) const override;

  int
  radiusSearch (const PointT &point, double radius, pcl::Indices &k_indices,
                std::vector<float> &k_sqr_distances, unsigned int max_nn = 0) const override;

private:
  int
  toIndices (const std::vector<detail::PointGrid::Neighbour> &found, pcl::Indices &k_indices,
             std::vector<float> &k_sqr_distances) const;

  using pcl::search::Search<PointT>::input_;
  using pcl::search::Search<PointT>::indices_;
  using pcl::search::Search<PointT>::sorted_results_;

  int neighbours_per_cell_block_;
  float requested_cell_size_ = 0.f;
  unsigned int threads_ = 1;
  std::size_t indexed_points_ = 0;
  detail::PointGrid grid_;
};

}  // namespace pcl_holefill

#ifdef PCL_NO_PRECOMPILE
#include <pcl_holefill/impl/voxel_hash_search.hpp>
#endif
