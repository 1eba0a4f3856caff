/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/crease_chords.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <utility>

namespace pcl_holefill::detail
{
namespace
{
// The rim's normals are compared over kTurnWindow points on each side of a
// point, kTurnGap points away from it: PCA blends the normals of the faces
// over a pitch or two next to a crease, and the gap steps over that.
constexpr int kTurnWindow = 4;
constexpr int kTurnGap = 2;
// A turn over kTurnDegrees between the windows is a crease crossing ...
constexpr float kTurnDegrees = 40.f;
// ... if it is sharp: over kSharpness times the turn within either window
// (between the means of its halves). A rim around a smoothly curved part
// turns steadily, about four times as much between the windows as within
// one: a rim across a bore turned by 43 degrees there, no crease.
constexpr float kSharpness = 6.f;
// More crossings than this: a ragged rim, not a few faces.
constexpr std::size_t kMaxCrossings = 8;
// A chord shorter than this (in spacings) is a corner's, not a crease across the hole.
constexpr float kMinChordInSpacings = 3.f;
// A face that curves towards its normals by more than this (the mean rise
// of its rim points over each other's tangent planes, in spacings) does not
// hold the other face's front: its planes lie below that front. The flat
// face next to a bore or a bowl's inner wall is then kept by the chord;
// next to a flat or convex face it is not: that face's planes stop it,
// and a chord, straight where a convex crease bows out, would cut the
// face short of it (a cylinder's cap).
constexpr float kMinRiseInSpacings = 0.25f;
// The rise is measured over at most this many points of a face's arcs.
constexpr std::size_t kRiseSamples = 48;
// The crease between its crossings: this many segments of a curve, unless
// the crease's direction at a crossing turns from the chord by more than
// acos(kMinBendCosine) (60 degrees): then the chord.
constexpr int kBendSegments = 8;
constexpr float kMinBendCosine = 0.5f;
// A sample is held as a point of one face only where its normal's dot
// products with the faces' differ by more than this (30 degrees off the
// bisector at a right-angled crease): PCA tilts a face's normals towards
// the other's over a pitch or two next to the crease, and such a sample is
// left to the other constraints. (0.2 gave the same figures on every case
// measured.)
constexpr float kClearlyOneFace = 0.5f;
// Faces whose normals' difference or cross product is shorter than this
// are too alike to tell a side or a direction of the crease.
constexpr float kBetweenFaces = 0.2f;

float
cosine (float degrees)
{
  return std::cos (degrees * static_cast<float> (M_PI) / 180.f);
}

/** The sum of the normals of the \a count rim points from \a first on (cyclic). */
Eigen::Vector3f
normalSum (const std::vector<Eigen::Vector3f> &normals, int first, int count)
{
  const int n = static_cast<int> (normals.size ());
  Eigen::Vector3f sum = Eigen::Vector3f::Zero ();
  for (int k = 0; k < count; ++k)
    sum += normals[((first + k) % n + n) % n];
  return sum;
}

/** \a sum's direction (zero for a zero sum). */
Eigen::Vector3f
unitMean (const Eigen::Vector3f &sum)
{
  return sum.norm () > 0.f ? Eigen::Vector3f (sum.normalized ()) : Eigen::Vector3f::Zero ();
}

/** The unit mean normal of the window of kTurnWindow rim points from \a
  * first on, and the cosine of the turn within it (between its halves). */
Eigen::Vector3f
faceOfWindow (const std::vector<Eigen::Vector3f> &normals, int first, float &inner_cosine)
{
  const int half = kTurnWindow / 2;
  const Eigen::Vector3f a = unitMean (normalSum (normals, first, half));
  const Eigen::Vector3f b = unitMean (normalSum (normals, first + half, kTurnWindow - half));
  inner_cosine = a.dot (b);
  return unitMean (normalSum (normals, first, kTurnWindow));
}

float
angleOf (float cosine_value)
{
  return std::acos (std::clamp (cosine_value, -1.f, 1.f));
}

/** The cosine of the sharp turn of the normals at each rim point (1 where the turn is not sharp). */
std::vector<float>
turnCosines (const std::vector<Eigen::Vector3f> &normals)
{
  const int n = static_cast<int> (normals.size ());
  std::vector<float> turn (n, 1.f);
  for (int i = 0; i < n; ++i)
  {
    float inner_before = 1.f, inner_after = 1.f;
    const Eigen::Vector3f before = faceOfWindow (normals, i - kTurnGap - kTurnWindow + 1, inner_before);
    const Eigen::Vector3f after = faceOfWindow (normals, i + kTurnGap, inner_after);
    if (before.isZero () || after.isZero ())
      continue;
    const float between = before.dot (after);
    if (angleOf (between) > kSharpness * std::max (angleOf (inner_before), angleOf (inner_after)))
      turn[i] = between;
  }
  return turn;
}

/** How far, on average, the points of \a members lie above each other's
  * tangent planes: > 0 where the face curves towards its normals (a bore's
  * wall), < 0 where it curves away, 0 on a plane. */
float
riseOverTangentPlanes (const std::vector<Eigen::Vector3f> &positions, const std::vector<Eigen::Vector3f> &normals,
                       const std::vector<int> &members)
{
  const std::size_t step = std::max<std::size_t> (1, members.size () / kRiseSamples);
  double rise = 0.0;
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < members.size (); i += step)
    for (std::size_t j = 0; j < members.size (); j += step)
      if (i != j)
      {
        rise += (positions[members[j]] - positions[members[i]]).dot (normals[members[i]]);
        ++pairs;
      }
  return pairs > 0 ? static_cast<float> (rise / static_cast<double> (pairs)) : 0.f;
}

/** The rim points where the rim passes from one face to another: the
  * sharpest turn within kTurnGap + kTurnWindow on either side. */
std::vector<int>
crossings (const std::vector<float> &turn)
{
  const int n = static_cast<int> (turn.size ());
  const int reach = kTurnGap + kTurnWindow;
  std::vector<int> found;
  for (int i = 0; i < n; ++i)
  {
    if (!(turn[i] < cosine (kTurnDegrees)))
      continue;
    bool sharpest = true;
    for (int d = -reach; d <= reach && sharpest; ++d)
    {
      const int j = ((i + d) % n + n) % n;
      sharpest = d == 0 || turn[j] > turn[i] || (turn[j] == turn[i] && d > 0);
    }
    if (sharpest)
      found.push_back (i);
  }
  return found;
}

/** Where the rim crosses the crease found at rim point \a i: between the
  * first two points, from the window before on, whose normals are nearer
  * the face after than the face before (PCA blends the faces' normals
  * evenly over the crease, so that is where they are half-way). */
struct Crossing
{
  Eigen::Vector3f position, before, after;  //!< where, and the unit normals of the faces on either side
};

Crossing
crossingAt (const std::vector<Eigen::Vector3f> &positions, const std::vector<Eigen::Vector3f> &normals, int i)
{
  const int n = static_cast<int> (normals.size ());
  auto at = [n] (int k) { return ((k % n) + n) % n; };
  float unused = 1.f;
  const Eigen::Vector3f before = faceOfWindow (normals, i - kTurnGap - kTurnWindow + 1, unused);
  const Eigen::Vector3f after = faceOfWindow (normals, i + kTurnGap, unused);
  for (int k = i - kTurnGap + 1; k <= i + kTurnGap; ++k)
    if (normals[at (k)].dot (after) > normals[at (k)].dot (before))
      return {0.5f * (positions[at (k - 1)] + positions[at (k)]), before, after};
  return {positions[at (i)], before, after};
}

/** The crease from \a from to \a to as kBendSegments segments of a cubic
  * Hermite curve leaving \a from along the crease's direction there (the
  * faces' normals' cross product) and reaching \a to along it there: a
  * crease that bends (a bore's edge) is followed, not cut by its chord.
  * Each segment's side bisects the faces' normals, interpolated along the
  * crease. False (and \a chord untouched) where a direction is unclear. */
bool
bend (const Crossing &from, const Crossing &to, bool a_before_at_from, bool a_before_at_to, CreaseChord &chord)
{
  const Eigen::Vector3f a0 = a_before_at_from ? from.before : from.after, b0 = a_before_at_from ? from.after : from.before;
  const Eigen::Vector3f a1 = a_before_at_to ? to.before : to.after, b1 = a_before_at_to ? to.after : to.before;
  const Eigen::Vector3f along = to.position - from.position;
  const float length = along.norm ();
  Eigen::Vector3f t0 = a0.cross (b0), t1 = a1.cross (b1);
  if (!(t0.norm () > kBetweenFaces && t1.norm () > kBetweenFaces && length > 0.f))
    return false;
  t0 = t0.normalized () * (t0.dot (along) < 0.f ? -1.f : 1.f);
  t1 = t1.normalized () * (t1.dot (along) < 0.f ? -1.f : 1.f);
  if (t0.dot (along) < kMinBendCosine * length || t1.dot (along) < kMinBendCosine * length)
    return false;
  chord.bend_points.clear ();
  chord.bend_sides.clear ();
  chord.bend_normals_a.clear ();
  chord.bend_normals_b.clear ();
  for (int k = 0; k <= kBendSegments; ++k)
  {
    const float u = static_cast<float> (k) / kBendSegments;
    const float h00 = 2 * u * u * u - 3 * u * u + 1, h10 = u * u * u - 2 * u * u + u;
    const float h01 = -2 * u * u * u + 3 * u * u, h11 = u * u * u - u * u;
    chord.bend_points.push_back (h00 * from.position + h10 * length * t0 + h01 * to.position + h11 * length * t1);
  }
  for (int k = 0; k < kBendSegments; ++k)
  {
    const float u = (static_cast<float> (k) + 0.5f) / kBendSegments;
    const Eigen::Vector3f segment = (chord.bend_points[k + 1] - chord.bend_points[k]).normalized ();
    const Eigen::Vector3f a = ((1.f - u) * a0 + u * a1).normalized (), b = ((1.f - u) * b0 + u * b1).normalized ();
    chord.bend_normals_a.push_back (a);
    chord.bend_normals_b.push_back (b);
    Eigen::Vector3f side = a - b;
    side -= side.dot (segment) * segment;
    if (!(side.norm () > kBetweenFaces))
      return false;
    chord.bend_sides.push_back (side.dot (chord.side) < 0.f ? Eigen::Vector3f (-side.normalized ()) : side.normalized ());
  }
  return true;
}
}  // namespace

bool
CreaseChord::crossedBy (const Eigen::Vector3f &position, const Eigen::Vector3f &normal, float tolerance) const
{
  // The nearest piece of the crease: its side, and its faces' normals.
  Eigen::Vector3f origin = from, normal_of_side = side, face_a = normal_a, face_b = normal_b;
  float nearest = std::numeric_limits<float>::infinity ();
  for (std::size_t k = 0; k < bend_sides.size (); ++k)
  {
    const Eigen::Vector3f segment = bend_points[k + 1] - bend_points[k];
    const float t = std::clamp ((position - bend_points[k]).dot (segment) / std::max (segment.squaredNorm (), 1e-12f),
                                0.f, 1.f);
    const float distance = (position - (bend_points[k] + t * segment)).squaredNorm ();
    if (distance < nearest)
    {
      nearest = distance;
      origin = bend_points[k];
      normal_of_side = bend_sides[k];
      face_a = bend_normals_a[k];
      face_b = bend_normals_b[k];
    }
  }
  const float towards_a = normal.dot (face_a) - normal.dot (face_b);
  if (std::abs (towards_a) < kClearlyOneFace)
    return false;
  const float height = (position - origin).dot (normal_of_side);
  return towards_a > 0.f ? keeps_a && height < -tolerance : keeps_b && height > tolerance;
}

std::vector<CreaseChord>
findCreaseChords (const std::vector<Eigen::Vector3f> &positions, const std::vector<Eigen::Vector3f> &normals,
                  float spacing)
{
  const int n = static_cast<int> (positions.size ());
  if (n < 4 * (kTurnGap + kTurnWindow) || normals.size () != positions.size ())
    return {};
  const std::vector<int> at = crossings (turnCosines (normals));
  if (at.size () < 2 || at.size () > kMaxCrossings)
    return {};
  // The arcs between consecutive crossings, labelled by face.
  const std::size_t arcs = at.size ();
  std::vector<int> label (arcs);
  std::vector<Eigen::Vector3f> face_sums;
  for (std::size_t a = 0; a < arcs; ++a)
  {
    const int first = at[a] + 1, count = ((at[(a + 1) % arcs] - at[a]) % n + n) % n - 1;
    const Eigen::Vector3f sum = normalSum (normals, first, std::max (count, 0));
    label[a] = -1;
    for (std::size_t f = 0; f < face_sums.size () && label[a] < 0 && sum.norm () > 0.f; ++f)
      if (face_sums[f].normalized ().dot (sum.normalized ()) > sameFaceCosine ())
        label[a] = static_cast<int> (f);
    if (label[a] < 0)
    {
      label[a] = static_cast<int> (face_sums.size ());
      face_sums.push_back (Eigen::Vector3f::Zero ());
    }
    face_sums[label[a]] += sum;
  }
  // Crossing c leads from arc c - 1 into arc c; a pair of faces met twice is a chord.
  std::map<std::pair<int, int>, std::vector<std::size_t>> met;
  for (std::size_t c = 0; c < arcs; ++c)
  {
    const int a = label[(c + arcs - 1) % arcs], b = label[c];
    if (a != b)
      met[{std::min (a, b), std::max (a, b)}].push_back (c);
  }
  std::vector<std::vector<int>> members (face_sums.size ());
  for (std::size_t a = 0; a < arcs; ++a)
  {
    const int count = ((at[(a + 1) % arcs] - at[a]) % n + n) % n;
    for (int k = 1; k < count; ++k)
      members[label[a]].push_back ((at[a] + k) % n);
  }
  std::vector<CreaseChord> chords;
  for (const auto &[faces, where] : met)
  {
    if (where.size () != 2 || !(face_sums[faces.first].norm () > 0.f) || !(face_sums[faces.second].norm () > 0.f))
      continue;
    CreaseChord chord;
    const Crossing from = crossingAt (positions, normals, at[where[0]]);
    const Crossing to = crossingAt (positions, normals, at[where[1]]);
    chord.from = from.position;
    chord.to = to.position;
    const Eigen::Vector3f along = chord.to - chord.from;
    if (!(along.norm () >= kMinChordInSpacings * spacing))
      continue;
    chord.normal_a = face_sums[faces.first].normalized ();
    chord.normal_b = face_sums[faces.second].normalized ();
    Eigen::Vector3f side = chord.normal_a - chord.normal_b;
    side -= side.dot (along.normalized ()) * along.normalized ();
    if (!(side.norm () > kBetweenFaces))
      continue;
    chord.side = side.normalized ();
    // The plane must part the faces' rim arcs: A's above it, B's below.
    float height_a = 0.f, height_b = 0.f;
    for (std::size_t a = 0; a < arcs; ++a)
    {
      const int count = ((at[(a + 1) % arcs] - at[a]) % n + n) % n;
      float &height = label[a] == faces.first ? height_a : height_b;
      if (label[a] != faces.first && label[a] != faces.second)
        continue;
      for (int k = 1; k < count; ++k)
        height += (positions[(at[a] + k) % n] - chord.from).dot (chord.side);
    }
    if (height_a < 0.f)
    {
      chord.side = -chord.side;
      height_a = -height_a;
      height_b = -height_b;
    }
    const float rise_a = riseOverTangentPlanes (positions, normals, members[faces.first]);
    const float rise_b = riseOverTangentPlanes (positions, normals, members[faces.second]);
    chord.keeps_a = rise_b > kMinRiseInSpacings * spacing;
    chord.keeps_b = rise_a > kMinRiseInSpacings * spacing;
    if (!(height_a > 0.f && height_b < 0.f && (chord.keeps_a || chord.keeps_b)))
      continue;
    bend (from, to, label[(where[0] + arcs - 1) % arcs] == faces.first,
          label[(where[1] + arcs - 1) % arcs] == faces.first, chord);
    chords.push_back (chord);
  }
  return chords;
}

float
sameFaceCosine ()
{
  return cosine (kSameFaceDegrees);
}

}  // namespace pcl_holefill::detail
