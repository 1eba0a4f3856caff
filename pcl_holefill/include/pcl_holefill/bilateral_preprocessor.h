/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/filters/filter.h>
#include <pcl/search/search.h>

namespace pcl_holefill
{
/** \brief Section 3.2 of the paper: bilateral filtering of an oriented point
  * cloud, normals first (f1), then positions along the filtered normals (f2),
  * as bilateral mesh denoising transfers to points. (PCL's BilateralFilter
  * smooths the intensity field only.)
  *
  *  f1: n_i <- normalise( sum_j g1(|p_j - p_i|) g2(|n_j - n_i|) n_j )
  *  f2: p_i <- p_i + n_i * sum_j g1 g2 ((p_j - p_i) . n_i) / sum_j g1 g2
  *
  * over the neighbours j within the radius (3 sigma_d), g1 a Gaussian of std
  * sigma_d and g2 one of std sigma_n. The small sigma_n keeps sharp edges:
  * the other face's normals carry no weight. Points without a usable normal
  * are passed through unchanged. Output: the indexed points, filtered.
  *
  * \code
  * pcl_holefill::BilateralPreprocessor<pcl::PointNormal> denoise;
  * denoise.setInputCloud (cloud);
  * denoise.setSigmaN (0.1f);           // keeps sharp edges
  * pcl::PointCloud<pcl::PointNormal> smoothed;
  * denoise.filter (smoothed);
  * \endcode
  *
  * \note Stage 1 (sec. 3.2) of "Shape controllable geometry completion for
  * point cloud models"; see HoleFilling for the citation.
  */
template <typename PointT>
class BilateralPreprocessor : public pcl::Filter<PointT>
{
public:
  using Ptr = pcl::shared_ptr<BilateralPreprocessor<PointT>>;
  using ConstPtr = pcl::shared_ptr<const BilateralPreprocessor<PointT>>;
  using PointCloud = pcl::PointCloud<PointT>;
  using SearchPtr = typename pcl::search::Search<PointT>::Ptr;

  BilateralPreprocessor () { filter_name_ = "BilateralPreprocessor"; }

  /** \brief Std of the spatial weight (cloud units); 0 (default) = 2 x mean spacing. */
  void setSigmaD (float s) { sigma_d_ = s; }
  float getSigmaD () const { return sigma_d_; }

  /** \brief Std of the normal weight over |n_j - n_i| (no unit, > 0, default 0.3). */
  void setSigmaN (float s) { sigma_n_ = s; }
  float getSigmaN () const { return sigma_n_; }

  /** \brief Rounds of f1 then f2 (1..100, default 1). */
  void setIterations (int n) { iterations_ = n; }
  int getIterations () const { return iterations_; }

  void setSearchMethod (const SearchPtr &search) { search_ = search; }

  /** \brief Threads for the per-point filtering; 0 (default) = all cores. */
  void setNumberOfThreads (unsigned int n) { threads_ = n; }
  unsigned int getNumberOfThreads () const { return threads_; }
  SearchPtr getSearchMethod () const { return search_; }

protected:
  using pcl::Filter<PointT>::filter_name_;
  using pcl::Filter<PointT>::getClassName;
  using pcl::Filter<PointT>::input_;
  using pcl::Filter<PointT>::indices_;

  void
  applyFilter (PointCloud &output) override;

private:
  float sigma_d_ = 0.f;
  float sigma_n_ = 0.3f;
  int iterations_ = 1;
  SearchPtr search_;
  unsigned int threads_ = 0;
};

}  // namespace pcl_holefill

#ifdef PCL_NO_PRECOMPILE
#include <pcl_holefill/impl/bilateral_preprocessor.hpp>
#endif
