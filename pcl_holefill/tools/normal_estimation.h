/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <vector>

namespace pcl_holefill_tool
{
/** \brief Normals for a cloud that has none, as the command and the Python
  * module give them: PCL NormalEstimationOMP over k = 16 nearest neighbours,
  * or more on a noisy cloud (normalNeighboursForNoise of the noise that the
  * first pass measures), on a clean cloud refitted at creases
  * (refitAtCreases), then consistently oriented
  * (pcl_holefill::orientNormalsConsistently), then refitted where they
  * reached another sheet (refitAcrossSheets, but for those refitted at
  * creases). Non-finite points get NaN normals. Returns the k used. */
int
estimateOrientedNormals (pcl::PointCloud<pcl::PointNormal> &cloud, unsigned int threads);

/** \brief Refits the oriented normals of \a cloud whose PCA over \a k
  * neighbours may have reached another sheet of a thin part: those of a
  * surface variation (\a variation, lambda_0 / sum, per point) well above
  * the cloud's median, on their neighbours (in \a xyz, through \a search)
  * whose normals face their own way, but for the points \a skip marks (1).
  * Returns how many were refitted. */
std::size_t
refitAcrossSheets (pcl::PointCloud<pcl::PointNormal> &cloud, const pcl::PointCloud<pcl::PointXYZ> &xyz,
                   const pcl::search::Search<pcl::PointXYZ> &search, const std::vector<float> &variation, int k,
                   unsigned int threads, const std::vector<char> &skip = {});

/** \brief Refits the normals of \a cloud whose PCA over \a k neighbours
  * reached round a crease (a surface variation well above the median, as
  * for refitAcrossSheets) on the neighbours of the point's own face: the
  * plane through the point that the most neighbours lie on (within a
  * tolerance of a share of the pitch, or of \a noise_in_pitches), if it
  * holds clearly more of them than the PCA plane. Returns which were
  * refitted (1). */
std::vector<char>
refitAtCreases (pcl::PointCloud<pcl::PointNormal> &cloud, const pcl::PointCloud<pcl::PointXYZ> &xyz,
                const pcl::search::Search<pcl::PointXYZ> &search, const std::vector<float> &variation, int k,
                float noise_in_pitches, unsigned int threads);

/** The noise of a cloud across its surface, in sampling pitches (sqrt of
  * the area per point), as PCA shows it at the median neighbourhood of
  * points spread over the cloud: over their k nearest neighbours (median),
  * and over their 16 nearest (close; scaled to read noise of 0.25-0.5 pitch
  * right; it saturates above, and a crease a few pitches away does not
  * reach it). */
struct NoiseReading
{
  float median = 0.f;
  float close = 0.f;
};

/** The NoiseReading of the cloud that \a search holds, over \a k
  * neighbours of about \a samples points; zeros when no point has k. */
NoiseReading
readNoise (const pcl::search::Search<pcl::PointXYZ> &search, int k, std::size_t samples);

/** The neighbours of PCA normals for a cloud of this noise (in pitches):
  * PCL's usual 16 up to 0.375 pitch, then 64 per pitch, at most 128. */
int
normalNeighboursForNoise (float noise_in_pitches);

/** The neighbours for a cloud read as \a noise: 16 when it reads clean
  * over 16 (under 0.25 pitch), else normalNeighboursForNoise of the
  * median. */
int
normalNeighboursForNoise (const NoiseReading &noise);

}  // namespace pcl_holefill_tool
