/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/detail/crease_chords.h>
#include <pcl_holefill/detail/front.h>
#include <pcl_holefill/detail/normal_propagation.h>
#include <pcl_holefill/detail/point_grid.h>

#include <pcl/point_cloud.h>
#include <pcl/search/search.h>

#include <algorithm>
#include <cmath>

namespace pcl_holefill::detail
{
/** \brief Section 4 of the paper: one pass of hole-boundary contraction.
  *
  * From the former boundary B' (a Front) it builds the new boundary B:
  *  1. each b'_i gets a contracting direction n x tangent (tangent over a
  *     5-point stencil; one inward sign per chain, by a vote of "away from the
  *     mean of the existing neighbours") and a control candidate at the
  *     equilibrium distance d_eq along it (eq. 5-6);
  *  2. the candidate's position is optimised (eq. 7-8, two rounds, normals
  *     from NormalPropagation, eq. 1);
  *  3. it is discarded when it feels a repulsive force (eq. 5: a former
  *     boundary point other than b'_i closer than d_eq), when it lands on
  *     existing surface (closer than d_eq/2: the hole is closed there), when
  *     it overshoots (the combination constraint, section 4.4), or when it
  *     leaves the hole's bounding ball;
  *  4. the kept control points, in order, form the control curve C, cut
  *     where consecutive ones are more than 3 d_eq apart (fronts that met);
  *  5. C is sampled every d_eq of arc length (sec. 4.2), each sample optimised
  *     and checked as in 2-3: the kept samples are B.
  *
  * Combination constraint (sec. 4.4), as the paper's READING notes advise:
  * a sample is tested against the tangent plane of every existing point q
  * within r (input and filled), not only of control points, because when one
  * face's front reaches a ridge first there is no control point of the other
  * face yet. q is convex when its neighbours lie below its tangent plane on
  * average (their g1-weighted mean offset < -tolerance), concave when above,
  * flat (untested) otherwise; a sample must lie on or below the plane of a
  * convex q and on or above that of a concave q, within the tolerance.
  *
  * The input cloud is the surface known so far and must be searchable by the
  * given search method; the caller appends each pass's B to it.
  */
template <typename PointT>
class ElasticSampler
{
public:
  using Ptr = pcl::shared_ptr<ElasticSampler<PointT>>;
  using ConstPtr = pcl::shared_ptr<const ElasticSampler<PointT>>;
  using PointCloud = pcl::PointCloud<PointT>;
  using PointCloudConstPtr = typename PointCloud::ConstPtr;
  using SearchPtr = typename pcl::search::Search<PointT>::Ptr;

  /** \brief d_eq from the paper's sigma_r by equation (6): exp(-d_eq / sigma_r^2) = 1e-4. */
  static float
  equilibriumDistanceFromSigmaR (float sigma_r) { return sigma_r * sigma_r * std::log (1e4f); }

  /** \brief The surface known so far (every point of it is used: a stage
    * of HoleFilling, it takes no indices). */
  void
  setInputCloud (const PointCloudConstPtr &cloud);
  const PointCloudConstPtr &
  getInputCloud () const { return input_; }

  void
  setSearchMethod (const SearchPtr &search);
  SearchPtr
  getSearchMethod () const { return propagation_.getSearchMethod (); }

  /** \brief Neighbourhood radius r of equations (1) and (7) (cloud units). */
  void
  setRadius (float radius) { propagation_.setRadius (radius); }
  float
  getRadius () const { return propagation_.getRadius (); }

  void
  setSigmaD (float sigma_d) { propagation_.setSigmaD (sigma_d); }
  float
  getSigmaD () const { return propagation_.getSigmaD (); }

  /** \brief sigma_n of g2, or kSup (the paper's "Sup") to switch g2 off. */
  void
  setSigmaN (float sigma_n) { propagation_.setSigmaN (sigma_n); }
  float
  getSigmaN () const { return propagation_.getSigmaN (); }

  void
  setFirstOrder (bool first_order) { propagation_.setFirstOrder (first_order); }
  bool
  getFirstOrder () const { return propagation_.getFirstOrder (); }

  /** \brief d_eq, the spacing of the new samples (cloud units, > 0). */
  void
  setEquilibriumDistance (float distance) { equilibrium_distance_ = distance; }
  float
  getEquilibriumDistance () const { return equilibrium_distance_; }

  /** \brief Tolerance of the combination constraint: how far past a
    * reference point's tangent plane a sample may lie (cloud units, >= 0;
    * default 0). On noisy data about the noise of one point. */
  void
  setConstraintTolerance (float tolerance) { tolerance_ = tolerance; }
  float
  getConstraintTolerance () const { return tolerance_; }

  /** \brief Growth of the constraint's tolerance with the distance from the
    * reference point (no unit, >= 0; default 0): the error of its normal, as
    * an angle. A tangent plane tilted by e puts a sample at distance d on the
    * true surface d sin(e) above or below it; estimated normals near a crease
    * tilt by much more than one point's noise. */
  void
  setConstraintSlope (float slope) { slope_ = slope; }
  float
  getConstraintSlope () const { return slope_; }

  /** \brief How far a reference point may lie above or below its
    * neighbours (their weighted mean height over its tangent plane) and
    * still count as flat, not convex or concave (cloud units, >= 0; default
    * 0). Smaller than the constraint's tolerance on noisy data: the mean
    * height grows with the reach across an edge, and a dead zone as wide as
    * one point's noise hides the edges of noisy scans (a cylinder's rim at
    * noise 0.3 % of the diagonal: the patch ran 0.1 past it). */
  void
  setCurvatureSignTolerance (float tolerance) { sign_tolerance_ = tolerance; }
  float
  getCurvatureSignTolerance () const { return sign_tolerance_; }

  /** \brief Reach of the combination constraint: the reference points a
    * sample is tested against, and the neighbours that label them convex or
    * concave (cloud units; 0 = r, default). Kept near the sampling pitch
    * when r is wide: a wider reach labels points far from an edge as convex
    * and tests each sample against more noisy tangent planes. */
  void
  setConstraintRadius (float radius) { constraint_radius_ = radius; }
  float
  getConstraintRadius () const { return constraint_radius_; }

  /** \brief Lets a sample past a reference point's tangent plane when the
    * plane bounds another face than the one the sample grew on (beyond the
    * paper; default off): its front vertex lies past the plane already, and
    * the point's neighbours on the vertex's side label it otherwise than
    * all its neighbours do. Where a wall meets two faces (a step beside a
    * floor, the foot of a thin plate), the wall's points see one face below
    * their tangent plane and the other above: whichever outweighs labels
    * them, and a floor behind a wall labelled concave had every sample
    * rejected. For clean rims: half a neighbourhood's mean height carries
    * twice the noise's variance. */
  void
  setSignTowardsFront (bool enabled) { sign_towards_front_ = enabled; }
  bool
  getSignTowardsFront () const { return sign_towards_front_; }

  /** \brief Switches the combination constraint (default on). */
  void
  setCombinationConstraint (bool enabled) { combination_constraint_ = enabled; }
  bool
  getCombinationConstraint () const { return combination_constraint_; }

  /** \brief New points must stay inside this ball (radius 0 = unbounded). */
  void
  setBoundingBall (const Eigen::Vector3f &centre, float radius)
  {
    bound_centre_ = centre;
    bound_radius_ = radius;
  }

  /** \brief The rim of a closed hole, which new points must lie within (an
    * empty rim, the default, switches the test off). A point is beyond the
    * rim when, seen along the hole's \a axis, the rim leaves a sector wider
    * than \a max_gap_along_axis empty around it (rimGapAround), and, seen
    * along its own normal, one wider than \a max_gap_along_normal (radians).
    * Either view alone misjudges some holes: along the axis, the faces of a
    * thin part's end run parallel to it and lie on the rim's outline; along
    * its own normal, the rim of a steep apex lies all on one side. A few
    * dozen points along the loop are enough. */
  void
  setRim (std::vector<Eigen::Vector3f> rim, const Eigen::Vector3f &axis, float max_gap_along_axis,
          float max_gap_along_normal)
  {
    rim_ = std::move (rim);
    rim_axis_ = axis.normalized ();
    max_rim_gap_along_axis_ = max_gap_along_axis;
    max_rim_gap_along_normal_ = max_gap_along_normal;
  }

  /** \brief New points must not lie above the tangent plane of any of the
    * rim points given (\a points with unit \a normals) by more than
    * \a tolerance + \a slope x their distance from it (cloud units, radians).
    * For the rim of a hole in a convex region (every rim point below every
    * other's tangent plane) this is the surface's own property; it stops a
    * face's front that reaches an edge or a corner before the other faces'
    * fronts do, where the combination constraint has no neighbour to test
    * against and the rim's outline, seen along the axis, still encloses it. */
  void
  setRimPlanes (std::vector<Eigen::Vector3f> points, std::vector<Eigen::Vector3f> normals, float tolerance,
                float slope)
  {
    rim_plane_points_ = std::move (points);
    rim_plane_normals_ = std::move (normals);
    rim_plane_tolerance_ = tolerance;
    rim_plane_slope_ = slope;
  }

  /** \brief The creases that cross the hole (findCreaseChords): a sample of
    * one face on the other's side of a chord's plane by more than \a
    * tolerance (cloud units) overshoots the crease. */
  void
  setCreaseChords (std::vector<CreaseChord> chords, float tolerance)
  {
    crease_chords_ = std::move (chords);
    crease_tolerance_ = tolerance;
  }

  /** \brief Only reference points whose normal lies within 45 degrees of
    * the unit \a direction bound the samples (the combination constraint);
    * zero (default): every reference point. Across an opening: the face's
    * normal, so that the walls standing across the face do not. */
  void
  setConstraintFacing (const Eigen::Vector3f &direction) { constraint_facing_ = direction; }
  const Eigen::Vector3f &
  getConstraintFacing () const { return constraint_facing_; }

  /** \brief The next pass's closed chains contract towards \a centre
    * instead of by the vote "away from the existing neighbours". Across an
    * opening the existing neighbours of the rim are the walls below it, level
    * with it (a box) or curving inwards (a tube), so that vote says nothing
    * or the wrong thing; from the second pass on the first ring is there to
    * vote against. Cleared by the pass that uses it. */
  void
  setInwardCentre (const Eigen::Vector3f &centre)
  {
    inward_centre_ = centre;
    has_inward_centre_ = true;
  }

  /** \brief Threads for the candidates of one pass (>= 1, default 1). The
    * candidates are placed side by side and kept in order: the result is the
    * same for any number. */
  void
  setNumberOfThreads (int threads) { threads_ = std::max (1, threads); }
  int
  getNumberOfThreads () const { return threads_; }

  /** \brief One pass: \a former is B', \a next receives B. False (PCL_ERROR) on bad setup. */
  bool
  contract (const Front &former, Front &next, ContractionStats &stats);

  /** \brief Equations (7)-(8), two rounds, then the final normal (eq. 1).
    * False when the neighbourhood carries no weight. \a around receives the
    * oriented points within r of the final position, nearest first. */
  bool
  optimisePosition (Eigen::Vector3f &position, const Eigen::Vector3f &reference_normal, Eigen::Vector3f &normal,
                    Neighbourhood &around) const;

private:
  PointCloudConstPtr input_;

  enum class Verdict
  {
    kKept,
    kRepelled,
    kTooClose,
    kOvershoot,
    kUnsupported,
    kOutsideBound,
    kBeyondRim
  };

  /** What one pass shares between its steps. */
  struct PassState
  {
    explicit PassState (float d_eq) : former_grid (d_eq), sample_grid (d_eq) {}
    PointGrid former_grid;                            //!< B', by id into former_vertices
    std::vector<const FrontVertex *> former_vertices;
    PointGrid sample_grid;                            //!< the samples of B so far
    std::size_t samples = 0;
  };

  /** Section 4.1, step 1: the contracting direction n x t at each vertex of
    * \a chain, one inward sign for the chain. */
  std::vector<Eigen::Vector3f>
  contractingDirections (const FrontChain &chain) const;

  /** A control point that survived, and whether a candidate discarded
    * between it and the one kept before it (cyclically on a closed chain)
    * met another piece of boundary or stopped at the shape. */
  struct ControlPoint
  {
    FrontVertex vertex;
    bool met_before = false;
  };

  /** Section 4.1, steps 2-3 (eq. 5-8): the control points that survive;
    * \a base is the id of the chain's first vertex in the former grid. */
  std::vector<ControlPoint>
  controlPoints (const FrontChain &chain, const std::vector<Eigen::Vector3f> &directions, int base,
                 const PassState &pass, ContractionStats &stats) const;

  /** Whether \a chain is a rim of input points (not sampled) along which
    * neighbours' normals agree within kSmoothRimCosine: no edge crosses it. */
  static bool
  smoothRim (const FrontChain &chain);

  /** The existing points (input and filled) within \a reach of \a position
    * on its own surface: a point across a thin part (detail::onOtherSideOfThinPart,
    * seen from \a normal) is none. */
  std::size_t
  surfacePointsWithin (const Eigen::Vector3f &position, const Eigen::Vector3f &normal, float reach) const;

  /** Whether the \a candidate from vertex \a i of \a chain (the
    * former grid's id base + i), given \a verdict, met another piece of
    * boundary or stopped at the shape. Repelled: one of \a close (the former
    * points within the repulsion reach, as found) is not among the chain's
    * own vertices near i (\a arc: arc length at each vertex). Too close: the
    * same within the duplicate reach (\a close is filled here), or an
    * existing point there that is no former vertex. */
  bool
  metOtherBoundary (const FrontVertex &candidate, Verdict verdict, std::vector<PointGrid::Neighbour> &close,
                    const FrontChain &chain, const std::vector<float> &arc, int i, int base,
                    const PassState &pass) const;

  /** Section 4.1: the control curve C, as runs of control points; \a wraps
    * tells that the single run is a closed loop. */
  std::vector<std::vector<FrontVertex>>
  controlCurve (const std::vector<ControlPoint> &controls, bool closed_chain, bool &wraps) const;

  /** Section 4.2: points every d_eq of arc length along a run (unplaced),
    * with the normal of the control point before each. */
  std::vector<FrontVertex>
  stationsAlong (const std::vector<FrontVertex> &run, bool closed_run,
                 std::vector<Eigen::Vector3f> &fallback_normals) const;

  /** Section 4.2: the samples of B along one run of C, appended to \a next. */
  void
  sampleAlongCurve (const std::vector<FrontVertex> &run, bool closed_run, PassState &pass, Front &next) const;

  static void
  count (Verdict verdict, ContractionStats &stats);

  /** Optimises a candidate grown from \a origin (a front vertex, or a point
    * of the control curve) and runs every check but the repulsion. */
  Verdict
  place (Eigen::Vector3f &position, const Eigen::Vector3f &origin, const Eigen::Vector3f &reference_normal,
         Eigen::Vector3f &normal) const;

  /** -1 concave, 0 flat, +1 convex; cached per surface point. */
  int
  curvatureSign (int index) const;

  /** setSignTowardsFront's test: point \a index (at \a q, unit \a normal),
    * labelled \a sign, would reject a sample grown from \a origin; does its
    * plane bound another face? */
  bool
  boundsAnotherFace (int index, const Eigen::Vector3f &q, const Eigen::Vector3f &normal,
                     const Eigen::Vector3f &origin, int sign) const;

  /** How steeply the input points of convex point \a index's own face
    * (normals within kCreaseNormalDifference of its unit \a normal, within
    * the constraint's reach, on the side of \a towards) rise above its
    * tangent plane at \a q, beyond the tolerance and beyond the height of
    * the point under each neighbour's own plane: the largest (height -
    * that - tolerance) / distance, at least 0. A tilted normal gives a
    * slope; a face that curves up for real gives none. */
  float
  ownFaceSlope (int index, const Eigen::Vector3f &q, const Eigen::Vector3f &normal,
                const Eigen::Vector3f &towards) const;

  /** Weighted mean height of the surface points within the constraint's
    * reach of point \a index over its tangent plane, of all of them (\a
    * towards null) or of those on the side of *towards (a positive component
    * along *towards minus the point; not cached), as a sign like curvatureSign's. */
  int
  signOfMeanHeight (int index, const Eigen::Vector3f *towards) const;

  /** The combination constraint of section 4.4: does a sample at \a position
    * lie past the tangent plane of a convex (below it) or concave (above it)
    * reference point within the constraint's reach, by more than the
    * tolerance? Such a sample overshoots an edge the rim shows. A convex
    * point bounds only beyond its own face's rise (ownFaceSlope). \a around:
    * the oriented points within r of \a position (optimisePosition's; the
    * constraint's reach is at most r, and an unoriented point bounds nothing). */
  bool
  breaksCombinationConstraint (const Eigen::Vector3f &position, const Eigen::Vector3f &origin,
                               const Neighbourhood &around) const;
  /** Above one of the rim planes of setRimPlanes? */
  bool
  aboveRimPlanes (const Eigen::Vector3f &position) const;

  /** The constraint's reach: its radius, at most r. */
  float
  constraintReach () const
  {
    const float r = propagation_.getRadius ();
    return constraint_radius_ > 0.f ? std::min (constraint_radius_, r) : r;
  }

  NormalPropagation<PointT> propagation_;
  float equilibrium_distance_ = 0.f;
  float tolerance_ = 0.f;
  float slope_ = 0.f;
  std::size_t points_before_front_ = 0;  //!< the cloud's points when set: input (and earlier holes' fill)
  float sign_tolerance_ = 0.f;
  float constraint_radius_ = 0.f;
  Eigen::Vector3f constraint_facing_ = Eigen::Vector3f::Zero ();
  int threads_ = 1;
  bool combination_constraint_ = true;
  bool sign_towards_front_ = false;
  Eigen::Vector3f bound_centre_ = Eigen::Vector3f::Zero ();
  float bound_radius_ = 0.f;
  std::vector<Eigen::Vector3f> rim_;
  std::vector<Eigen::Vector3f> rim_plane_points_, rim_plane_normals_;
  std::vector<CreaseChord> crease_chords_;
  float crease_tolerance_ = 0.f;
  float rim_plane_tolerance_ = 0.f, rim_plane_slope_ = 0.f;
  Eigen::Vector3f rim_axis_ = Eigen::Vector3f::UnitZ ();
  float max_rim_gap_along_axis_ = 0.f, max_rim_gap_along_normal_ = 0.f;
  Eigen::Vector3f inward_centre_ = Eigen::Vector3f::Zero ();
  bool has_inward_centre_ = false;
  mutable std::vector<signed char> curvature_signs_;  //!< 2 = not computed yet
};

}  // namespace pcl_holefill::detail

#ifdef PCL_NO_PRECOMPILE
#include <pcl_holefill/detail/elastic_sampler.hpp>
#endif
