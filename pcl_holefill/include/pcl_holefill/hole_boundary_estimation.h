/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/boundary_loop.h>
#include <pcl_holefill/detail/boundary_point_test.h>
#include <pcl_holefill/hole_filling_parameters.h>
#include <pcl_holefill/detail/loop_tracing.h>
#include <pcl_holefill/detail/point_grid.h>
#include <pcl_holefill/detail/sampling_evenness.h>

#include <pcl/pcl_base.h>
#include <pcl/search/search.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pcl_holefill
{
/** \brief Finds every rim of missing surface in an oriented point cloud and
  * returns each as an ordered loop of the cloud's own indices, labelled as a
  * hole or as the outer border of an open surface.
  *
  * Three steps, each bounded by the number of points:
  *  1. a point is on a rim when its k nearest neighbours, seen in its tangent
  *     plane, leave an empty sector wider than the angle threshold (PCL's
  *     BoundaryEstimation test; with the given normals it does not fire along
  *     sharp edges and corners of a solid, see largestAngularGap), and an
  *     empty disc of the minimum hole size touches it inside that sector
  *     (emptyDiscTouches): every sampling leaves small gaps, white noise
  *     (uniform random sampling) gaps of up to 4.9 pitches across on 4
  *     million points; a hole is missing surface wider than those;
  *  2. rim points closer than link_distance_factor pitches (the cloud's
  *     mean pitch, or the pitch around them where the cloud is sparser) are
  *     chained into loops (traceBoundaryLoops), and gaps between consecutive
  *     loop points are closed with the paper's midpoint refinement (sec. 3.3);
  *  3. a loop whose empty sectors face its inside is a hole; one facing
  *     outwards is a border. A loop wider than the maximum hole diameter (if
  *     set) is a border too.
  *
  * The paper's own semi-automatic mode is refineFeaturePoints(): from a few
  * user points in order along a hole, the same midpoint refinement.
  *
  * Points with non-finite coordinates or a missing/zero normal are skipped
  * (with a PCL_WARN). setIndices() restricts the search to a subset; the
  * loops still index the input cloud.
  *
  * \code
  * pcl_holefill::HoleBoundaryEstimation<pcl::PointNormal> estimation;
  * estimation.setInputCloud (cloud);   // oriented: normals required
  * std::vector<pcl_holefill::BoundaryLoop> loops;
  * estimation.compute (loops);
  * for (const auto &loop : loops)
  *   if (loop.is_hole)                 // the others are borders of an open surface
  *     std::cout << loop.indices.size () << " rim points, " << loop.diameter << " across\n";
  * \endcode
  *
  * \note Stage 2 (sec. 3.3) of "Shape controllable geometry completion for
  * point cloud models", made automatic; see HoleFilling for the citation.
  */
template <typename PointT>
class HoleBoundaryEstimation : public pcl::PCLBase<PointT>
{
public:
  using Ptr = pcl::shared_ptr<HoleBoundaryEstimation<PointT>>;
  using ConstPtr = pcl::shared_ptr<const HoleBoundaryEstimation<PointT>>;
  using PointCloud = pcl::PointCloud<PointT>;
  using Search = pcl::search::Search<PointT>;
  using SearchPtr = typename Search::Ptr;

  HoleBoundaryEstimation () = default;

  /** \brief A search to use for the k nearest neighbours (it is given the
    * input cloud). By default a VoxelHashSearch is built. */
  void
  setSearchMethod (const SearchPtr &search) { search_ = search; }
  SearchPtr
  getSearchMethod () const { return search_; }

  /** \brief Neighbours looked at per point: parameters::kKSearch. */
  void
  setKSearch (int k) { k_ = k; }
  int
  getKSearch () const { return k_; }

  /** \brief Widest empty sector a point off the rim may have: parameters::kAngleThreshold. */
  void
  setAngleThreshold (float radians) { angle_threshold_ = radians; }
  float
  getAngleThreshold () const { return angle_threshold_; }

  /** \brief Rim points closer than this many sampling pitches are chained: parameters::kLinkDistanceFactor. */
  void
  setLinkDistanceFactor (float factor) { link_factor_ = factor; }
  float
  getLinkDistanceFactor () const { return link_factor_; }

  /** \brief Loops with fewer points are ignored as noise: parameters::kMinLoopPoints. */
  void
  setMinLoopPoints (int n) { min_loop_points_ = n; }
  int
  getMinLoopPoints () const { return min_loop_points_; }

  /** \brief Loops wider than this are borders, never holes: parameters::kMaxHoleDiameter. */
  void
  setMaxHoleDiameter (float diameter) { max_hole_diameter_ = diameter; }
  float
  getMaxHoleDiameter () const { return max_hole_diameter_; }

  /** \brief Smallest hole reported, as the diameter of the empty disc it
    * must hold, in local sampling pitches (sqrt of the surface area per
    * point, measured from the k nearest neighbours): parameters::kMinHoleSize.
    * 0 (default): chosen from how evenly the cloud is sampled, 6 on
    * uniformly random samples, 4 on even ones (getMinHoleSizeUsed ()); a
    * region sampled more randomly than the whole (a part thinned, one of
    * merged scans) gets its own, larger size (detail::RegionEvenness).
    * Below 5 the gaps of uniformly random sampling are reported as holes. */
  void
  setMinHoleSize (float pitches) { min_hole_pitches_ = pitches; }
  float
  getMinHoleSize () const { return min_hole_pitches_; }

  /** \brief The same in cloud units, when not 0: parameters::kMinHoleDiameter. */
  void
  setMinHoleDiameter (float diameter) { min_hole_diameter_ = diameter; }
  float
  getMinHoleDiameter () const { return min_hole_diameter_; }

  /** \brief Threads for the per-point test; 0 (default) = all cores. */
  void
  setNumberOfThreads (unsigned int threads) { threads_ = threads; }
  unsigned int
  getNumberOfThreads () const { return threads_; }

  /** \brief Finds all loops, holes and borders. Empty (with a message) on bad input. */
  void
  compute (std::vector<BoundaryLoop> &loops);

  /** \brief The paper's semi-automatic boundary (sec. 3.3): \a feature_indices,
    * in order along one rim, are densified by midpoint refinement into
    * \a loop (marked as a hole). Returns false (with a PCL_ERROR) on bad input. */
  bool
  refineFeaturePoints (const pcl::Indices &feature_indices, BoundaryLoop &loop, bool closed = true);

  /** \brief After compute(): per input point, 1 where the rim test fired. */
  const std::vector<char> &
  getBoundaryFlags () const { return flags_; }

  /** \brief After compute() or refineFeaturePoints(): mean nearest-neighbour spacing. */
  float
  getMeanSpacing () const { return mean_spacing_; }

  /** \brief After compute(): mean sampling pitch, sqrt(area per point). */
  float
  getMeanPitch () const { return mean_pitch_; }

  /** \brief After compute(): how evenly the cloud is sampled, the lower
    * quartile of each point's nearest neighbour in its tangent plane over its
    * pitch: about 0.3 for uniformly random samples, 0.4 for scan lines, 0.6
    * for a jittered grid, 0.75-0.85 for Poisson-disk and voxel-grid samples. */
  float
  getSamplingEvenness () const { return sampling_evenness_; }

  /** \brief After compute(): the min hole size applied (pitches): the one
    * set, or the one chosen from getSamplingEvenness () (detail::minHoleSizeForEvenness;
    * the least applied: a region sampled more randomly gets a larger one);
    * not applied when setMinHoleDiameter () gave one in cloud units. */
  float
  getMinHoleSizeUsed () const { return min_hole_size_used_; }

  /** \brief After compute(): points set aside as strays (off the surface,
    * detail::isStrayPoint); the rim test ran again without them beside them. */
  std::size_t
  getStrayCount () const { return stray_count_; }

  /** \brief After compute(): rim candidates whose normal faced the wrong way
    * (nearly all their neighbours' face away): detection turned them over;
    * the cloud keeps its normals. More than none: orient the normals (e.g.
    * orientNormalsConsistently) or check their source. */
  std::size_t
  getTurnedNormalCount () const { return turned_normal_count_; }

protected:
  using pcl::PCLBase<PointT>::input_;
  using pcl::PCLBase<PointT>::indices_;
  using pcl::PCLBase<PointT>::initCompute;
  using pcl::PCLBase<PointT>::deinitCompute;

  /** \brief The name messages print, as pcl::Feature's getClassName (). */
  const std::string &
  getClassName () const { return class_name_; }

  std::string class_name_ = "HoleBoundaryEstimation";

private:
  /** A usable point that the angular-gap test put on a rim. */
  struct RimPoint
  {
    int local;        //!< usable point
    detail::AngularGap gap;   //!< its widest empty sector
    float spacing;    //!< distance to its nearest distinct neighbour
    float second_spacing;  //!< ... and to its second nearest (infinite without one)
    Eigen::Vector3f walk_normal = Eigen::Vector3f::Zero ();  //!< the loop tracing's normal (tracingNormal)
    int nearest_store = 0;       //!< its k nearest: RimCandidates::nearest[nearest_store] ...
    std::size_t nearest_at = 0;  //!< ... from here ...
    int nearest_count = 0;       //!< ... this many, nearest first (on its own side)
    bool on_thin_part = false;   //!< the other side of a thin part is among its k nearest
    float pitch = 0.f;           //!< the sampling pitch around it (its own and its k nearest's, averaged)
    float min_hole_size = 0.f;   //!< the min hole size (pitches) applied around it (minHoleSizeAround)
  };

  /** The rim points of stage 1 and the k nearest of each, in one store per
    * thread that found them: a vector each cost more memory than the ids
    * themselves (a fifth of a million random samples are candidates: 13 MB
    * of ids). */
  struct RimCandidates
  {
    std::vector<RimPoint> points;
    std::vector<std::vector<int>> nearest;
  };

  /** The rim points that one thread of findRimPoints found, and their k
    * nearest. */
  struct ThreadRimPoints
  {
    std::vector<RimPoint> points;
    std::vector<int> nearest;
    std::vector<int> turned_over;  //!< usable points whose normal faces the wrong way (normalTurnedOver)
  };

  /** Validates parameters and input, builds the neighbour search over the
    * usable points. False (after a message) when nothing can be done. */
  bool
  prepare (const char *caller);

  /** Are the parameters in range? (A message says which is not.) */
  bool
  checkParameters (const char *caller) const;

  /** usable_: the points of indices_ with finite coordinates and a normal;
    * false when too few. */
  bool
  selectUsablePoints (const char *caller);

  /** Puts usable_ in spatial (Morton) order, each position once; returns
    * the grid's cell size. */
  float
  orderSpatially (const char *caller);

  /** positions_, normals_ and local_of_ from usable_. */
  void
  copyUsablePoints ();

  /** Stage 1, the angular-gap test on every usable point: the rim points
    * (in usable order) with their k nearest, and every point's spacing and
    * sampling pitch. */
  RimCandidates
  findRimPoints (std::vector<float> &pitch_of);

  /** Stage 1 again, without the strays (markStrays), on the points that
    * held one among their k nearest (pointsBesideStrays; \a test_point:
    * findRimPoints' test); their first verdicts in \a found go. */
  template <typename TestPoint> void
  retestBesideStrays (const std::vector<float> &spacing_of, const std::vector<float> &pitch_of,
                      const std::vector<float> &reach_of, std::vector<ThreadRimPoints> &found,
                      const TestPoint &test_point);

  /** True when more than three in four of the \a count neighbours \a ids
    * of usable point \a local face away from it (detail::kOtherSideCosine):
    * its normal has the wrong sign. */
  bool
  normalTurnedOver (std::size_t local, const int *ids, int count) const;

  /** Turns over the normals_ that stage 1 found facing the wrong way
    * (ThreadRimPoints::turned_over), each once. */
  void
  turnNormalsOver (std::vector<ThreadRimPoints> &found);

  /** Marks stray_ (isStray): points off
    * the surface, found among those whose nearest neighbour is far for their
    * pitch (\a spacing_of, \a pitch_of of stage 1). Returns each stray with
    * the reach of its k nearest. */
  std::vector<std::pair<int, float>>
  markStrays (const std::vector<float> &spacing_of, const std::vector<float> &pitch_of);

  /** The usable points, not strays, that hold one of \a strays (markStrays)
    * among their k nearest (within \a reach_of, the squared distance of
    * each point's k-th nearest), sorted. */
  std::vector<int>
  pointsBesideStrays (const std::vector<std::pair<int, float>> &strays, const std::vector<float> &reach_of) const;

  /** The rim points that each thread of findRimPoints found, in usable
    * order in one store. */
  static RimCandidates
  mergeRimCandidates (std::vector<ThreadRimPoints> &found);

  /** Sets min_hole_size_used_: the min hole size set, or one for the
    * sampling's evenness (the lower quartile of \a evenness_of: every
    * kEvennessStride-th point's tangential nearest neighbour over its pitch,
    * 0 where not measured); and, when none is set, region_evenness_ (with
    * \a pitch_of, each usable point's pitch). */
  void
  chooseMinHoleSize (const std::vector<float> &evenness_of, const std::vector<float> &pitch_of);

  /** The min hole size (pitches) around usable point \a local, where the
    * sampling pitch is \a pitch: the one for the evenness of the sampling
    * around it (the whole cloud's where too few points were measured). */
  float
  minHoleSizeAround (int local, float pitch) const;

  /** Stage 1b: keeps the rim points that an empty disc of the minimum hole
    * size around them (minHoleSizeAround) touches; the others border gaps of
    * the sampling. Stray points (detail::isStrayPoint: off the surface,
    * their gap is their own) go too.
    * Sets the kept points' walk_normal from the same neighbours. */
  void
  keepHoleSizedGaps (RimCandidates &rim, const std::vector<float> &pitch_of) const;

  /** Is a point whose nearest and second nearest neighbours lie at
    * \a nearest and \a second, of neighbours \a ids, off the surface
    * (detail::isStrayPoint past kRimStrayPitches, over their pitch_of)? */
  static bool
  isStray (float nearest, float second, const std::vector<int> &ids, const std::vector<float> &pitch_of);

  /** Stage 3 for one traced loop (members index \a rim): the midpoint
    * refinement of section 3.3, its measures, and hole or border. */
  BoundaryLoop
  finishLoop (const detail::TracedLoop &traced, const std::vector<RimPoint> &rim, const std::vector<float> &pitch_of) const;

  /** k nearest usable points to usable point \a local (itself excluded), as local ids. */
  void
  nearestUsable (std::size_t local, int k, std::vector<int> &ids, std::vector<float> &sqr_distances) const;

  /** Nearest usable point to a position on the surface of the input points
    * \a end_a and \a end_b (not across a thin part), as a cloud index (-1 if none). */
  int
  nearestCloudIndex (const Eigen::Vector3f &position, int end_a, int end_b) const;

  /** Nearest-neighbour distance of a rim point, the mean spacing for others. */
  float
  spacingOf (int local) const;

  /** True when usable point \a local, of unit normal \a normal, lies on a
    * thin part: of its \a count nearest \a ids, enough lie on the other
    * side (\a other_side, set for each: detail::onOtherSideOfThinPart) and
    * few face the other way without (noise). */
  bool
  onThinPart (std::size_t local, const Eigen::Vector3f &normal, const int *ids, int count, bool *other_side) const;

  /** True when a disc of diameter \a diameter, empty of points on this side
    * of the surface, touches usable point \a local from inside its empty
    * sector \a gap (tried at several angles within the sector: the sector's
    * bisector on a ragged rim need not point at the hole's centre). \a nearest
    * are its k nearest neighbours (local ids). On a thin part the disc must
    * also lie over the other face (see detail::emptyDiscTouches). */
  bool
  emptyDiscTouches (int local, const detail::AngularGap &gap, const std::vector<int> &nearest, float diameter,
                    float pitch, bool on_thin_part) const;

  /** True when more than half of \a ids have normals within
    * kMinPlainViewNormalCosine of usable point \a local's: the unfolding
    * into its tangent plane can be trusted. */
  bool
  normalsAgree (int local, const std::vector<int> &ids) const;

  /** The normal the loop tracing uses for rim point \a local, given its
    * nearest neighbours \a ids: its own, or their mean normal when its own
    * turned far from all of theirs. */
  Eigen::Vector3f
  tracingNormal (int local, const std::vector<int> &ids) const;

  /** Is usable point \a local a stray that detection sets aside (stray_)? */
  bool
  setAside (int local) const { return !stray_.empty () && stray_[static_cast<std::size_t> (local)]; }

  /** Usable points within \a radius of usable point \a local, as local ids,
    * strays (setAside) left out. */
  void
  usableWithin (int local, float radius, std::vector<int> &ids) const;

  /** Fills length, spacing, diameter of a loop from its indices. */
  void
  measure (BoundaryLoop &loop) const;

  SearchPtr search_;
  int k_ = static_cast<int> (parameters::kKSearch.default_value);
  float angle_threshold_ = parameters::kAngleThreshold.default_value;
  float link_factor_ = parameters::kLinkDistanceFactor.default_value;
  float min_hole_pitches_ = parameters::kMinHoleSize.default_value;
  float min_hole_diameter_ = parameters::kMinHoleDiameter.default_value;
  int min_loop_points_ = static_cast<int> (parameters::kMinLoopPoints.default_value);
  float max_hole_diameter_ = parameters::kMaxHoleDiameter.default_value;
  unsigned int threads_ = 0;

  // Working state of one call.
  pcl::IndicesPtr usable_;                //!< cloud indices of the oriented points
  std::vector<int> local_of_;             //!< cloud index -> position in usable_, or -1
  std::vector<Eigen::Vector3f> positions_;
  std::vector<Eigen::Vector3f> normals_;  //!< unit
  std::vector<std::pair<int, float>> rim_spacing_;  //!< (usable point, nearest distance) of rim points, sorted
  detail::PointGrid grid_;                        //!< over positions_, when no search is set
  std::vector<char> flags_;
  std::vector<char> stray_;  //!< usable point -> off the surface (markStrays); empty when none
  float mean_spacing_ = 0.f;
  float mean_pitch_ = 0.f;
  float sampling_evenness_ = 0.f;
  float min_hole_size_used_ = 0.f;
  detail::RegionEvenness region_evenness_;  //!< when no min hole size is set
  std::size_t stray_count_ = 0;
  std::size_t turned_normal_count_ = 0;
};

}  // namespace pcl_holefill

#ifdef PCL_NO_PRECOMPILE
#include <pcl_holefill/impl/hole_boundary_estimation.hpp>
#endif
