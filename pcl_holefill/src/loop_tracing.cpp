/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/boundary_point_test.h>
#include <pcl_holefill/detail/loop_tracing.h>
#include <pcl_holefill/detail/point_grid.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

namespace pcl_holefill::detail
{
// A loop is a border when the mean of its gaps' parts across the surface it
// spans, dotted with the direction to its centre, is under -kOpeningGapVote:
// outer borders of a flat patch, a saddle, a half cylinder measure -0.45 to
// -0.86; openings, whose gaps point along the walls, -0.01 to 0.01 (the sign
// of that decided before, and one cylinder was a border with exact normals
// and a hole without).
constexpr float kOpeningGapVote = 0.25f;
namespace
{
/** The link of points \a a and \a b: the longer of their own. */
float
pairLink (const std::vector<float> &links, int a, int b)
{
  return std::max (links[static_cast<std::size_t> (a)], links[static_cast<std::size_t> (b)]);
}

/** Keeps of \a near, the points found within the longest link of \a p,
  * those linked to \a p. */
void
keepLinked (std::vector<PointGrid::Neighbour> &near, const std::vector<float> &links, int p)
{
  near.erase (std::remove_if (near.begin (), near.end (),
                              [&] (const PointGrid::Neighbour &q) {
                                const float link = pairLink (links, p, q.id);
                                return q.sqr_distance > link * link;
                              }),
              near.end ());
}

/** Connected sets of points under "closer than their link". */
std::vector<std::vector<int>>
linkedSets (const PointGrid &grid, const std::vector<Eigen::Vector3f> &positions, const std::vector<float> &links,
            float longest)
{
  std::vector<int> label (positions.size (), -1);
  std::vector<std::vector<int>> sets;
  std::vector<PointGrid::Neighbour> near;
  for (std::size_t seed = 0; seed < positions.size (); ++seed)
  {
    if (label[seed] >= 0)
      continue;
    const int id = static_cast<int> (sets.size ());
    sets.emplace_back ();
    std::vector<int> stack{static_cast<int> (seed)};
    label[seed] = id;
    while (!stack.empty ())  // each point is pushed once: bounded
    {
      const int p = stack.back ();
      stack.pop_back ();
      sets[id].push_back (p);
      grid.withinRadius (positions[p], longest, near);
      keepLinked (near, links, p);
      for (const auto &q : near)
        if (label[q.id] < 0)
        {
          label[q.id] = id;
          stack.push_back (q.id);
        }
    }
  }
  return sets;
}

std::vector<Eigen::Vector3f>
pathPositions (const std::vector<int> &path, const std::vector<Eigen::Vector3f> &positions)
{
  std::vector<Eigen::Vector3f> out;
  for (const int i : path)
    out.push_back (positions[i]);
  return out;
}

// A walk stuck within 2 links of its start closes only when it is no
// farther from the start than this share of the farthest it went. A
// straight piece is at 1 (noise: 0.95-1); 0.75 also refused small loops
// stuck across from home (a fandisk hole at noise 0.5 %, 4 % less covered).
constexpr float kMaxHomeShareWhenStuck = 0.9f;

// A walk back within a link of home closes only once it has been well away:
// home no farther than this share of the farthest it went. A rim about a
// link in radius (the apex of a pyramid at 0.3 % noise, 6 links round) was
// within a link of home after a quarter of the way, zigzagging between two
// rows: that quarter closed as a loop of its own, too small for a hole, and
// the rest was filled as a hole missing a quarter of its rim (90 % covered).
// On a circle 0.6 means at least 290 degrees walked.
constexpr float kMaxHomeShareToClose = 0.6f;

// Two rim points whose normals differ by more than 138.6 degrees lie on the
// two sides of a thin part: the walk neither steps nor closes across it.
// The end of a 0.04-thick fin is 5 pitches across, near the 4.5-pitch link:
// a walk from its lower rim went round the end face and "came home" to the
// upper rim (180 degrees), cutting one hole into two half-loops. Not 120
// degrees (-0.5), as it was: the faces of an acute edge, a star's tips of
// 44 degrees, have normals 136 degrees apart, and the rim of a hole across
// a tip came out as two open halves (a star prism's voxel-grid samples,
// bench/probe_check.py: 75.6 % covered, now 100 %). Tips down to 41.4
// degrees now link; the fast corpus bench (its fin included) is unchanged.
constexpr float kMinLinkNormalCosine = -0.75f;

// A point beside the walk's step is absorbed as a second row of its rim
// unless its gap faces away from the walking point's (gap directions' dot
// product under this): then it is the rim of another hole across a narrow
// bridge. Not 0: on noisy random samples (0.5 %, PCA normals) a second row
// whose gaps turned past a right angle, left unabsorbed, was walked as a
// false hole of its own.
constexpr float kMaxAbsorbedGapOpposition = -0.5f;

// Open pieces of one rim are joined across a gap of up to this many links.
// Noisy random samples leave gaps in a long rim: a cap of 0.3 cut from
// 100,000 random samples of a sphere at 0.1 % noise came out as two open
// pieces, 4.6 and 5.9 pitches apart at their ends (the link is 4.5), and
// the hole was not filled at all.
constexpr float kMaxJoinGapInLinks = 2.f;

/** Does the open \a closing path, its last point being a rim's end, close
  * as a loop: long, and ending near its start (the rule of a walk stuck next
  * to home)? */
bool
endsNearStart (const std::vector<int> &path, const std::vector<Eigen::Vector3f> &positions,
               const std::vector<float> &links)
{
  const float link = path.empty () ? 0.f : pairLink (links, path.front (), path.back ());
  return path.size () > 4 && loopLength (pathPositions (path, positions), false) > 3.f * link &&
         (positions[path.front ()] - positions[path.back ()]).norm () <= 2.f * link;
}

/** Joins the open loops whose pieces continue each other: the end of one
  * within kMaxJoinGapInLinks of the start of another, ahead of its walk,
  * on the same side of the surface; the shortest gaps first. A chain that
  * comes back near its start is a closed loop and takes no further piece.
  * One search per open loop, so a scan with many border pieces stays cheap. */
void
joinOpenPieces (std::vector<TracedLoop> &loops, const std::vector<Eigen::Vector3f> &positions,
                const std::vector<Eigen::Vector3f> &normals, const std::vector<Eigen::Vector3f> &tangents,
                const std::vector<float> &links, float longest)
{
  std::vector<std::size_t> open;
  std::vector<Eigen::Vector3f> starts;
  for (std::size_t l = 0; l < loops.size (); ++l)
    if (!loops[l].closed && !loops[l].members.empty ())
    {
      open.push_back (l);
      starts.push_back (positions[loops[l].members.front ()]);
    }
  if (open.size () < 2)
    return;
  const float reach = kMaxJoinGapInLinks * longest;
  PointGrid grid (reach);
  grid.build (starts);
  struct Join
  {
    float length;
    std::size_t from, to;  // loop indices: from's end, to's start
  };
  std::vector<Join> joins;
  std::vector<PointGrid::Neighbour> near;
  for (std::size_t x = 0; x < open.size (); ++x)
  {
    const int end = loops[open[x]].members.back ();
    grid.withinRadius (positions[end], reach, near);
    for (const auto &q : near)
    {
      const std::size_t to = open[static_cast<std::size_t> (q.id)];
      const int start = loops[to].members.front ();
      const float gap = kMaxJoinGapInLinks * pairLink (links, end, start);
      if (to != open[x] && q.sqr_distance <= gap * gap &&
          (positions[start] - positions[end]).dot (tangents[end]) > 0.f &&
          normals[end].dot (normals[start]) >= kMinLinkNormalCosine)
        joins.push_back ({std::sqrt (q.sqr_distance), open[x], to});
    }
  }
  std::sort (joins.begin (), joins.end (), [] (const Join &l, const Join &r) {
    return std::tie (l.length, l.from, l.to) < std::tie (r.length, r.from, r.to);
  });
  // Chains of pieces: the head of the chain a tail ends, the tail of a head's
  // chain; a piece is followed (its end taken) or preceded (its start) once.
  std::vector<std::size_t> head_of (loops.size ()), tail_of (loops.size ());
  std::vector<char> followed (loops.size (), 0), preceded (loops.size (), 0);
  for (std::size_t l = 0; l < loops.size (); ++l)
    head_of[l] = tail_of[l] = l;
  for (const Join &join : joins)
  {
    const std::size_t head = head_of[join.from];
    if (followed[join.from] || preceded[join.to] || head == join.to || loops[head].closed)
      continue;
    const std::size_t tail = tail_of[join.to];
    auto &chain = loops[head].members;
    chain.insert (chain.end (), loops[join.to].members.begin (), loops[join.to].members.end ());
    loops[join.to].members.clear ();
    followed[join.from] = preceded[join.to] = 1;
    head_of[tail] = head;
    tail_of[head] = tail;
    loops[head].closed = endsNearStart (chain, positions, links);
  }
  loops.erase (std::remove_if (loops.begin (), loops.end (), [] (const TracedLoop &l) { return l.members.empty (); }),
               loops.end ());
}

/** Walks one linked set from \a start. Returns the ordered path. */
std::vector<int>
walk (int start, float sense, const std::vector<Eigen::Vector3f> &positions,
      const std::vector<Eigen::Vector3f> &normals, const std::vector<Eigen::Vector3f> &tangents,
      const std::vector<Eigen::Vector3f> &gap_directions, const PointGrid &grid, const std::vector<float> &links,
      float longest, std::vector<char> &visited, bool &closed)
{
  std::vector<int> path{start};
  visited[start] = 1;
  closed = false;
  std::vector<PointGrid::Neighbour> near;
  Eigen::Vector3f heading = sense * tangents[start];
  int current = start;
  float travelled = 0.f, farthest = 0.f;
  const std::size_t bound = positions.size ();
  for (std::size_t step = 0; step < bound; ++step)
  {
    grid.withinRadius (positions[current], longest, near);
    keepLinked (near, links, current);
    // The thresholds of closing, in links: the longer of start's and current's.
    const float link = pairLink (links, start, current);
    std::sort (near.begin (), near.end (), [] (const auto &a, const auto &b) {
      return a.sqr_distance < b.sqr_distance || (a.sqr_distance == b.sqr_distance && a.id < b.id);
    });
    // Back home, once the walk has gone well away from it?
    const float home = (positions[start] - positions[current]).norm ();
    farthest = std::max (farthest, home);
    const bool same_side = normals[current].dot (normals[start]) >= kMinLinkNormalCosine;
    if (travelled > 2.f * link && home <= link && home <= kMaxHomeShareToClose * farthest && same_side)
    {
      closed = true;
      break;
    }
    // The next point: near and ahead of the walk, seen flattened (a rim that
    // turns over a sharp edge still lies ahead), allowed to turn up to a bit
    // past a right angle (corners of a border), and with its rim running the
    // same way, so the walk never jumps to the facing side of a narrow hole.
    int next = -1;
    float best_score = std::numeric_limits<float>::max ();
    for (const auto &q : near)
    {
      if (visited[q.id] || q.id == current || normals[current].dot (normals[q.id]) < kMinLinkNormalCosine)
        continue;
      const Eigen::Vector3f d =
          unfoldIntoTangentPlane (positions[q.id] - positions[current], normals[current], normals[q.id]);
      const float len = d.norm ();
      if (!(len > 0.f) || sense * tangents[q.id].dot (heading) <= -0.5f)
        continue;
      const float cosine = d.dot (heading) / len;
      // Of two rows of rim points, keep to the outer one (towards the gap).
      const float score = len * (1.5f - cosine) - 0.5f * d.dot (gap_directions[current]);
      if (cosine > -0.2f && score < best_score)
      {
        best_score = score;
        next = q.id;
      }
    }
    if (next < 0)
    {
      // Stuck next to home, its last neighbours absorbed: that closes too,
      // if the walk has turned back towards home. A straight piece of rim
      // that ends 2 links from its start has not: on a noisy cube edge one
      // such piece (6 points, 0.15 long) was taken for a whole hole, and the
      // rest of the rim left as an open border.
      closed = travelled > 2.f * link && home <= 2.f * link && home <= kMaxHomeShareWhenStuck * farthest && same_side;
      break;
    }
    // Absorb the points beside or behind the step: a second row of the rim.
    // Not the rim across a bridge a pitch or two wide between two holes,
    // whose gaps face the other way: absorbed, it left the other hole's walk
    // stuck at both ends of the bridge, an open piece taken for a border
    // (two holes 12 pitches across, random samples, bridges of 1-3 pitches:
    // one of the two found).
    const Eigen::Vector3f step_dir = (positions[next] - positions[current]).normalized ();
    const auto second_row = [&] (const PointGrid::Neighbour &q) {
      const bool beside_or_behind = (positions[q.id] - positions[current]).dot (step_dir) <= 0.5f * std::sqrt (q.sqr_distance);
      const bool same_side = gap_directions[q.id].dot (gap_directions[current]) > kMaxAbsorbedGapOpposition;
      const float row_link = pairLink (links, current, q.id);
      return beside_or_behind && q.sqr_distance <= 0.25f * row_link * row_link && same_side;
    };
    for (const auto &q : near)
      if (!visited[q.id] && second_row (q))
        visited[q.id] = 1;
    visited[next] = 1;
    travelled += (positions[next] - positions[current]).norm ();
    path.push_back (next);
    // The heading follows the rim, smoothed so that one jagged step cannot
    // turn it, and is laid into the new point's tangent plane (edges).
    Eigen::Vector3f blended = heading + (sense * tangents[next] + step_dir).normalized ();
    blended -= blended.dot (normals[next]) * normals[next];
    heading = blended.norm () > 1e-6f ? blended.normalized () : Eigen::Vector3f (sense * tangents[next]);
    current = next;
  }
  return path;
}
}  // namespace

std::vector<TracedLoop>
traceBoundaryLoops (const std::vector<Eigen::Vector3f> &positions,
                    const std::vector<Eigen::Vector3f> &normals,
                    const std::vector<Eigen::Vector3f> &gap_directions,
                    const std::vector<float> &link_distances, int min_points)
{
  std::vector<TracedLoop> loops;
  if (positions.empty () || link_distances.size () != positions.size () ||
      !std::all_of (link_distances.begin (), link_distances.end (), [] (float l) { return l > 0.f && std::isfinite (l); }))
    return loops;
  const float longest = *std::max_element (link_distances.begin (), link_distances.end ());
  PointGrid grid (longest);
  grid.build (positions);
  std::vector<Eigen::Vector3f> tangents (positions.size ());
  // Walking along n x g keeps the missing surface on the right-hand side.
  for (std::size_t i = 0; i < positions.size (); ++i)
    tangents[i] = normals[i].cross (gap_directions[i]).normalized ();
  std::vector<char> visited (positions.size (), 0);
  for (const auto &set : linkedSets (grid, positions, link_distances, longest))
  {
    if (static_cast<int> (set.size ()) < min_points)
      continue;
    // Walks may leave points of a wide rim unvisited: start again from those
    // still far from any walked point, a bounded number of times.
    for (std::size_t attempt = 0; attempt < set.size (); ++attempt)
    {
      const auto fresh = std::find_if (set.begin (), set.end (), [&] (int p) { return !visited[p]; });
      if (fresh == set.end ())
        break;
      bool closed = false;
      std::vector<int> forward =
          walk (*fresh, 1.f, positions, normals, tangents, gap_directions, grid, link_distances, longest, visited, closed);
      if (!closed)
      {
        // An open rim: the start may be mid-way, so extend backwards too.
        bool ignored = false;
        std::vector<int> backward = walk (*fresh, -1.f, positions, normals, tangents, gap_directions, grid,
                                          link_distances, longest, visited, ignored);
        std::reverse (backward.begin (), backward.end ());
        backward.pop_back ();  // the start, already in forward
        backward.insert (backward.end (), forward.begin (), forward.end ());
        forward.swap (backward);
        // Both walks went round and met: a loop after all (a sharp corner, or
        // the last points absorbed by a ragged rim, stopped one). The ends may
        // be as far apart as a walk stuck next to home is allowed to be.
        closed = endsNearStart (forward, positions, link_distances);
      }
      if (static_cast<int> (forward.size ()) >= min_points)
        loops.push_back ({forward, closed});
    }
  }
  joinOpenPieces (loops, positions, normals, tangents, link_distances, longest);
  return loops;
}

std::vector<int>
refineByMidpoints (const std::vector<int> &features, bool closed,
                   const std::function<Eigen::Vector3f (int)> &position_of,
                   const std::function<int (const Eigen::Vector3f &, int, int)> &nearest_index,
                   std::size_t max_points)
{
  std::vector<int> result;
  if (features.empty ())
    return result;
  std::set<int> used (features.begin (), features.end ());
  const std::size_t segments = closed ? features.size () : features.size () - 1;
  result.push_back (features[0]);
  for (std::size_t s = 0; s < segments; ++s)
  {
    const int a = features[s];
    const int b = features[(s + 1) % features.size ()];
    // Depth-first over sub-segments, left half first, so insertions come out in order.
    std::vector<std::pair<int, int>> stack{{a, b}};
    std::vector<int> piece;
    while (!stack.empty () && used.size () < max_points)
    {
      const auto [from, to] = stack.back ();
      stack.pop_back ();
      if (from < 0)  // a marker: emit the point 'to'
      {
        piece.push_back (to);
        continue;
      }
      const int m = nearest_index (0.5f * (position_of (from) + position_of (to)), from, to);
      if (m < 0 || used.count (m))
        continue;
      used.insert (m);
      // Process (from, m), then emit m, then (m, to).
      stack.push_back ({m, to});
      stack.push_back ({-1, m});
      stack.push_back ({from, m});
    }
    result.insert (result.end (), piece.begin (), piece.end ());
    if (closed && s + 1 == segments)
      break;  // b is features[0], already first
    result.push_back (b);
  }
  return result;
}

Eigen::Vector3f
vectorArea (const std::vector<Eigen::Vector3f> &loop_positions)
{
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero ();
  for (const auto &p : loop_positions)
    centroid += p;
  centroid /= static_cast<float> (std::max<std::size_t> (1, loop_positions.size ()));
  Eigen::Vector3f area = Eigen::Vector3f::Zero ();
  for (std::size_t i = 0; i < loop_positions.size (); ++i)
  {
    const auto &next = loop_positions[(i + 1) % loop_positions.size ()];
    area += 0.5f * (loop_positions[i] - centroid).cross (next - centroid);
  }
  return area;
}

bool
gapsPointInside (const std::vector<Eigen::Vector3f> &loop_positions,
                 const std::vector<Eigen::Vector3f> &loop_gap_directions)
{
  if (loop_positions.empty ())
    return false;
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero ();
  for (const auto &p : loop_positions)
    centroid += p;
  centroid /= static_cast<float> (loop_positions.size ());
  // Only the gaps' parts across the surface the loop spans: at an opening
  // (the end of a tube, a box without its lid) the gaps point along the
  // walls, out of that surface, and what is left of them is small either way.
  const Eigen::Vector3f area = vectorArea (loop_positions);
  const Eigen::Vector3f axis = area.norm () > 0.f ? Eigen::Vector3f (area.normalized ()) : Eigen::Vector3f::Zero ();
  float vote = 0.f;
  for (std::size_t i = 0; i < loop_positions.size (); ++i)
  {
    const Eigen::Vector3f to_centre = centroid - loop_positions[i];
    const float len = to_centre.norm ();
    if (len > 0.f)
    {
      const Eigen::Vector3f gap = loop_gap_directions[i] - loop_gap_directions[i].dot (axis) * axis;
      vote += gap.dot (to_centre / len);
    }
  }
  vote /= static_cast<float> (loop_positions.size ());
  return vote >= -kOpeningGapVote;
}

float
loopDiameter (const std::vector<Eigen::Vector3f> &loop_positions)
{
  const std::size_t n = loop_positions.size ();
  const std::size_t stride = std::max<std::size_t> (1, n / 2000);
  float best = 0.f;
  for (std::size_t i = 0; i < n; i += stride)
    for (std::size_t j = i + stride; j < n; j += stride)
      best = std::max (best, (loop_positions[i] - loop_positions[j]).squaredNorm ());
  return std::sqrt (best);
}

float
loopLength (const std::vector<Eigen::Vector3f> &loop_positions, bool closed)
{
  float length = 0.f;
  for (std::size_t i = 1; i < loop_positions.size (); ++i)
    length += (loop_positions[i] - loop_positions[i - 1]).norm ();
  if (closed && loop_positions.size () > 2)
    length += (loop_positions.front () - loop_positions.back ()).norm ();
  return length;
}

}  // namespace pcl_holefill::detail
