/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/boundary_loop.h>
#include <pcl_holefill/detail/elastic_sampler.h>
#include <pcl_holefill/hole_filling_parameters.h>
#include <pcl_holefill/hole_report.h>
#include <pcl_holefill/detail/local_surface.h>
#include <pcl_holefill/voxel_hash_search.h>

#include <pcl/filters/filter.h>
#include <pcl/search/search.h>

#include <functional>
#include <limits>
#include <vector>

namespace pcl_holefill
{
/** \brief Fills the holes of an oriented point cloud: the paper's Algorithm 1
  * as a PCL filter.
  *
  * filter(output) writes every input point (of setIndices(), if given),
  * unchanged, then the filled points with their propagated normals; other
  * fields of a filled point (colour, intensity, ...) are copied from its
  * nearest neighbour. Per hole, as Algorithm 1: measure the rim (the
  * boundary loop found by HoleBoundaryEstimation, or given by setHoles()),
  * contract it pass by pass (normal propagation, eq. 1-2; the control curve
  * and the sampling along it, sec. 4.1-4.2; position optimisation, eq. 7-8;
  * the combination constraint, sec. 4.4) until the termination rule of
  * sec. 4.2, then report. Holes are independent and filled in parallel, in a
  * deterministic order; getReports() tells what happened to each.
  *
  * Parameters keep the paper's names. Each one's default, range and unit is
  * written once, in hole_filling_parameters.h (parameters::k...), and listed
  * in doc/parameters.md. Lengths are in cloud units and, left at 0, derived
  * per hole from the mean nearest-neighbour distance h and the sampling
  * pitch p (sqrt of the surface area per point) around its rim, so the
  * defaults work on any cloud without tuning. Where the paper is ambiguous:
  *  - sigma_n is taken over |n_p - n_ref| (no unit; the paper prints "BBL",
  *    which cannot apply to a normal difference). Small (0.1) recovers sharp
  *    edges, corners and apexes; kSup (the paper's "Sup") switches g2 off for
  *    round patches; 0 chooses per hole, twice the spread of the normals
  *    around its rim within 0.1..0.3, and the report says which value each
  *    hole got.
  *  - sigma_r gives the spacing of the filled points by eq. (6),
  *    d_eq = sigma_r^2 ln(10^4), taken literally in cloud units. The paper's
  *    Table 1 values (0.12-0.25 "BBL") would give d_eq of 13-58 % of the
  *    model's size under any reading, so they cannot be reused; 0 takes d_eq
  *    = spacing factor x p instead, so that the fill is as dense as the
  *    input whatever its sampling.
  *  - first order (beyond the paper) fits a linear normal field instead of
  *    eq. (1)'s constant one, which makes cones on smooth holes; it is left
  *    out per hole where the rim is noisy and its normals too rough to
  *    extrapolate (HoleReport::first_order says which).
  *
  * \code
  * pcl::PointCloud<pcl::PointNormal>::Ptr cloud (new pcl::PointCloud<pcl::PointNormal>);
  * // ... read or compute an oriented cloud ...
  * pcl_holefill::HoleFilling<pcl::PointNormal> filler;
  * filler.setInputCloud (cloud);
  * filler.setSigmaN (0.1f);  // sharp edges; pcl_holefill::kSup for round patches; 0 = per hole
  * pcl::PointCloud<pcl::PointNormal> filled;
  * filler.filter (filled);   // the input points, unchanged, then the filled ones
  * for (const auto &report : filler.getReports ())
  *   std::cout << report.points_added << (report.closed ? " closed\n" : " open\n");
  * \endcode
  *
  * \note The method of "Shape controllable geometry completion for point
  * cloud models" (decomposing each pass of hole-boundary contraction into
  * normal propagation and position sampling, with a normal-dissimilarity
  * constraint for sharp features). The copy of the paper this project works
  * from carries no author or venue line, so only its title is cited here.
  */
template <typename PointT>
class HoleFilling : public pcl::Filter<PointT>
{
public:
  using Ptr = pcl::shared_ptr<HoleFilling<PointT>>;
  using ConstPtr = pcl::shared_ptr<const HoleFilling<PointT>>;
  using PointCloud = pcl::PointCloud<PointT>;
  using PointCloudPtr = typename PointCloud::Ptr;
  using PointCloudConstPtr = typename PointCloud::ConstPtr;
  using SearchPtr = typename pcl::search::Search<PointT>::Ptr;

  HoleFilling () { filter_name_ = "HoleFilling"; }

  // Each parameter's default, range and unit: hole_filling_parameters.h.

  /** \brief r, the neighbourhood of eq. (1) and (7): parameters::kRadius. */
  void setRadius (float r) { radius_ = r; }
  float getRadius () const { return radius_; }

  /** \brief r <- r / factor after each pass (Fig. 1(c)): parameters::kRadiusShrinkFactor. */
  void setRadiusShrinkFactor (float factor) { shrink_ = factor; }
  float getRadiusShrinkFactor () const { return shrink_; }

  /** \brief sigma_d, the std of the distance weight g1: parameters::kSigmaD. */
  void setSigmaD (float sigma_d) { sigma_d_ = sigma_d; }
  float getSigmaD () const { return sigma_d_; }

  /** \brief sigma_n, the std of the normal weight g2: small keeps edges
    * sharp, kSup gives round patches; 0 chooses per hole from the rim's
    * normals: parameters::kSigmaN. */
  void setSigmaN (float sigma_n) { sigma_n_ = sigma_n; }
  float getSigmaN () const { return sigma_n_; }

  /** \brief sigma_r, the width of the elastic force (eq. 6), which sets the
    * spacing of new points d_eq: parameters::kSigmaR. */
  void setSigmaR (float sigma_r) { sigma_r_ = sigma_r; }
  float getSigmaR () const { return sigma_r_; }

  /** \brief d_eq in sampling pitches when sigma_r is 0: parameters::kSpacingFactor. */
  void setSpacingFactor (float factor) { spacing_factor_ = factor; }
  float getSpacingFactor () const { return spacing_factor_; }

  /** \brief The termination rule of sec. 4.2 (the paper's 30 %): parameters::kTerminationRatio. */
  void setTerminationRatio (float ratio) { termination_ratio_ = ratio; }
  float getTerminationRatio () const { return termination_ratio_; }

  /** \brief Bound on the passes of one hole: parameters::kMaxPasses. */
  void setMaxPasses (int passes) { max_passes_ = passes; }
  int getMaxPasses () const { return max_passes_; }

  /** \brief A hole whose boundary grows past this many times its first
    * length is diverging and stopped: parameters::kMaxBoundaryGrowth. */
  void setMaxBoundaryGrowth (float growth) { max_growth_ = growth; }
  float getMaxBoundaryGrowth () const { return max_growth_; }

  /** \brief The first-order extension of eq. (1)-(2) (a linear normal field
    * around each candidate) instead of the paper's constant one; left out
    * per hole on noisy rims: parameters::kFirstOrder. */
  void setFirstOrder (bool on) { first_order_ = on; }
  bool getFirstOrder () const { return first_order_; }

  /** \brief The combination constraint of section 4.4: parameters::kCombinationConstraint. */
  void setCombinationConstraint (bool on) { combination_constraint_ = on; }
  bool getCombinationConstraint () const { return combination_constraint_; }

  /** \brief The bilateral preprocessing of section 3.2 first; it moves
    * input points: parameters::kDenoise. */
  void setDenoise (bool on) { denoise_ = on; }
  bool getDenoise () const { return denoise_; }

  /** \brief Smallest hole filled: the diameter of the empty disc it must
    * hold, in local sampling pitches (sqrt of the surface area per point);
    * below 5 the gaps of uniformly random sampling are taken for holes
    * (HoleBoundaryEstimation::setMinHoleSize): parameters::kMinHoleSize. */
  void setMinHoleSize (float pitches) { min_hole_pitches_ = pitches; }
  float getMinHoleSize () const { return min_hole_pitches_; }

  /** \brief Holes wider than this are left alone: parameters::kMaxHoleDiameter. */
  void setMaxHoleDiameter (float diameter) { max_hole_diameter_ = diameter; }
  float getMaxHoleDiameter () const { return max_hole_diameter_; }

  /** \brief Loops to fill (indices into the input cloud) instead of the
    * detected holes; an empty vector (default) means detect. */
  void setHoles (const std::vector<BoundaryLoop> &holes) { user_holes_ = holes; }
  const std::vector<BoundaryLoop> &getHoles () const { return user_holes_; }

  /** \brief A search over the input cloud for detection and for gathering each
    * hole's surroundings (default: a VoxelHashSearch). */
  void setSearchMethod (const SearchPtr &search) { search_ = search; }
  SearchPtr getSearchMethod () const { return search_; }

  /** \brief Threads for detection and for filling holes side by side; 0 = all cores. */
  void setNumberOfThreads (unsigned int n) { threads_ = n; }
  unsigned int getNumberOfThreads () const { return threads_; }

  /** \brief Called once per hole as soon as it is done (from the thread that
    * filled it, one call at a time), with its position in the list of holes,
    * their number and its report: for progress output. */
  using ProgressCallback = std::function<void (std::size_t hole, std::size_t holes, const HoleReport &report)>;
  void setProgressCallback (const ProgressCallback &callback) { progress_ = callback; }

  /** \brief After filter(): one report per hole, in output order. */
  const std::vector<HoleReport> &getReports () const { return reports_; }

  /** \brief True when every parameter is usable; prints the first bad one otherwise. */
  bool
  checkParameters () const;

protected:
  using pcl::Filter<PointT>::filter_name_;
  using pcl::Filter<PointT>::input_;
  using pcl::Filter<PointT>::indices_;

  void
  applyFilter (PointCloud &output) override;

private:
  using pcl::Filter<PointT>::getClassName;

  /** The scale of one hole, measured on its rim. */
  struct HoleScale
  {
    Eigen::Vector3f centre = Eigen::Vector3f::Zero ();  //!< centroid of the rim
    float rim_radius = 0.f;  //!< largest distance of a rim point from the centre
    float spacing = 0.f;     //!< h: mean nearest-neighbour distance of the rim points
    float pitch = 0.f;       //!< sqrt(surface area per point) around the rim (median)
    float d_eq = 0.f;        //!< equilibrium distance: the spacing of the filled points
    float radius = 0.f;      //!< r of the first pass
    float constraint_radius = 0.f;  //!< reach of the combination constraint
    float min_radius = 0.f;  //!< r never shrinks below this
    float bound = 0.f;       //!< the fill stays this close to the centre
    int max_passes = 0;      //!< bound on passes for this hole
    /** How far from the centre the searches that measured the rim looked
      * (infinite when one found fewer than it asked for): a search that
      * holds every point within this, and within bound + radius, gives this
      * hole exactly what a search over the whole cloud gives. */
    float searched_reach = 0.f;
  };

  /** A hole's surroundings, copied: the fill grows this cloud, never the input. */
  struct Surroundings
  {
    PointCloudPtr cloud;                           //!< input points near the hole, then the fill
    typename VoxelHashSearch<PointT>::Ptr search;  //!< over cloud, extended pass by pass
    std::size_t input_points = 0;                  //!< how many of cloud are input points
    pcl::Indices rim;                              //!< the rim, as indices into cloud
    int threads = 1;                               //!< for the work within this hole
  };

  /** Fills one hole of \a working with \a threads, its \a rim and \a scale
    * measured (step 1, measureHole): steps 2-5 of Algorithm 1 for one loop.
    * The new points go to \a filled. */
  void
  fillHole (const PointCloud &working, pcl::search::Search<PointT> &search, const BoundaryLoop &loop,
            const pcl::Indices &rim, const HoleScale &scale, PointCloud &filled, HoleReport &report,
            int threads) const;

  /** Steps 2-4 of Algorithm 1 for one hole: its surroundings and their
    * normals, the sampler, the passes until termination, the closure check
    * (and the fill taken up again where it stopped early). With
    * \a across_opening the rim's normals are first turned to the face
    * across the opening (turnRimAcrossOpening). Returns the surroundings,
    * the fill appended to their cloud. */
  Surroundings
  contractHole (const PointCloud &working, pcl::search::Search<PointT> &search, const BoundaryLoop &loop,
                const pcl::Indices &rim, const HoleScale &scale, HoleReport &report, int threads,
                bool across_opening) const;

  /** Did the fill in \a surroundings (reported in \a report) run off its
    * loop along walls parallel to the loop's axis (detail::shareAlongWalls,
    * alignmentWithLoop), or set out along them and stop at the rim? */
  static bool
  ranAlongWalls (const Surroundings &surroundings, const HoleReport &report);

  /** The centroid of the input points of \a surroundings. */
  static Eigen::Vector3f
  surroundingsCentroid (const Surroundings &surroundings);

  /** The rim's points in loop order: their \a positions and unit \a normals
    * (as the fill's copy has them now). */
  static void
  rimPositionsAndNormals (const Surroundings &surroundings, std::vector<Eigen::Vector3f> &positions,
                          std::vector<Eigen::Vector3f> &normals);

  /** Sets the fill's copy of the rim's normals to the normal of the face
    * across the opening (detail::openingNormal) and, on a flat rim, moves
    * the copy onto the plane of its outermost points; returns the depth
    * along that normal left in the copy (detail::depthAlong; 0 when moved)
    * and sets \a across to the face's normal (zero when the loop spans
    * nothing and the copy is left alone). */
  static float
  turnRimAcrossOpening (Surroundings &surroundings, Eigen::Vector3f &across);

  /** Refits the normals of the surroundings' input points that PCA blended
    * across a crease (detail::refitCreaseNormal), planes counting neighbours
    * within \a tolerance; returns how many. Only the fill's copy changes. */
  std::size_t
  refitCreaseNormals (Surroundings &surroundings, const HoleScale &scale, float tolerance) const;

  /** Refits by a quadric over \a neighbours (detail::quadricNormal) the
    * normals of the input points near the rim that lie on one smooth piece
    * (all of them when \a one_piece: the rim's wide fits showed no crease),
    * leaving out neighbours farther than \a tolerance (and the fit's own
    * spread) from it; returns how many changed. Only the fill's copy changes. */
  std::size_t
  removeRimNormalBias (Surroundings &surroundings, const HoleScale &scale, int neighbours, bool one_piece,
                       float tolerance) const;

  /** Replaces, on a noisy rim, the fill's copy of the normals within
    * kNoisyRimReachInPitches of the rim by PCA over more neighbours
    * (wideNeighbours), when the given ones are rougher (\a rough: PCA
    * normals of noisy points) and the rim shows no crease; returns how many. */
  std::size_t
  smoothNoisyNormals (Surroundings &surroundings, const HoleScale &scale, float noise, bool &rough) const;

  /** The refits of the fill's copy of the normals, for a rim of \a noise:
    * smoothNoisyNormals, refitCreaseNormals, removeRimNormalBias; returns
    * how many normals changed. */
  std::size_t
  refitNormals (Surroundings &surroundings, const HoleScale &scale, float noise) const;

  /** The \a k nearest neighbours of the surroundings' point \a i (\a nearest)
    * and the positions of those that are usable input points. */
  static void
  nearestInputPoints (const Surroundings &surroundings, std::ptrdiff_t i, int k, pcl::Indices &nearest,
                      std::vector<Eigen::Vector3f> &positions);

  /** Calls \a visit (i, nearest, positions) on the threads of \a surroundings
    * for each oriented input point i marked in \a marked, with its \a k
    * nearest neighbours (nearestInputPoints). */
  template <typename Visit>
  static void
  forEachMarked (const Surroundings &surroundings, const std::vector<char> &marked, int k, Visit &&visit);

  /** Marks the surroundings' input points within \a reach of the rim: 2
    * within \a core_reach of it, 1 farther. */
  static std::vector<char>
  markNearRim (Surroundings &surroundings, float reach, float core_reach);

  /** Does a rim point have a neighbour within \a reach whose normal is ~30 degrees off its own? */
  static bool
  rimSeesCrease (const Surroundings &surroundings, float reach);

  /** Widest empty sectors (radians) a new point may see round the rim,
    * seen along the hole's axis and along its own normal
    * (ElasticSampler::setRim). */
  struct RimGapLimits
  {
    float along_axis;
    float along_normal;
  };

  /** The limits for this rim. Wider on a rim that shows a crease when the
    * combination constraint is on: both on a clean rim (\a report's noise;
    * the constraint holds each face within 0.1 h), the axis's alone on a rim
    * with up to half a pitch of noise. The strict ones elsewhere and across
    * an opening. */
  RimGapLimits
  rimGapLimits (const Surroundings &surroundings, const HoleScale &scale, const HoleReport &report,
                bool across_opening) const;

  /** Has \a sampler keep new points within the hole's closed rim: points
    * evenly along it (at most detail::kRimOutlinePoints), seen along the
    * mean of its normals (no test where they cancel out), within \a limits
    * (the test is the backstop for fronts nothing else holds). */
  static void
  encloseByRim (detail::ElasticSampler<PointT> &sampler, const Surroundings &surroundings,
                const RimGapLimits &limits);

  /** Has \a sampler keep new points below the rim's supporting tangent
    * planes: those of rim points that (almost) every other rim point lies
    * below (ElasticSampler::setRimPlanes). */
  static void
  keepBelowRimPlanes (detail::ElasticSampler<PointT> &sampler, Surroundings &surroundings,
                      const HoleScale &scale, const HoleReport &report);

  /** Adds to the rim planes (\a points, unit \a normals) the planes of
    * faces the hole took that the rim shows only by running along them
    * (detail::findRimSidePlanes, within \a tolerance), and gives the rim
    * points on such a plane its normal in the fill's copy where theirs are
    * the face beside's. */
  static void
  holdAtRimSidePlanes (Surroundings &surroundings, float tolerance, std::vector<Eigen::Vector3f> &points,
                       std::vector<Eigen::Vector3f> &normals);

  /** The creases that cross the hole, from the faces its rim passes
    * through: each face's front stays on its side of the crease
    * (detail::findCreaseChords, ElasticSampler::setCreaseChords). */
  static void
  keepFacesApartAtCreases (detail::ElasticSampler<PointT> &sampler, const Surroundings &surroundings,
                           const HoleScale &scale, const HoleReport &report);

  /** Step 1 of Algorithm 1: the loop's usable points (\a rim) and the hole's
    * scale. False when fewer than 3 are usable or they have no spacing. */
  bool
  measureHole (const PointCloud &working, pcl::search::Search<PointT> &search, const BoundaryLoop &loop,
               pcl::Indices &rim, HoleScale &scale) const;

  /** The loop's points with a usable normal (the rim the fill works from). */
  static pcl::Indices
  usableRim (const PointCloud &working, const BoundaryLoop &loop);

  /** A ball (centre, radius) holding every point the fill of \a loop can
    * search, estimated from the detection's pitch and spacing with a margin;
    * radius 0 when the loop has no pitch (a given loop). */
  Eigen::Vector4f
  estimatedReach (const PointCloud &working, const BoundaryLoop &loop) const;

  /** Points the fill of \a holes can reach, from the detection's pitch and
    * spacing with a margin: balls about the rims' centroids (\a reaches:
    * centre and radius each). Null when the holes reach much of the cloud,
    * are many, or were given without a pitch: then the whole cloud. */
  pcl::IndicesPtr
  pointsNearHoles (const PointCloud &working, const std::vector<BoundaryLoop> &holes,
                   std::vector<Eigen::Vector4f> &reaches) const;

  /** The rim's centroid and its largest distance from it, into \a scale. */
  static void
  measureRimExtent (const PointCloud &working, const pcl::Indices &rim, HoleScale &scale);

  /** d_eq, r, the constraint's reach, r's floor, the bound and the pass
    * bound, from \a scale's spacing, pitch and rim radius. */
  void
  deriveSizes (HoleScale &scale) const;

  /** The hole's scale: centre, spacing h, pitch, d_eq, r, the bound. False without any spacing. */
  bool
  measureRim (const PointCloud &working, pcl::search::Search<PointT> &search, const pcl::Indices &rim,
              HoleScale &scale) const;

  /** Copies the input points that the fill of this hole can reach. */
  void
  gatherSurroundings (const PointCloud &working, pcl::search::Search<PointT> &search, const pcl::Indices &rim,
                      const HoleScale &scale, Surroundings &surroundings) const;

  /** Removes from \a found (sorted cloud indices) the stray points
    * (detail::markStrayPoints) that are not on the \a rim. */
  static void
  leaveOutStrayPoints (const PointCloud &working, const pcl::Indices &rim, int threads, pcl::Indices &found);

  /** The sampler's parameters for this hole, from the scale and the rim's noise. */
  void
  setUpSampler (detail::ElasticSampler<PointT> &sampler, const Surroundings &surroundings, const HoleScale &scale,
                HoleReport &report) const;

  /** The Do ... Until loop of Algorithm 1: contraction passes from \a front
    * until the termination rule; returns the boundary where the fill stopped. */
  detail::Front
  contractUntilTermination (detail::ElasticSampler<PointT> &sampler, Surroundings &surroundings, detail::Front front,
                            const HoleScale &scale, HoleReport &report,
                            int pass_budget = std::numeric_limits<int>::max ()) const;

  /** The termination rule after pass \a pass of this run, \a passes_done in all (kNotStarted: go on). */
  Termination
  terminationOf (const detail::ContractionStats &stats, const detail::Front &next, int pass, float first_length,
                 unsigned passes_done, int max_passes) const;

  /** closed, open_points and open_diameter of \a report: where an empty disc
    * still touches \a last or a filled point. Returns the openings' boundaries. */
  detail::Front
  checkClosure (const Surroundings &surroundings, const detail::Front &last, const HoleScale &scale,
                HoleReport &report) const;

  /** Whether an empty disc of \a diameter touches \a v in the surroundings;
    * \a gap_direction receives the direction of the empty side. */
  bool
  emptyDiscAt (const Surroundings &surroundings, const detail::FrontVertex &v, float diameter,
               Eigen::Vector3f &gap_direction) const;

  /** Contracts again from one opening's boundary, confined to the opening. */
  detail::Front
  resumeOpening (detail::ElasticSampler<PointT> &sampler, Surroundings &surroundings, detail::FrontChain opening,
                 const HoleScale &scale, HoleReport &report) const;

  /** The openings worth contracting again: those inside the rim. */
  static detail::Front
  resumable (const detail::Front &openings, const HoleScale &scale);

  /** Stopped by the paper's rule (ratio, no new boundary), not cut short. */
  static bool
  stoppedNaturally (const HoleReport &report);

  /** The area of \a added filled points over that of the disc spanning
    * the rim of \a loop. */
  static float
  discsCovered (const BoundaryLoop &loop, const HoleScale &scale, std::size_t added);

  /** Did a fill that stayed open cover more than a band along its rim can
    * (detail::kNotClosedIn, kBandMargin)? Then it grew elsewhere and is
    * withdrawn. */
  static bool
  grewPastHole (const BoundaryLoop &loop, const HoleScale &scale, std::size_t added, const HoleReport &report);

  /** The warnings a user should see about one hole. */
  void
  warnAbout (const BoundaryLoop &loop, const HoleScale &scale, std::size_t added, const HoleReport &report) const;

  /** \a output = \a points then every fill, allocated once. */
  void
  writeOutput (const PointCloud &points, const std::vector<PointCloud> &fills, PointCloud &output) const;

  /** The loops to fill, as indices into \a working (the indexed points). */
  bool
  collectHoles (const PointCloudConstPtr &working, const SearchPtr &search, std::vector<BoundaryLoop> &holes) const;

  /** Parameters and indices usable, input not empty (else says why). */
  bool
  inputIsUsable () const;

  /** \a given: the points the output starts with (the input, or the indexed
    * points; denoised if asked). \a working: the same, consistently oriented. */
  void
  prepareClouds (PointCloudConstPtr &given, PointCloudConstPtr &working) const;

  /** Every hole filled (side by side), its points in \a fills, reports_ set. */
  void
  fillHoles (const PointCloudConstPtr &working, pcl::search::Search<PointT> &search,
             const std::vector<BoundaryLoop> &holes, std::vector<PointCloud> &fills);

  float radius_ = parameters::kRadius.default_value;
  float shrink_ = parameters::kRadiusShrinkFactor.default_value;
  float sigma_d_ = parameters::kSigmaD.default_value;
  float sigma_n_ = parameters::kSigmaN.default_value;
  float sigma_r_ = parameters::kSigmaR.default_value;
  float spacing_factor_ = parameters::kSpacingFactor.default_value;
  float termination_ratio_ = parameters::kTerminationRatio.default_value;
  int max_passes_ = static_cast<int> (parameters::kMaxPasses.default_value);
  float max_growth_ = parameters::kMaxBoundaryGrowth.default_value;
  bool first_order_ = parameters::kFirstOrder.default_value;
  bool combination_constraint_ = parameters::kCombinationConstraint.default_value;
  bool denoise_ = parameters::kDenoise.default_value;
  float max_hole_diameter_ = parameters::kMaxHoleDiameter.default_value;
  float min_hole_pitches_ = parameters::kMinHoleSize.default_value;
  std::vector<BoundaryLoop> user_holes_;
  SearchPtr search_;
  unsigned int threads_ = 0;
  std::vector<HoleReport> reports_;
  ProgressCallback progress_;
};

}  // namespace pcl_holefill

#ifdef PCL_NO_PRECOMPILE
#include <pcl_holefill/impl/hole_filling.hpp>
#endif
