/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/boundary_point_test.h>
#include <pcl_holefill/detail/crease_chords.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <vector>

namespace pcl_holefill::detail
{
namespace
{
/** A number that grows with the angle of the 2D vector (x, y) from 0 to
  * 2 pi, without trigonometry ("diamond angle", 0..4; any length but 0):
  * per quadrant y / (x + y), 1 - x / (y - x), 2 + y / (x + y), 3 - x / (y - x).
  * One division and no branch: the quadrant of a neighbour or a rim point
  * is a coin toss, and branching on it mispredicted half the time. */
inline float
diamondAngle (float x, float y)
{
  const bool upper = y >= 0.f;
  const bool first = upper && x >= 0.f, third = !upper && x < 0.f;
  const bool y_over_sum = first || third;
  const float ratio = (y_over_sum ? y : x) / (y_over_sum ? x + y : y - x);
  const float base = upper ? (first ? 0.f : 1.f) : (third ? 2.f : 3.f);
  return y_over_sum ? base + ratio : base - ratio;
}

/** Whether the counter-clockwise turn from a to b is under half a turn,
  * given \a step, b's diamond angle less a's (0..4, a unit per quarter
  * turn). The sign of the cross product alone cannot tell for about
  * parallel directions: the neighbours on one scan line lie on one straight
  * line, their directions equal up to rounding, and for some orders of the
  * neighbours the rounding put one a whole turn past the other, a 2 pi gap
  * in the middle of a scanned face (a false hole at a box's edge). Within
  * a unit of diamond angle the turn is under half a turn, beyond three
  * units over it. */
inline bool
underHalfTurn (const Eigen::Vector2f &a, const Eigen::Vector2f &b, float step)
{
  return step < 1.f || (step <= 3.f && a.x () * b.y () - a.y () * b.x () >= 0.f);
}

/** A number that grows with the counter-clockwise angle from unit a to unit
  * b over [0, 2 pi), without trigonometry; \a step as for underHalfTurn. */
inline float
turnKey (const Eigen::Vector2f &a, const Eigen::Vector2f &b, float step)
{
  const float dot = a.dot (b);
  return underHalfTurn (a, b, step) ? 1.f - dot : 3.f + dot;
}
constexpr int kRimSectors = 128;

// The true angle of each sector boundary: the sectors are equal in diamond angle.
const std::array<float, kRimSectors + 1> &
sectorBoundaryAngles ()
{
  static const std::array<float, kRimSectors + 1> angles = [] {
    std::array<float, kRimSectors + 1> a{};
    for (int k = 0; k <= kRimSectors; ++k)
    {
      const float d = 4.f * static_cast<float> (k) / kRimSectors;
      const int quadrant = std::min (3, static_cast<int> (d));
      const float f = d - static_cast<float> (quadrant);
      a[k] = static_cast<float> (quadrant) * static_cast<float> (M_PI / 2.0) + std::atan2 (f, 1.f - f);
    }
    return a;
  }();
  return angles;
}

/** The lowest set bit's place in \a bits (not 0). */
inline int
lowestBit (std::uint64_t bits)
{
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_ctzll (bits);
#else
  int place = 0;
  for (; !(bits & 1u); bits >>= 1)
    ++place;
  return place;
#endif
}

// The sector proof uses 64 sectors, equal in diamond angle (each two of the
// table's): 3.6 to 7.2 degrees wide.
constexpr int kProofSectors = 64;

/** The sector of 64 that a direction of diamond angle \a key (0..4) lies in. */
inline int
proofSector (float key)
{
  return std::clamp (static_cast<int> (key * (kProofSectors / 4.f)), 0, kProofSectors - 1);
}

/** Whether the directions in the sectors set in \a occupied leave no gap
  * as wide as \a limit (radians): two angularly consecutive directions lie
  * in consecutive occupied sectors, so they are at most as far apart as the
  * first sector's start and the second's end. A margin keeps the diamond
  * angle's rounding at a sector's edge on the safe side. */
bool
sectorsProveNarrower (std::uint64_t occupied, float limit)
{
  if (occupied == 0)
    return false;
  const auto &boundary = sectorBoundaryAngles ();
  const auto start = [&] (int sector) { return boundary[2 * sector]; };
  const float bound = limit - 1e-4f;
  const int first = lowestBit (occupied);
  int previous = first;
  for (std::uint64_t rest = occupied & (occupied - 1); rest != 0; rest &= rest - 1)
  {
    const int sector = lowestBit (rest);
    if (start (sector + 1) - start (previous) >= bound)
      return false;
    previous = sector;
  }
  return start (first + 1) + static_cast<float> (2.0 * M_PI) - start (previous) < bound;
}

// The disc may lean this far (radians) from the gap's bisector ...
constexpr float kDiscLeans[] = {0.f, 0.26f, -0.26f, 0.52f, -0.52f, 0.79f, -0.79f};
// ... while staying this far (radians) inside the gap.
constexpr float kDiscLeanMargin = 0.17f;
}  // namespace

bool
emptyDiscTouches (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal, const AngularGap &gap,
                  const Eigen::Vector3f *positions, const Eigen::Vector3f *unit_normals, const int *ids, int count,
                  float diameter, float test_radius, bool unfold, bool over_other_face)
{
  const float radius = 0.5f * diameter;
  thread_local std::vector<Eigen::Vector2f> flat, other_face;
  flat.clear ();
  other_face.clear ();
  // The gap's direction is tangent to the point's own plane; another plane
  // gets its projection.
  const Eigen::Vector3f along_gap =
      unfold ? gap.direction : Eigen::Vector3f (gap.direction - gap.direction.dot (unit_normal) * unit_normal);
  if (!(along_gap.squaredNorm () > 1e-6f))
    return false;  // the gap lies across the plane: no disc in it
  const Eigen::Vector3f e1 = unfold ? along_gap : along_gap.normalized ();
  const Eigen::Vector3f e2 = unit_normal.cross (e1);
  for (int k = 0; k < count; ++k)
  {
    const int j = ids[k];
    const Eigen::Vector3f offset = positions[j] - point;
    if (unit_normals[j].dot (unit_normal) < kOtherSideCosine)
    {
      if (over_other_face)
      {
        const Eigen::Vector3f below (offset - offset.dot (unit_normal) * unit_normal);
        other_face.emplace_back (below.dot (e1), below.dot (e2));
      }
      continue;
    }
    const Eigen::Vector3f u = unfold ? unfoldIntoTangentPlane (offset, unit_normal, unit_normals[j])
                                     : Eigen::Vector3f (offset - offset.dot (unit_normal) * unit_normal);
    flat.emplace_back (u.dot (e1), u.dot (e2));
  }
  const float max_lean = std::max (0.f, 0.5f * gap.angle - kDiscLeanMargin);
  for (const float lean : kDiscLeans)
  {
    if (std::abs (lean) > max_lean)
      continue;
    const Eigen::Vector2f centre = radius * Eigen::Vector2f (std::cos (lean), std::sin (lean));
    const auto inside = [&] (const Eigen::Vector2f &u) { return (u - centre).squaredNorm () < test_radius * test_radius; };
    if (std::none_of (flat.begin (), flat.end (), inside) &&
        (!over_other_face || std::any_of (other_face.begin (), other_face.end (), inside)))
      return true;
  }
  return false;
}

AngularGap
largestAngularGap (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal,
                   const std::vector<Eigen::Vector3f> &neighbours,
                   const std::vector<Eigen::Vector3f> &neighbour_normals)
{
  int ids[64];
  const int count = static_cast<int> (std::min<std::size_t> (neighbours.size (), 64));
  for (int i = 0; i < count; ++i)
    ids[i] = i;
  return largestAngularGap (point, unit_normal, neighbours.data (), neighbour_normals.data (), ids, count);
}

namespace
{
/** largestAngularGap; with \a read_over above 0, a gap that the occupied
  * sectors prove narrower than it (at least pi/2) comes back as read_over. */
AngularGap
measureAngularGap (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal,
                   const Eigen::Vector3f *positions, const Eigen::Vector3f *unit_normals, const int *ids,
                   int count_given, float read_over)
{
  AngularGap gap;
  const Eigen::Vector3f u = unit_normal.unitOrthogonal ();
  const Eigen::Vector3f v = unit_normal.cross (u);
  const int count_in = std::min (count_given, 64);
  Eigen::Vector2f flat[64];
  unsigned octants = 0;
  for (int i = 0; i < count_in; ++i)
  {
    const Eigen::Vector3f d = unfoldIntoTangentPlane (positions[ids[i]] - point, unit_normal, unit_normals[ids[i]]);
    flat[i] = Eigen::Vector2f (d.dot (u), d.dot (v));
    const float x = flat[i].x (), y = flat[i].y ();
    octants |= 1u << ((y < 0.f ? 4 : 0) + ((x < 0.f) != (y < 0.f) ? 2 : 0) + (std::abs (x) < std::abs (y) ? 1 : 0));
    if (octants == 0xFFu)
    {
      // Every 45 degree sector holds a neighbour, so no gap reaches 90
      // degrees: the common case of an interior point, decided without
      // sorting, and without unfolding the neighbours left.
      gap.angle = static_cast<float> (M_PI / 2.0);
      gap.direction = u;
      return gap;
    }
  }
  float length[64];
  float reach = 0.f;
  for (int i = 0; i < count_in; ++i)
  {
    length[i] = flat[i].norm ();
    reach = std::max (reach, length[i]);
  }
  Eigen::Vector2f unsorted[64];
  float unsorted_key[64];
  int count = 0;
  std::uint64_t occupied = 0;
  for (int i = 0; i < count_in; ++i)
  {
    if (length[i] <= 1e-3f * reach)
      continue;  // on the normal line: no direction
    unsorted[count] = flat[i] / length[i];
    unsorted_key[count] = diamondAngle (unsorted[count].x (), unsorted[count].y ());
    occupied |= std::uint64_t{1} << proofSector (unsorted_key[count]);
    ++count;
  }
  if (read_over > 0.f && sectorsProveNarrower (occupied, read_over))
  {
    // 37 % of a random sampling's points (the octant test 31 %): not
    // sorted below.
    gap.angle = read_over;
    gap.direction = u;
    return gap;
  }
  // Directions, sorted by angle (insertion sort: at most 64 of them).
  Eigen::Vector2f direction[64];
  float order[64];
  for (int i = 0; i < count; ++i)
  {
    const float key = unsorted_key[i];
    int at = i;
    while (at > 0 && order[at - 1] > key)
    {
      order[at] = order[at - 1];
      direction[at] = direction[at - 1];
      --at;
    }
    order[at] = key;
    direction[at] = unsorted[i];
  }
  if (count == 0)
  {
    gap.angle = static_cast<float> (2.0 * M_PI);
    gap.direction = u;
    return gap;
  }
  // The widest turn between angularly consecutive directions (the last to the first wraps).
  const auto step_after = [&] (int i) { return i + 1 < count ? order[i + 1] - order[i] : order[0] + 4.f - order[i]; };
  int widest_from = count - 1;
  float widest_key = count == 1 ? 4.f : turnKey (direction[count - 1], direction[0], step_after (count - 1));
  for (int i = 0; i + 1 < count; ++i)
  {
    const float key = turnKey (direction[i], direction[i + 1], step_after (i));
    if (key > widest_key)
    {
      widest_key = key;
      widest_from = i;
    }
  }
  const Eigen::Vector2f &a = direction[widest_from];
  const Eigen::Vector2f &b = direction[(widest_from + 1) % count];
  constexpr float kFullTurn = static_cast<float> (2.0 * M_PI);
  float angle = kFullTurn;
  if (count > 1)
  {
    angle = std::atan2 (a.x () * b.y () - a.y () * b.x (), a.dot (b));
    if (angle < 0.f)
      angle += kFullTurn;
    // About parallel directions: no turn or a whole one, as their order
    // says (atan2 reads the rounding's side). Elsewhere atan2 is exact enough.
    const bool under_half = underHalfTurn (a, b, step_after (widest_from));
    if (under_half && angle > 0.75f * kFullTurn)
      angle = 0.f;
    else if (!under_half && angle < 0.25f * kFullTurn)
      angle = kFullTurn;
  }
  const float half = 0.5f * angle;
  const Eigen::Vector2f bisector = std::cos (half) * a + std::sin (half) * Eigen::Vector2f (-a.y (), a.x ());
  gap.angle = angle;
  gap.direction = (bisector.x () * u + bisector.y () * v).normalized ();
  return gap;
}
}  // namespace

AngularGap
largestAngularGap (const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal,
                   const Eigen::Vector3f *positions, const Eigen::Vector3f *unit_normals, const int *ids,
                   int count)
{
  return measureAngularGap (point, unit_normal, positions, unit_normals, ids, count, 0.f);
}

AngularGap
angularGapOver (float threshold, const Eigen::Vector3f &point, const Eigen::Vector3f &unit_normal,
                const Eigen::Vector3f *positions, const Eigen::Vector3f *unit_normals, const int *ids, int count)
{
  return measureAngularGap (point, unit_normal, positions, unit_normals, ids, count,
                            std::max (threshold, static_cast<float> (M_PI / 2.0)));
}

bool
besideOneOtherFace (const Eigen::Vector3f &unit_normal, const Eigen::Vector3f *unit_normals, const int *ids, int count)
{
  const float same_face = sameFaceCosine ();
  const Eigen::Vector3f *other = nullptr;
  for (int k = 0; k < count; ++k)
  {
    const Eigen::Vector3f &n = unit_normals[ids[k]];
    if (n.dot (unit_normal) > same_face)
      continue;
    if (other == nullptr)
      other = &n;
    else if (n.dot (*other) <= same_face)
      return false;
  }
  return true;
}

float
rimGapAround (const Eigen::Vector3f &position, const Eigen::Vector3f &normal, const std::vector<Eigen::Vector3f> &rim)
{
  const Eigen::Vector3f n = normal.normalized ();
  const Eigen::Vector3f u = n.unitOrthogonal (), v = n.cross (u);
  std::array<bool, kRimSectors> seen{};
  bool any = false;
  for (const auto &q : rim)
  {
    const Eigen::Vector3f d = q - position;
    const float a = d.dot (u), b = d.dot (v);
    if (!(a * a + b * b > 1e-12f * d.squaredNorm ()))
      continue;  // on top of the point, or straight above it
    const int sector = static_cast<int> (diamondAngle (a, b) * (kRimSectors / 4.f));
    seen[std::clamp (sector, 0, kRimSectors - 1)] = true;
    any = true;
  }
  if (!any)
    return static_cast<float> (2.0 * M_PI);
  // The widest run of empty sectors, around the circle, as a true angle.
  const auto &angle = sectorBoundaryAngles ();
  float widest = 0.f;
  for (int start = 0; start < kRimSectors; ++start)
  {
    if (seen[start] || !seen[(start + kRimSectors - 1) % kRimSectors])
      continue;  // runs are measured from their first sector
    int end = start;
    while (!seen[end % kRimSectors])
      ++end;
    const float from = angle[start], to = end > kRimSectors ? angle[end - kRimSectors] + static_cast<float> (2.0 * M_PI)
                                                             : angle[end];
    widest = std::max (widest, to - from);
  }
  return widest;
}

}  // namespace pcl_holefill::detail
