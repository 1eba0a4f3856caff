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

/** The points whose surface variation (lambda_0 / sum) is well above the
  * cloud's median (kSheetVariationOverMedian, kMinSheetVariation): where the
  * PCA neighbourhood reached another sheet or round a crease. */
std::vector<int>
highVariationPoints (const pcl::PointCloud<pcl::PointNormal> &cloud, const std::vector<float> &variation)
{
  const float limit = std::max (kMinSheetVariation, kSheetVariationOverMedian * medianOf (variation));
  std::vector<int> suspects;
  for (std::size_t i = 0; i < cloud.size (); ++i)
    if (variation[i] > limit && cloud[i].getNormalVector3fMap ().allFinite ())
      suspects.push_back (static_cast<int> (i));
  return suspects;
}
}  // namespace

std::size_t
refitAcrossSheets (pcl::PointCloud<pcl::PointNormal> &cloud, const pcl::PointCloud<pcl::PointXYZ> &xyz,
                   const pcl::search::Search<pcl::PointXYZ> &search, const std::vector<float> &variation, int k,
                   unsigned int threads, const std::vector<char> &skip)
{
  std::vector<int> suspects = highVariationPoints (cloud, variation);
  const auto skipped = [&skip] (int i) { return !skip.empty () && skip[i]; };
  suspects.erase (std::remove_if (suspects.begin (), suspects.end (), skipped), suspects.end ());
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
// A PCA normal whose neighbours reach round a crease (two faces of a part
// meeting at an edge) is the normal of neither face, and near an acute
// edge it is the other face's: on a star-shaped prism (edges of 44
// degrees), uniformly random samples, PCL's k = 16 gave the points of one
// face within a pitch or two of the edge the normal of the face across it,
// the orientation walk carried that sign into the whole face, and 3,819 of
// 19,367 normals came out inside-out (six faces flipped; a false hole 0.6
// across, a cut hole missed). The plane of the point's own face is the one
// through the point that most neighbours lie on: among the planes through
// the point and two of its nearest kCreasePlaneNeighbours, the one with the
// most neighbours within the tolerance is refitted on those, if it holds at
// least kCreaseGain x k neighbours more than the PCA plane through the point
// (a smooth surface's PCA plane holds about all of them, and keeps its
// normal), and the edge is acute (kMaxCreaseAngle).
constexpr int kCreasePlaneNeighbours = 12;
constexpr float kCreaseGain = 0.15f;
// Planes from two neighbours at an angle under asin (this) of each other
// (nearly collinear with the point) are not tried: their normal is noise.
constexpr float kCreaseMinSine = 0.25f;
// The tolerance: this share of the local pitch (a sphere 20 pitches in
// radius rises 0.2 pitch over 3 pitches), or this many times the noise
// that the cloud's 16 nearest neighbours read (under 0.25 pitch: the refit
// is for clean clouds).
constexpr float kCreaseTolerancePitch = 0.2f;
constexpr float kCreaseToleranceNoise = 2.5f;
// The refitted neighbours must spread over a patch: the second variance of
// their scatter at least this share of the first (a half disc: 0.4 and up).
constexpr float kCreaseMinSpread = 0.2f;
// Only acute edges (faces meeting at under 80 degrees inside) are refitted:
// there PCA gives the other face's normal, and the orientation walk carried
// it into whole faces. At right and obtuse edges PCA's blended normal is
// what the fill's rim tests were measured with (refitted there too, a cube
// corner's hole from estimated normals was 92.6 % covered instead of 98 %,
// and an open box's missing underside was no longer seen as an opening).
constexpr float kMaxCreaseAngle = 80.f * static_cast<float> (M_PI) / 180.f;

/** Neighbours of offsets \a v within \a tolerance of the plane through the origin of unit normal \a n. */
int
countWithin (const std::vector<Eigen::Vector3f> &v, const Eigen::Vector3f &n, float tolerance)
{
  int count = 0;
  for (const auto &x : v)
    count += std::abs (x.dot (n)) <= tolerance;
  return count;
}

/** Of the planes through the origin and two of the first
  * kCreasePlaneNeighbours + 1 offsets \a v (nearest first), the normal of
  * the one the most offsets lie on within \a tolerance (zero if none is
  * tried), and that count. */
Eigen::Vector3f
bestPlaneThroughPoint (const std::vector<Eigen::Vector3f> &v, float tolerance, int &best_count)
{
  best_count = 0;
  Eigen::Vector3f best = Eigen::Vector3f::Zero ();
  const int m = std::min (static_cast<int> (v.size ()), kCreasePlaneNeighbours + 1);
  for (int a = 0; a < m; ++a)
    for (int b = a + 1; b < m; ++b)
    {
      const Eigen::Vector3f n = v[a].cross (v[b]);
      const float norm = n.norm ();
      if (!(norm > kCreaseMinSine * v[a].norm () * v[b].norm ()))
        continue;
      const int count = countWithin (v, n / norm, tolerance);
      if (count > best_count)
      {
        best_count = count;
        best = n / norm;
      }
    }
  return best;
}

/** Do the points \a indices lie on one plane, within \a tolerance (root mean square)? */
bool
onOnePlane (const pcl::PointCloud<pcl::PointXYZ> &xyz, const pcl::Indices &indices, float tolerance)
{
  Eigen::Matrix3f scatter;
  Eigen::Vector4f centroid;
  return pcl::computeMeanAndCovarianceMatrix (xyz, indices, scatter, centroid) > 0 &&
         Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> (scatter, Eigen::EigenvaluesOnly).eigenvalues () (0) <=
             tolerance * tolerance;
}

/** The PCA normal of the points \a indices into \a normal, if they spread
  * over a patch (kCreaseMinSpread): a strip, such as a cone's points along
  * one generator line, has no normal across it. */
bool
patchNormal (const pcl::PointCloud<pcl::PointXYZ> &xyz, const pcl::Indices &indices, Eigen::Vector3f &normal)
{
  Eigen::Matrix3f scatter;
  Eigen::Vector4f centroid;
  if (indices.size () < 3 || pcl::computeMeanAndCovarianceMatrix (xyz, indices, scatter, centroid) == 0)
    return false;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> solver (scatter);
  if (!(solver.eigenvalues () (1) >= kCreaseMinSpread * solver.eigenvalues () (2)))
    return false;
  normal = solver.eigenvectors ().col (0);
  return true;
}

/** Do the faces of points \a a (plane normal \a n) and \a b (normal \a m)
  * meet at an edge under kMaxCreaseAngle inside? Seen along the edge, the
  * directions from it to each face's centroid. */
bool
acuteEdge (const pcl::PointCloud<pcl::PointXYZ> &xyz, const pcl::Indices &a, const Eigen::Vector3f &n,
           const pcl::Indices &b, const Eigen::Vector3f &m)
{
  const Eigen::Vector3f along = n.cross (m);
  if (!(along.norm () > kCreaseMinSine))
    return false;  // parallel faces: a sheet, not an edge
  Eigen::Vector4f centroid_a, centroid_b;
  pcl::compute3DCentroid (xyz, a, centroid_a);
  pcl::compute3DCentroid (xyz, b, centroid_b);
  const Eigen::Vector3f ca = centroid_a.head<3> (), cb = centroid_b.head<3> ();
  Eigen::Matrix3f planes;
  planes << n.transpose (), m.transpose (), along.normalized ().transpose ();
  const Eigen::Vector3f on_edge = planes.colPivHouseholderQr ().solve (
      Eigen::Vector3f (n.dot (ca), m.dot (cb), along.normalized ().dot (0.5f * (ca + cb))));
  const auto across = [&along] (const Eigen::Vector3f &d) {
    const Eigen::Vector3f u = along.normalized ();
    return Eigen::Vector3f (d - d.dot (u) * u).normalized ();
  };
  return across (ca - on_edge).dot (across (cb - on_edge)) > std::cos (kMaxCreaseAngle);
}

/** The normal of point \a i's own face (see kCreaseGain) from its neighbours
  * \a found (nearest first, the point among them), or \a pca when no plane
  * beats the PCA one by enough or the neighbours off it lie on no plane
  * (off a plane through a strongly curved surface, such as the thin rim of
  * an ellipsoid or a cone's apex, they do not; at a crease they lie on the
  * other face). */
Eigen::Vector3f
ownFaceNormal (const pcl::PointCloud<pcl::PointXYZ> &xyz, std::size_t i, const pcl::Indices &found,
               const Eigen::Vector3f &pca, float noise_in_pitches)
{
  const Eigen::Vector3f p = xyz[i].getVector3fMap ();
  std::vector<Eigen::Vector3f> v;
  float reach = 0.f;
  for (const auto j : found)
  {
    v.push_back (xyz[j].getVector3fMap () - p);
    reach = std::max (reach, v.back ().squaredNorm ());
  }
  const int k = static_cast<int> (v.size ());
  // k neighbours fill a disc of about k pitch^2 / pi.
  const float pitch = std::sqrt (reach * static_cast<float> (M_PI) / static_cast<float> (std::max (k, 1)));
  const float tolerance = pitch * std::max (kCreaseTolerancePitch, kCreaseToleranceNoise * noise_in_pitches);
  int best_count = 0;
  const Eigen::Vector3f best = bestPlaneThroughPoint (v, tolerance, best_count);
  if (best_count < countWithin (v, pca, tolerance) + kCreaseGain * static_cast<float> (k))
    return pca;
  pcl::Indices own_face, others;
  for (int j = 0; j < k; ++j)
    (std::abs (v[j].dot (best)) <= tolerance ? own_face : others).push_back (found[j]);
  Eigen::Vector3f n, m;
  if (others.size () < 3 || !onOnePlane (xyz, others, tolerance) || !patchNormal (xyz, own_face, n) ||
      !patchNormal (xyz, others, m) || !acuteEdge (xyz, own_face, n, others, m))
    return pca;
  return n.dot (pca) < 0.f ? Eigen::Vector3f (-n) : n;
}
}  // namespace

std::vector<char>
refitAtCreases (pcl::PointCloud<pcl::PointNormal> &cloud, const pcl::PointCloud<pcl::PointXYZ> &xyz,
                const pcl::search::Search<pcl::PointXYZ> &search, const std::vector<float> &variation, int k,
                float noise_in_pitches, unsigned int threads)
{
  const std::vector<int> suspects = highVariationPoints (cloud, variation);
  std::vector<char> refitted (cloud.size (), 0);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 64)
  for (std::ptrdiff_t s = 0; s < static_cast<std::ptrdiff_t> (suspects.size ()); ++s)
  {
    const int i = suspects[s];
    pcl::Indices found;
    std::vector<float> sqr_distances;
    if (search.nearestKSearch (xyz[i], k, found, sqr_distances) < 3)
      continue;
    // PCL's kd-tree returns them sorted, nearest first (bestPlaneThroughPoint).
    const Eigen::Vector3f pca = cloud[i].getNormalVector3fMap ();
    const Eigen::Vector3f own = ownFaceNormal (xyz, i, found, pca, noise_in_pitches);
    if (own != pca)
    {
      cloud[i].getNormalVector3fMap () = own;
      refitted[i] = 1;
    }
  }
  return refitted;
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
  const NoiseReading noise = readNoise (*tree, kNoiseNeighbours, kNoiseSamples);
  const int k = normalNeighboursForNoise (noise);
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
  // On a noisy cloud PCA's k grows to average the noise out, and a plane
  // through a point and two of its neighbours is mostly noise: there it
  // chose wrong sides (a star prism at 0.3 % noise: 3,962 of 20,000 normals
  // against their exact ones after orientation, 413 with PCA's).
  const std::vector<char> own_face = noise.close < kCleanCloseNoise
                                         ? refitAtCreases (cloud, *xyz, *tree, variation, k, noise.close, threads)
                                         : std::vector<char> (cloud.size (), 0);
  pcl_holefill::orientNormalsConsistently (cloud);
  refitAcrossSheets (cloud, *xyz, *tree, variation, k, threads, own_face);
  return k;
}

}  // namespace pcl_holefill_tool
