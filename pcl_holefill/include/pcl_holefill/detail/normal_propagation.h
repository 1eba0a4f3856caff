/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/detail/local_surface.h>

#include <pcl/point_cloud.h>
#include <pcl/search/search.h>

namespace pcl_holefill::detail
{
/** \brief Section 3.4 of the paper: the normal of a candidate filling point,
  * propagated from the oriented points around it (equations 1-2).
  *
  * The input cloud is the surface known so far (the input points and what
  * has been filled); the neighbours are those within radius r. Each counts
  * with g1(|p - b|) g2(|n_p - n_ref|), n_ref being the normal of the former
  * boundary point nearest to the candidate, so that near a sharp edge only
  * the candidate's own side speaks (small sigma_n) or both do (sigma_n = kSup).
  *
  * Beyond the paper, setFirstOrder(true) fits a linear normal field with the
  * same weights, which continues the rim's curvature instead of freezing it
  * (see propagateNormal()).
  */
template <typename PointT>
class NormalPropagation
{
public:
  using Ptr = pcl::shared_ptr<NormalPropagation<PointT>>;
  using ConstPtr = pcl::shared_ptr<const NormalPropagation<PointT>>;
  using PointCloud = pcl::PointCloud<PointT>;
  using PointCloudConstPtr = typename PointCloud::ConstPtr;
  using SearchPtr = typename pcl::search::Search<PointT>::Ptr;

  /** \brief The oriented points the normals are propagated from (every
    * point is used: a stage of HoleFilling, it takes no indices). */
  void
  setInputCloud (const PointCloudConstPtr &cloud) { input_ = cloud; }
  const PointCloudConstPtr &
  getInputCloud () const { return input_; }

  /** \brief The search over the input cloud (required; given the cloud by the caller). */
  void
  setSearchMethod (const SearchPtr &search) { search_ = search; }
  SearchPtr
  getSearchMethod () const { return search_; }

  /** \brief Neighbourhood radius r (cloud units, > 0). */
  void
  setRadius (float radius) { radius_ = radius; }
  float
  getRadius () const { return radius_; }

  /** \brief Std of the distance weight g1 (cloud units, > 0). */
  void
  setSigmaD (float sigma_d) { kernel_.sigma_d = sigma_d; }
  float
  getSigmaD () const { return kernel_.sigma_d; }

  /** \brief Std of the normal-dissimilarity weight g2 (no unit, > 0), or kSup to switch it off. */
  void
  setSigmaN (float sigma_n) { kernel_.sigma_n = sigma_n; }
  float
  getSigmaN () const { return kernel_.sigma_n; }

  /** \brief Threads for propagate(); 0 (default) = all cores. */
  void
  setNumberOfThreads (unsigned int n) { threads_ = n; }
  unsigned int
  getNumberOfThreads () const { return threads_; }

  /** \brief Fit a linear normal field instead of a constant one (default true). */
  void
  setFirstOrder (bool first_order) { first_order_ = first_order; }
  bool
  getFirstOrder () const { return first_order_; }

  /** \brief The oriented input points within r of \a position (within
    * \a radius instead when it is given, > 0). */
  void
  gatherNeighbourhood (const Eigen::Vector3f &position, Neighbourhood &neighbours, float radius = 0.f) const;

  /** \brief What gatherNeighbourhood (position, neighbours) returns, taken
    * from \a wider: a neighbourhood gathered with a larger radius around a
    * point near \a position, that holds the ball of radius r around it. */
  void
  selectNeighbourhood (const Neighbourhood &wider, const Eigen::Vector3f &position, Neighbourhood &neighbours) const;

  /** \brief Equation (1) at \a position with reference normal \a reference_normal. */
  SurfaceEstimate
  computeNormal (const Eigen::Vector3f &position, const Eigen::Vector3f &reference_normal) const;

  /** \brief Equation (1) from neighbours already gathered. */
  SurfaceEstimate
  computeNormal (const Neighbourhood &neighbours, const Eigen::Vector3f &position,
                 const Eigen::Vector3f &reference_normal) const
  { return propagateNormal (neighbours, position, reference_normal, kernel_, first_order_); }

  /** \brief Sets the normal of every point of \a candidates from the input
    * cloud, each against its entry of \a reference_normals. Points with no
    * weighted neighbour get NaN normals. False (PCL_ERROR) on bad setup. */
  bool
  propagate (PointCloud &candidates, const std::vector<Eigen::Vector3f> &reference_normals);

  const BilateralKernel &
  kernel () const { return kernel_; }

  /** \brief True when the parameters can work; prints why not otherwise. */
  bool
  checkParameters (const char *caller) const;

private:
  PointCloudConstPtr input_;
  SearchPtr search_;
  float radius_ = 0.f;
  BilateralKernel kernel_;
  bool first_order_ = true;
  unsigned int threads_ = 0;
};

}  // namespace pcl_holefill::detail

#ifdef PCL_NO_PRECOMPILE
#include <pcl_holefill/detail/normal_propagation.hpp>
#endif
