/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/bilateral_preprocessor.h>
#include <pcl_holefill/detail/local_surface.h>
#include <pcl_holefill/detail/point_validity.h>
#include <pcl_holefill/detail/thread_count.h>
#include <pcl_holefill/voxel_hash_search.h>

#include <pcl/common/io.h>
#include <pcl/console/print.h>

#include <cmath>

namespace pcl_holefill
{
namespace detail
{
/** 2 x the mean nearest-neighbour distance over a sample of \a cloud (at most
  * ~2,000 points): a few rings of neighbours. 0 when none is found. */
template <typename PointT> float
automaticSigmaD (const pcl::PointCloud<PointT> &cloud, pcl::search::Search<PointT> &search)
{
  constexpr std::size_t kSampledPoints = 2000;
  double sum = 0.0;
  std::size_t count = 0;
  pcl::Indices found;
  std::vector<float> d2;
  for (std::size_t i = 0; i < cloud.size (); i += 1 + cloud.size () / kSampledPoints)
    if (detail::isOrientedPoint (cloud[i]) && search.nearestKSearch (cloud[i], 2, found, d2) == 2)
    {
      sum += std::sqrt (d2[1]);
      ++count;
    }
  return count ? static_cast<float> (2.0 * sum / count) : 0.f;
}

/** f1: each oriented point's normal in \a next becomes the g1 g2-weighted
  * mean of its neighbours' normals in \a current (within \a radius). Each
  * point reads \a current and writes its own entry: parallel and deterministic. */
template <typename PointT> void
filterNormals (const pcl::PointCloud<PointT> &current, pcl::search::Search<PointT> &search,
               const detail::BilateralKernel &kernel, double radius, int threads, pcl::PointCloud<PointT> &next)
{
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1024)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (current.size ()); ++i)
  {
    const PointT &p = current[i];
    if (!detail::isOrientedPoint (p))
      continue;
    const Eigen::Vector3f n = p.getNormalVector3fMap ().normalized ();
    pcl::Indices found;
    std::vector<float> d2;
    search.radiusSearch (p, radius, found, d2);
    Eigen::Vector3f sum = Eigen::Vector3f::Zero ();
    for (std::size_t k = 0; k < found.size (); ++k)
    {
      const PointT &q = current[found[k]];
      if (!detail::isOrientedPoint (q))
        continue;
      const Eigen::Vector3f nq = q.getNormalVector3fMap ().normalized ();
      sum += kernel.spatial (d2[k]) * kernel.normal ((nq - n).squaredNorm ()) * nq;
    }
    if (sum.norm () > 1e-9f)
      next[i].getNormalVector3fMap () = sum.normalized ();
  }
}

/** f2: each oriented point of \a next moves along its filtered normal by the
  * g1 g2-weighted mean offset of its neighbours in \a current (g2 on the
  * filtered normals). */
template <typename PointT> void
filterPositions (const pcl::PointCloud<PointT> &current, pcl::search::Search<PointT> &search,
                 const detail::BilateralKernel &kernel, double radius, int threads, pcl::PointCloud<PointT> &next)
{
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1024)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (current.size ()); ++i)
  {
    const PointT &p = next[i];
    if (!detail::isOrientedPoint (p))
      continue;
    const Eigen::Vector3f n = p.getNormalVector3fMap ();
    pcl::Indices found;
    std::vector<float> d2;
    search.radiusSearch (current[i], radius, found, d2);
    float total = 0.f, offset = 0.f;
    for (std::size_t k = 0; k < found.size (); ++k)
    {
      const PointT &q = next[found[k]];
      if (!detail::isOrientedPoint (q))
        continue;
      const float w = kernel.spatial (d2[k]) * kernel.normal ((q.getNormalVector3fMap () - n).squaredNorm ());
      offset += w * (current[found[k]].getVector3fMap () - current[i].getVector3fMap ()).dot (n);
      total += w;
    }
    if (total > 1e-9f)
      next[i].getVector3fMap () = current[i].getVector3fMap () + n * (offset / total);
  }
}
}  // namespace detail

template <typename PointT> void
BilateralPreprocessor<PointT>::applyFilter (PointCloud &output)
{
  if (!(sigma_d_ >= 0.f && std::isfinite (sigma_d_)) || !(sigma_n_ > 0.f && std::isfinite (sigma_n_)) ||
      iterations_ < 1 || iterations_ > 100)
  {
    PCL_ERROR ("[pcl_holefill::%s::applyFilter] Invalid parameters: sigma_d = %g (>= 0), sigma_n = %g (> 0), "
               "iterations = %d (1..100).\n", getClassName ().c_str (), sigma_d_, sigma_n_, iterations_);
    output.clear ();
    return;
  }
  typename PointCloud::Ptr current (new PointCloud);
  pcl::copyPointCloud (*input_, *indices_, *current);
  SearchPtr search = search_;
  if (!search)
    search.reset (new VoxelHashSearch<PointT> (16));
  const int threads = detail::resolveThreadCount (threads_);
  for (int round = 0; round < iterations_; ++round)
  {
    search->setInputCloud (current);
    const float sigma_d = sigma_d_ > 0.f ? sigma_d_ : detail::automaticSigmaD (*current, *search);
    if (!(sigma_d > 0.f))
      break;
    const detail::BilateralKernel kernel{sigma_d, sigma_n_};
    const double radius = 3.0 * sigma_d;
    PointCloud next = *current;
    detail::filterNormals (*current, *search, kernel, radius, threads, next);
    detail::filterPositions (*current, *search, kernel, radius, threads, next);
    *current = next;
  }
  const auto header = output.header;
  output = *current;
  output.header = header;
}

}  // namespace pcl_holefill

#define PCL_INSTANTIATE_BilateralPreprocessor(T) template class pcl_holefill::BilateralPreprocessor<T>;
