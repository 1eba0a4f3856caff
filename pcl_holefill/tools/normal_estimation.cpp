/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
// PCL's NormalEstimationOMP compiled here from its templates rather than
// taken from libpcl_features: that library and the ones it needs (filters,
// sample_consensus) cost every start of the command 0.055 s in the dynamic
// loader (0.061 -> 0.006 s for an empty program), a tenth of a fill of
// 25,000 points. The code and so the normals are PCL's.
#define PCL_NO_PRECOMPILE
#include "normal_estimation.h"

#include <pcl_holefill/normal_orientation.h>

#include <pcl/common/centroid.h>
#include <pcl/common/io.h>
#include <pcl/features/normal_3d_omp.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace pcl_holefill_tool
{
namespace
{
// Neighbours of the PCA normal: what PCL's tools and most users take ...
constexpr int kNormalNeighbours = 16;
// ... and, on noisy clouds, this many per unit of noise (noise / sampling
// pitch), up to kMaxNormalNeighbours. PCA's normal errs by about noise /
// (reach sqrt(k)), so ~noise / (pitch k): at a noise of 0.9 pitch (a random
// sphere of 100,000 points at 0.3 % of its diagonal) PCL's 16 scatter by 25
// degrees, the orientation walk left 1.2 % of them flipped and no hole was
// found; at 1.5 pitches (0.5 %) 16 and 32 found none even oriented right,
// 64 did.
constexpr float kNormalNeighboursPerNoise = 64.f;
constexpr int kMaxNormalNeighbours = 128;
// Under this many, PCL's 16 stay (under 0.375 pitch of noise).
constexpr int kMinNoisyNeighbours = 24;
// The noise is measured over this many neighbours of this many points
// spread over the cloud. Over 16 the measure saturates as the noise nears
// the neighbourhood's radius (1 pitch read 0.63, 1.5 read 0.70); over 64
// 0.91-0.92 and 1.23-1.24 (unit squares, jittered and random samples).
constexpr int kNoiseNeighbours = 64;
constexpr std::size_t kNoiseSamples = 2000;
// A cloud whose noise, read over its points' nearest kNormalNeighbours,
// is under kCleanCloseNoise pitch is clean, whatever the reading over 64
// says: creases raise a reading wherever a neighbourhood reaches one, and
// on a CAD mesh's vertices (dense along curved strips and feature lines)
// most neighbourhoods of 64 do. Their median read fandisk's noise-free
// vertices as 0.73 pitch of noise (k = 46: PCA blended the two sides of its
// blade and turned 7 % of the normals more than 29 degrees off); over 16 it
// reads 0.05. Over 16, pure noise reads kCloseReadsOfNoise of itself at
// 0.25-0.5 pitch (random squares; the reading is divided by that) and
// saturates above. Not 0.375, the count's own threshold: a thin bowl at
// 0.37 pitch of noise read 0.36 over 16, and at k = 16 instead of the 41
// its reading over 64 asked for had twice the max error.
constexpr float kCleanCloseNoise = 0.25f;
constexpr float kCloseReadsOfNoise = 0.907f;
// A PCA normal whose neighbours reach another sheet of a thin part (the far
// wall of a shell a few pitches thick, where a hole left the neighbourhood
// one-sided) is tilted towards it: 90 % of the rim points of holes in a
// bowl 5 pitches thick (Poisson-disk, 0.3 % noise, k = 42) within 21
// degrees, 1 % past 63. Such a point shows as a surface variation
// (lambda_0 / sum) over kSheetVariationOverMedian times the cloud's median,
// and over kMinSheetVariation (a sheet 4 pitches under a hole's rim reads
// 0.05 and more; a sphere 40 pitches in radius, 1e-4), and it is refitted
// on the neighbours whose oriented normals face its own way (a dot product
// > 0: the far wall's face away), kSheetRefits times.
constexpr float kSheetVariationOverMedian = 3.f;
constexpr float kMinSheetVariation = 0.002f;
constexpr int kSheetRefits = 2;

/** The median of the finite \a values (0 when none). */
float
medianOf (std::vector<float> values)
{
  values.erase (std::remove_if (values.begin (), values.end (), [] (float v) { return !std::isfinite (v); }),
                values.end ());
  if (values.empty ())
    return 0.f;
  const auto middle = values.begin () + static_cast<std::ptrdiff_t> (values.size () / 2);
  std::nth_element (values.begin (), middle, values.end ());
  return *middle;
}

/** The normal of the plane through the neighbours \a found of point \a i
  * whose normals face the way of i's (\a normals), turned to i's side; i's
  * own normal when fewer than 3 do. */
Eigen::Vector3f
sameSheetNormal (const pcl::PointCloud<pcl::PointXYZ> &xyz, const std::vector<Eigen::Vector3f> &normals,
                 std::size_t i, const pcl::Indices &found)
{
  pcl::Indices same;
  for (const auto j : found)
    if (normals[j].dot (normals[i]) > 0.f)
      same.push_back (j);
  Eigen::Matrix3f scatter;
  Eigen::Vector4f centroid;
  if (same.size () < 3 || pcl::computeMeanAndCovarianceMatrix (xyz, same, scatter, centroid) == 0)
    return normals[i];
  const Eigen::Vector3f n = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> (scatter).eigenvectors ().col (0);
  return n.dot (normals[i]) < 0.f ? Eigen::Vector3f (-n) : n;
}
}  // namespace

std::size_t
refitAcrossSheets (pcl::PointCloud<pcl::PointNormal> &cloud, const pcl::PointCloud<pcl::PointXYZ> &xyz,
                   const pcl::search::Search<pcl::PointXYZ> &search, const std::vector<float> &variation, int k,
                   unsigned int threads)
{
  const float limit = std::max (kMinSheetVariation, kSheetVariationOverMedian * medianOf (variation));
  std::vector<int> suspects;
  for (std::size_t i = 0; i < cloud.size (); ++i)
    if (variation[i] > limit && cloud[i].getNormalVector3fMap ().allFinite ())
      suspects.push_back (static_cast<int> (i));
  std::vector<Eigen::Vector3f> normals (cloud.size ());
  for (std::size_t i = 0; i < cloud.size (); ++i)
    normals[i] = cloud[i].getNormalVector3fMap ();
  std::vector<pcl::Indices> neighbours (suspects.size ());
  for (int round = 0; round < kSheetRefits; ++round)
  {
    // Jacobi-style: every refit of a round reads the normals of the one
    // before, so the result is the same for any number of threads.
    std::vector<Eigen::Vector3f> refitted (suspects.size ());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 64)
    for (std::ptrdiff_t s = 0; s < static_cast<std::ptrdiff_t> (suspects.size ()); ++s)
    {
      const int i = suspects[s];
      if (round == 0)
      {
        std::vector<float> sqr_distances;
        search.nearestKSearch (xyz[i], k, neighbours[s], sqr_distances);
      }
      refitted[s] = sameSheetNormal (xyz, normals, i, neighbours[s]);
    }
    for (std::size_t s = 0; s < suspects.size (); ++s)
      normals[suspects[s]] = refitted[s];
  }
  for (const int i : suspects)
    cloud[i].getNormalVector3fMap () = normals[i];
  return suspects.size ();
}

namespace
{
/** lambda_0 / (lambda_1 + lambda_2) of the scatter of \a found in \a cloud (NaN when degenerate). */
float
flatnessRatio (const pcl::PointCloud<pcl::PointXYZ> &cloud, const pcl::Indices &found)
{
  Eigen::Matrix3f scatter;
  Eigen::Vector4f centroid;
  if (pcl::computeMeanAndCovarianceMatrix (cloud, found, scatter, centroid) == 0)
    return std::numeric_limits<float>::quiet_NaN ();
  const Eigen::Vector3f lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> (scatter).eigenvalues ();
  return lambda (1) + lambda (2) > 0.f ? std::max (lambda (0), 0.f) / (lambda (1) + lambda (2))
                                       : std::numeric_limits<float>::quiet_NaN ();
}

/** The median of \a ratios as a noise over \a k neighbours, in pitches (0 when none). */
float
medianInPitches (std::vector<float> ratios, int k)
{
  // On a noisy flat piece the smallest eigenvalue of the k neighbours'
  // scatter (per point) is the noise's variance, and the two others add up
  // to k pitch^2 / (2 pi) (k points fill a disc of k pitch^2 / pi): noise^2 /
  // pitch^2 = lambda_0 / (lambda_1 + lambda_2) k / (2 pi). A surface curved
  // at radius R reads as ~0.05 k pitch^2 / R of noise (0.07 pitch for k = 64
  // on a sphere 40 pitches in radius).
  return std::sqrt (medianOf (std::move (ratios)) * static_cast<float> (k) / (2.f * static_cast<float> (M_PI)));
}
}  // namespace

NoiseReading
readNoise (const pcl::search::Search<pcl::PointXYZ> &search, int k, std::size_t samples)
{
  const auto &cloud = *search.getInputCloud ();
  const int close_k = std::min (k, kNormalNeighbours);
  std::vector<float> ratios, close_ratios;
  const std::size_t stride = std::max<std::size_t> (1, cloud.size () / std::max<std::size_t> (samples, 1));
  pcl::Indices found;
  std::vector<float> sqr_distances;
  for (std::size_t i = 0; i < cloud.size (); i += stride)
  {
    if (!pcl::isFinite (cloud[i]) || search.nearestKSearch (cloud[i], k, found, sqr_distances) < k)
      continue;
    ratios.push_back (flatnessRatio (cloud, found));
    // The nearest close_k of them (the search need not sort its results).
    std::vector<std::pair<float, int>> by_distance;
    for (std::size_t j = 0; j < found.size (); ++j)
      by_distance.emplace_back (sqr_distances[j], found[j]);
    std::nth_element (by_distance.begin (), by_distance.begin () + close_k - 1, by_distance.end ());
    pcl::Indices nearest;
    for (int j = 0; j < close_k; ++j)
      nearest.push_back (by_distance[j].second);
    close_ratios.push_back (flatnessRatio (cloud, nearest));
  }
  NoiseReading noise;
  noise.median = medianInPitches (std::move (ratios), k);
  noise.close = medianInPitches (std::move (close_ratios), close_k) / kCloseReadsOfNoise;
  return noise;
}

int
normalNeighboursForNoise (float noise_in_pitches)
{
  const float wanted = std::ceil (kNormalNeighboursPerNoise * noise_in_pitches);
  if (!std::isfinite (wanted) || wanted < static_cast<float> (kMinNoisyNeighbours))
    return kNormalNeighbours;
  return static_cast<int> (std::min (wanted, static_cast<float> (kMaxNormalNeighbours)));
}

int
normalNeighboursForNoise (const NoiseReading &noise)
{
  return noise.close < kCleanCloseNoise ? kNormalNeighbours : normalNeighboursForNoise (noise.median);
}

int
estimateOrientedNormals (pcl::PointCloud<pcl::PointNormal> &cloud, unsigned int threads)
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr xyz (new pcl::PointCloud<pcl::PointXYZ>);
  pcl::copyPointCloud (cloud, *xyz);
  xyz->is_dense = true;
  for (const auto &p : *xyz)
    xyz->is_dense = xyz->is_dense && std::isfinite (p.x) && std::isfinite (p.y) && std::isfinite (p.z);
  // One tree for the noise and the normals (PCL keeps a tree already on its input).
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree (new pcl::search::KdTree<pcl::PointXYZ>);
  tree->setInputCloud (xyz);
  const int k = normalNeighboursForNoise (readNoise (*tree, kNoiseNeighbours, kNoiseSamples));
  pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> estimation (threads);
  estimation.setInputCloud (xyz);
  estimation.setSearchMethod (tree);
  estimation.setKSearch (k);
  pcl::PointCloud<pcl::Normal> normals;
  estimation.compute (normals);
  std::vector<float> variation (normals.size ());
  for (std::size_t i = 0; i < normals.size (); ++i)
  {
    cloud[i].getNormalVector3fMap () = normals[i].getNormalVector3fMap ();
    variation[i] = normals[i].curvature;
  }
  pcl_holefill::orientNormalsConsistently (cloud);
  refitAcrossSheets (cloud, *xyz, *tree, variation, k, threads);
  return k;
}

}  // namespace pcl_holefill_tool
