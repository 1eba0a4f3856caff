/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include "normal_estimation.h"

#include <pcl_holefill/normal_orientation.h>

#include <pcl/common/centroid.h>
#include <pcl/common/io.h>
#include <pcl/features/normal_3d_omp.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
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
// Creases, borders, curvature and a thin part's far sheet only raise a
// neighbourhood's reading. Whether a cloud is noisy at all is read off its
// flattest quarter: on a CAD mesh's vertices (dense along curved strips and
// feature lines) most neighbourhoods of 64 reach a crease, and the median
// read fandisk's noise-free vertices as 0.73 pitch of noise (k = 46: PCA
// blended the two sides of its blade and turned 7 % of the normals more
// than 29 degrees off); the quarter reads 0.25. How many neighbours a noisy
// cloud needs stays read at the median, which kNormalNeighboursPerNoise was
// set on (the quarter's lower count left a thin bowl at 0.3 % noise with
// 1.5 times the max error). On pure noise the quarter reads
// kQuarterOverMedian of the median (random squares at 0.25-1.5 pitches of
// noise: 0.922-0.928); it is divided by that.
constexpr float kFlattestShare = 0.25f;
constexpr float kQuarterOverMedian = 0.925f;
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

NoiseReading
readNoise (const pcl::search::Search<pcl::PointXYZ> &search, int k, std::size_t samples)
{
  // On a noisy flat piece the smallest eigenvalue of the k neighbours'
  // scatter (per point) is the noise's variance, and the two others add up
  // to k pitch^2 / (2 pi) (k points fill a disc of k pitch^2 / pi): noise^2 /
  // pitch^2 = lambda_0 / (lambda_1 + lambda_2) k / (2 pi). A surface curved
  // at radius R reads as ~0.05 k pitch^2 / R of noise (0.07 pitch for k = 64
  // on a sphere 40 pitches in radius).
  const auto &cloud = *search.getInputCloud ();
  std::vector<float> ratios;
  const std::size_t stride = std::max<std::size_t> (1, cloud.size () / std::max<std::size_t> (samples, 1));
  pcl::Indices found;
  std::vector<float> sqr_distances;
  for (std::size_t i = 0; i < cloud.size (); i += stride)
  {
    if (!pcl::isFinite (cloud[i]) || search.nearestKSearch (cloud[i], k, found, sqr_distances) < k)
      continue;
    Eigen::Matrix3f scatter;
    Eigen::Vector4f centroid;
    if (pcl::computeMeanAndCovarianceMatrix (cloud, found, scatter, centroid) == 0)
      continue;
    const Eigen::Vector3f lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> (scatter).eigenvalues ();
    if (lambda (1) + lambda (2) > 0.f)
      ratios.push_back (std::max (lambda (0), 0.f) / (lambda (1) + lambda (2)));
  }
  NoiseReading noise;
  if (ratios.empty ())
    return noise;
  const auto inPitches = [k] (float ratio) {
    return std::sqrt (ratio * static_cast<float> (k) / (2.f * static_cast<float> (M_PI)));
  };
  const auto at = [&ratios] (float share) {
    return ratios.begin () + static_cast<std::ptrdiff_t> (share * static_cast<float> (ratios.size ()));
  };
  std::nth_element (ratios.begin (), at (0.5f), ratios.end ());
  noise.median = inPitches (*at (0.5f));
  std::nth_element (ratios.begin (), at (kFlattestShare), at (0.5f));
  noise.flattest = inPitches (*at (kFlattestShare)) / kQuarterOverMedian;
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
  const float noisy_from = static_cast<float> (kMinNoisyNeighbours) / kNormalNeighboursPerNoise;
  return noise.flattest < noisy_from ? kNormalNeighbours : normalNeighboursForNoise (noise.median);
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
