/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl_holefill::detail
{
/** Rim arcs (or rim points' planes) whose mean normals lie within this
  * angle of each other (degrees) are one face's. */
constexpr float kSameFaceDegrees = 25.f;

/** cos (kSameFaceDegrees): two unit normals with a larger dot product are
  * one face's. */
float
sameFaceCosine ();

/** \brief A crease that crosses a hole, as the rim shows it: the rim turns
  * from face A to face B at \a from and back at \a to, and the crease
  * inside the hole is taken as the chord between them.
  *
  * The plane through the chord whose normal \a side bisects the faces'
  * normals (A's side positive), or through the nearest piece of the crease
  * where it bends (bend_points), keeps each face's front on its side: without
  * it, a face whose neighbour across a convex edge curves towards its
  * normal (a bore's wall, a bowl's inner wall) grows on as a flat sheet
  * across the opening, as no tangent plane of the other face lies above it. */
struct CreaseChord
{
  Eigen::Vector3f from = Eigen::Vector3f::Zero ();
  Eigen::Vector3f to = Eigen::Vector3f::Zero ();
  Eigen::Vector3f side = Eigen::Vector3f::UnitZ ();      //!< unit, A's side positive
  Eigen::Vector3f normal_a = Eigen::Vector3f::UnitZ ();  //!< unit mean normals of the faces' rim arcs
  Eigen::Vector3f normal_b = Eigen::Vector3f::UnitZ ();
  /** Is face A's front held by the chord (face B curves towards its
    * normals, so that its tangent planes do not hold A), and B's? */
  bool keeps_a = true, keeps_b = true;
  /** The crease as it bends between the crossings (from ... to), and each
    * piece's side (unit, A's positive) and faces' normals (unit, from the
    * crossings' on); empty: the chord. */
  std::vector<Eigen::Vector3f> bend_points, bend_sides, bend_normals_a, bend_normals_b;

  /** Is a sample at \a position with unit normal \a normal a point of one
    * face on the other's side by more than \a tolerance? A sample whose
    * normal is between the two (on the crease) is not. */
  bool
  crossedBy (const Eigen::Vector3f &position, const Eigen::Vector3f &normal, float tolerance) const;
};

/** \brief The creases crossing the hole of the rim \a positions (in loop
  * order, the loop closed) with unit normals \a normals: where the rim's
  * normals turn by more than kCreaseTurnDegrees over a few points, the rim
  * passes from one face to another; two faces met at exactly two such
  * turns make a chord, which holds the front of a face whose neighbour
  * curves towards its normals. \a spacing (the rim's mean spacing) sets
  * the shortest chord and the least such curving. */
std::vector<CreaseChord>
findCreaseChords (const std::vector<Eigen::Vector3f> &positions, const std::vector<Eigen::Vector3f> &normals,
                  float spacing);

}  // namespace pcl_holefill::detail
