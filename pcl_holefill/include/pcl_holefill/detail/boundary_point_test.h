/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <vector>

namespace pcl_holefill::detail
{
/** \brief The widest empty sector around a point, seen in its tangent plane. */
struct AngularGap
{
  float angle = 0.f;                                    //!< radians, 0..2pi
  Eigen::Vector3f direction = Eigen::Vector3f::Zero (); //!< unit, tangent, bisects the gap
};

/** \brief Where a neighbour at \a offset from a point would lie in the
  * point's tangent plane if the surface between them were flattened. On a
  * smooth patch this is the plain projection; beyond a sharp edge (normals
  * more than ~12 degrees apart) the neighbour's height is laid out towards
  * the edge, so it keeps its true distance and lands beyond the edge instead
  * of being squeezed onto it. */
inline Eigen::Vector3f
unfoldIntoTangentPlane (const Eigen::Vector3f &offset, const Eigen::Vector3f &unit_normal,
                        const Eigen::Vector3f &neighbour_normal)
{
  const float height = offset.dot (unit_normal);
  Eigen::Vector3f unfolded = offset - height * unit_normal;
  // The tangent part of the neighbour's normal points towards the edge on a
  // convex edge and away from it on a concave one; -height has the matching sign.
  const float along = neighbour_normal.dot (unit_normal);
  const float tilt_sqr = neighbour_normal.squaredNorm () - along * along;
  if (tilt_sqr > 0.04f)  // |tilt| > 0.2: more than ~12 degrees
    unfolded -= height * (neighbour_normal - along * unit_normal) / std::sqrt (tilt_sqr);
  return unfolded;
}

// The two faces of a thin part (a sheet, a wall scanned from both sides)
// are parallel: normals within 14 degrees of opposite. Not 150 degrees: the
// noisy PCA normals on both sides of fandisk's acute edge counted as a
// sheet, and the corner hole there lost rim points (max error 0.015 ->
// 0.029 at 0.3 % noise).
constexpr float kOppositeNormalCosine = -0.97f;
// The empty-disc test leaves out neighbours whose normals are more opposed
// than this (cosine) to the point's: the other side of a thin part.
constexpr float kOtherSideCosine = -0.3f;
// A neighbour of the other face lies below the tangent plane by at least
// this share of its distance (a sheet as thick as 0.3 pitch, seen from 2
// pitches); a normal flipped by a bad orientation lies about in the plane
// (below it by distance / 2R on a curve of radius R).
constexpr float kMinDepthSlope = 0.15f;

/** \brief Whether a neighbour at \a offset lies on the other side of a thin
  * part rather than on the point's own surface: behind the point's tangent
  * plane (kMinDepthSlope) with a normal facing the other way
  * (kOppositeNormalCosine). Unfolding cannot lay such a neighbour beside the
  * point (a parallel face has no edge to unfold across), so its plain
  * projection would stand in for surface that is missing: on a sheet one
  * pitch thick a hole in one face was hidden by the face below. A neighbour
  * across a sharp edge stays. */
inline bool
onOtherSideOfThinPart (const Eigen::Vector3f &offset, const Eigen::Vector3f &unit_normal,
                       const Eigen::Vector3f &neighbour_normal)
{
  return neighbour_normal.dot (unit_normal) < kOppositeNormalCosine &&
         offset.dot (unit_normal) < -kMinDepthSlope * offset.norm ();
}

/** \brief The sampling pitch at a point, sqrt(surface area per point), from
  * its \a count nearest neighbours, the farthest at squared distance
  * \a farthest_sqr, which cover the disc of that radius less the empty sector
  * \a gap_angle (radians; 0 inside the surface). Unlike the nearest-neighbour
  * distance (about 0.5 pitch for uniformly random samples, 0.9 for
  * Poisson-disk, 1 for a grid) it means the same for every sampler. */
inline float
samplingPitch (float farthest_sqr, int count, float gap_angle)
{
  if (count < 2)
    return 0.f;
  // Area of the covered sector, r^2 (2 pi - gap) / 2, over the points in it
  // (count - 0.5: the farthest lies on the sector's edge).
  const float area = 0.5f * farthest_sqr * (2.f * static_cast<float> (M_PI) - gap_angle);
  return std::sqrt (area / (static_cast<float> (count) - 0.5f));
}

/** \brief The angular-gap boundary test (as PCL's BoundaryEstimation): the
  * neighbours are projected on the tangent plane of \a point and the largest
  * angle between consecutive ones is returned with its bisector, which points
  * into the missing surface.
  *
  * Where PCL projects every neighbour straight onto the tangent plane, this
  * test first unfolds neighbours that lie beyond a sharp edge (their normal
  * turns away by more than ~12 degrees) into the plane, as the surface would
  * lie if flattened: a plain projection squeezes the other face onto a thin
  * sliver next to the point and opens false gaps along every edge and corner
  * of a solid (PCL issue #5075). On smooth surfaces the two agree. Neighbours
  * that land on the point itself carry no direction and are ignored. At most
  * 64 neighbours are used.
  *
  * Gaps up to a right angle are not measured: when every 45 degree sector
  * around the point holds a neighbour (no gap can reach 90 degrees) the
  * result is pi/2 with an arbitrary direction, decided without sorting, the
  * common case of an interior point. Wider gaps are exact. */
AngularGap
largestAngularGap (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal,
                   const std::vector<Eigen::Vector3f> &neighbours,
                   const std::vector<Eigen::Vector3f> &neighbour_normals);

/** \brief The same test with the neighbours given as \a count indices into
  * \a positions and \a unit_normals (no copies: the hot path of detection). */
AngularGap
largestAngularGap (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal,
                   const Eigen::Vector3f *positions, const Eigen::Vector3f *unit_normals, const int *ids,
                   int count);

/** \brief The same test for a caller that reads only gaps wider than
  * \a threshold (radians, at least pi/2: the detection's angle threshold):
  * a narrower gap may come back as pi/2 or \a threshold. Such gaps are proven
  * narrower, without sorting, by which of 64 sectors hold a neighbour
  * direction (two consecutive directions lie at most a sector's start to
  * the next occupied sector's end apart). On a million uniformly random
  * samples the octant test above decides 31 % of the points, this proof
  * 37 %, the sort the other 33 %. Wider gaps are exact, as
  * largestAngularGap's. */
AngularGap
angularGapOver (float threshold, const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal,
                const Eigen::Vector3f *positions, const Eigen::Vector3f *unit_normals, const int *ids, int count);

/** \brief The empty-disc test: whether a disc of \a diameter, lying in the
  * tangent plane of \a point and touching it from the side of its widest
  * angular \a gap, holds none of the \a count neighbours given as \a ids
  * into \a positions and \a unit_normals.
  *
  * The neighbours are unfolded into the tangent plane as the angular-gap test
  * sees them; those whose normal faces away (the other side of a thin part)
  * are not surface next to the point and are ignored. The disc is tried along
  * the gap's bisector and leaning within the gap by up to 45 degrees; a
  * neighbour closer than \a test_radius (at most diameter / 2: the margin a
  * ragged rim needs) to its centre fills it.
  *
  * With \a unfold false the neighbours are projected straight onto the
  * plane normal to \a unit_normal (which then need not be the point's own
  * normal; the gap's direction is projected onto that plane too): the view
  * that does not trust the neighbours' normals.
  *
  * With \a over_other_face (a point on a thin part: its other side lies
  * among the point's nearest) the disc must also hold a point of the other
  * side: one face missing over the other is a hole; where both end together
  * (a sheet's edge, whose side strip a pitch wide has gaps of random
  * sampling, or a bore through it) the sheet ends, and nothing is missing
  * that the points can tell. */
bool
emptyDiscTouches (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal, const AngularGap &gap,
                  const Eigen::Vector3f *positions, const Eigen::Vector3f *unit_normals, const int *ids, int count,
                  float diameter, float test_radius, bool unfold = true, bool over_other_face = false);

/** \brief Whether the \a count neighbours given as \a ids into \a unit_normals
  * show one face besides the point's own at most: those turned further than
  * kSameFaceDegrees (crease_chords.h) from \a unit_normal all lie within that
  * angle of each other. False next to a corner (two other faces or more) and
  * on rough normals. */
bool
besideOneOtherFace (const Eigen::Vector3f &unit_normal, const Eigen::Vector3f *unit_normals, const int *ids, int count);

/** \brief A point lies on a thin part when at least this many of its k
  * nearest lie on the other side (onOtherSideOfThinPart; one may be a normal
  * flipped by noise) ... */
constexpr int kMinOtherSideNeighbours = 2;
/** \brief ... and they are at least this share of those facing the other
  * way: the other face of a sheet lies below the point, all of it; normals
  * flipped by noise lie above and below alike. */
constexpr float kMinOtherSideShare = 0.8f;

/** \brief The widest sector, seen from \a position in the plane normal to
  * \a normal, that holds none of the \a rim points (radians, 0..2 pi;
  * 2 pi when the rim is empty or on top of \a position). A point of the
  * surface a closed rim encloses sees the rim all around it (under pi, up to
  * pi on a straight stretch of it); a point past the rim sees it on one side
  * only. Resolution: 128 sectors of the circle, equal in diamond angle (the
  * enclosure test of ElasticSampler::setRim; no unfolding: the rim lies far
  * from the point, across any edge). */
float
rimGapAround (const Eigen::Vector3f &position, const Eigen::Vector3f &normal, const std::vector<Eigen::Vector3f> &rim);

}  // namespace pcl_holefill::detail
