/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#include <pcl_holefill/detail/point_grid.h>
#include <pcl_holefill/detail/first_touch.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_holefill::detail
{
namespace
{
constexpr std::uint64_t kEmpty = std::numeric_limits<std::uint64_t>::max ();
// Cell coordinates are packed in 21 bits each, offset so negatives fit.
constexpr int kCoordinateBias = 1 << 20;
constexpr int kCoordinateLimit = (1 << 20) - 1;
// Past this many rings a kNN query scans every cell instead (isolated points).
constexpr int kMaxRings = 6;
// spatialOrder's key of a non-finite point: after every cell's (those use 63 bits).
constexpr std::uint64_t kNonFiniteKey = std::numeric_limits<std::uint64_t>::max ();

std::uint64_t
mix (std::uint64_t key)
{
  // splitmix64 finaliser: spreads neighbouring cells over the table.
  key ^= key >> 30;
  key *= 0xbf58476d1ce4e5b9ULL;
  key ^= key >> 27;
  key *= 0x94d049bb133111ebULL;
  key ^= key >> 31;
  return key;
}

// A function object, not a function: std::nth_element and std::sort inline
// it (through a function pointer they call it, and selection was a fifth of
// the detection on random samples).
constexpr struct
{
  bool
  operator() (const PointGrid::Neighbour &a, const PointGrid::Neighbour &b) const
  {
    return a.sqr_distance < b.sqr_distance || (a.sqr_distance == b.sqr_distance && a.id < b.id);
  }
} lessByDistance;

void
keepNearest (std::vector<PointGrid::Neighbour> &neighbours, std::size_t count)
{
  if (neighbours.size () > count)
  {
    std::nth_element (neighbours.begin (), neighbours.begin () + count, neighbours.end (),
                      lessByDistance);
    neighbours.resize (count);
  }
  std::sort (neighbours.begin (), neighbours.end (), lessByDistance);
}

/** Moves the \a m nearest of \a candidates [0, \a n) (by lessByDistance)
  * to its front, in no particular order; what follows them is left
  * unspecified. Needs n > m and every candidate within \a max_sqr (> 0).
  *
  * A bucket select: the candidates are counted into shells of equal squared
  * width (on a surface, of about equal point counts), the shells nearer
  * than the one that holds the m-th nearest are taken whole, and only that
  * shell's few candidates are compared. std::nth_element's partition of the
  * 17 nearest out of about 30 candidates mispredicted branch after branch:
  * it took a fifth of the detection on 1,000,000 uniformly random samples. */
void
selectNearest (PointGrid::Neighbour *candidates, std::size_t n, std::size_t m, float max_sqr,
               std::vector<PointGrid::Neighbour> &edge)
{
  constexpr int kShells = 16;
  const float scale = static_cast<float> (kShells) / max_sqr;
  // Monotonic in the squared distance (a product by a positive number
  // rounds monotonically), so a nearer shell never holds a farther point.
  const auto shell = [scale] (float sqr) { return std::min (static_cast<int> (sqr * scale), kShells - 1); };
  std::size_t count[kShells] = {};
  for (std::size_t i = 0; i < n; ++i)
    ++count[shell (candidates[i].sqr_distance)];
  int edge_shell = 0;
  std::size_t before = 0;
  while (before + count[edge_shell] < m)  // ends: the shells hold n > m candidates
    before += count[edge_shell++];
  // Without branches: which shell a candidate falls in is a coin toss.
  // One slot more than the shell holds: the candidates of other shells are
  // written there and overwritten.
  edge.resize (count[edge_shell] + 1);
  std::size_t kept = 0, on_edge = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const PointGrid::Neighbour c = candidates[i];
    const int s = shell (c.sqr_distance);
    candidates[kept] = c;  // kept <= i: nothing unread is overwritten
    kept += s < edge_shell ? 1 : 0;
    edge[on_edge] = c;
    on_edge += s == edge_shell ? 1 : 0;
  }
  edge.pop_back ();
  std::sort (edge.begin (), edge.end (), lessByDistance);
  std::copy (edge.begin (), edge.begin () + static_cast<std::ptrdiff_t> (m - before), candidates + before);
}

/** std::merge of the sorted ranges [a, middle) and [middle, end) into \a out,
  * its output cut into \a threads parts along the merge path: part t takes
  * the first elements of each range that the serial merge would put in its
  * share of the output, so the result is std::merge's for any \a threads. */
template <typename T, typename Less>
void
mergeInParallel (const T *a, const T *middle, const T *end, T *out, int threads, const Less &less)
{
  const std::ptrdiff_t m = middle - a, l = end - middle, total = m + l;
  const auto split = [&] (std::ptrdiff_t k) {
    // How many of the first k outputs come from [a, middle): the least i
    // with middle[k - i - 1] < a[i] (std::merge takes a tie from a first).
    std::ptrdiff_t lo = std::max<std::ptrdiff_t> (0, k - l), hi = std::min (k, m);
    while (lo < hi)
    {
      const std::ptrdiff_t i = lo + (hi - lo) / 2;
      if (less (middle[k - i - 1], a[i]))
        hi = i;
      else
        lo = i + 1;
    }
    return lo;
  };
  const int parts = std::max (1, threads);
#pragma omp parallel for num_threads(parts) schedule(static, 1)
  for (int t = 0; t < parts; ++t)
  {
    const std::ptrdiff_t k0 = total * t / parts, k1 = total * (t + 1) / parts;
    const std::ptrdiff_t i0 = split (k0), i1 = split (k1);
    std::merge (a + i0, a + i1, middle + (k0 - i0), middle + (k1 - i1), out + k0, less);
  }
}

/** Asks for the cache line at \a address ahead of its use (a hint; nothing
  * where the compiler has no such builtin). */
inline void
prefetch (const void *address)
{
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch (address);
#else
  (void) address;
#endif
}

/** One cell coordinate of a key made by PointGrid::keyOf (\a shift 42, 21 or 0). */
int
decode (std::uint64_t key, int shift)
{
  return static_cast<int> ((key >> shift) & 0x1FFFFFULL) - kCoordinateBias;
}

}  // namespace

PointGrid::PointGrid (float cell_size) { reset (cell_size); }

void
PointGrid::reset (float cell_size)
{
  cell_size_ = (std::isfinite (cell_size) && cell_size > 0.f) ? cell_size : 1.f;
  inverse_cell_size_ = 1.f / cell_size_;
  size_ = 0;
  cell_keys_.clear ();
  bulk_.clear ();
  bulk_begin_.clear ();
  extra_.clear ();
  table_.assign (64, Slot{kEmpty, -1});
  for (int d = 0; d < 3; ++d)
  {
    min_cell_[d] = std::numeric_limits<int>::max ();
    max_cell_[d] = std::numeric_limits<int>::min ();
  }
}

void
PointGrid::cellCoordinates (const Eigen::Vector3f &p, int &ix, int &iy, int &iz) const
{
  auto cell = [this] (float v) {
    const float c = std::floor (v * inverse_cell_size_);
    return static_cast<int> (std::max (-static_cast<float> (kCoordinateLimit),
                                       std::min (static_cast<float> (kCoordinateLimit), c)));
  };
  ix = cell (p.x ());
  iy = cell (p.y ());
  iz = cell (p.z ());
}

PointGrid::CellKey
PointGrid::keyOf (int ix, int iy, int iz) const
{
  const auto pack = [] (int v) { return static_cast<std::uint64_t> (v + kCoordinateBias) & 0x1FFFFFULL; };
  return (pack (ix) << 42) | (pack (iy) << 21) | pack (iz);
}

int
PointGrid::findCell (CellKey key) const
{
  const std::size_t mask = table_.size () - 1;
  for (std::size_t slot = mix (key) & mask, probes = 0; probes <= mask; slot = (slot + 1) & mask, ++probes)
  {
    if (table_[slot].key == key)
      return table_[slot].cell;
    if (table_[slot].key == kEmpty)
      return -1;
  }
  return -1;
}

int
PointGrid::findOrAddCell (CellKey key)
{
  if ((cell_keys_.size () + 1) * 2 > table_.size ())
    rehash (table_.size () * 2);
  const std::size_t mask = table_.size () - 1;
  std::size_t slot = mix (key) & mask;
  while (table_[slot].key != kEmpty && table_[slot].key != key)
    slot = (slot + 1) & mask;  // the table is at most half full: this ends
  if (table_[slot].key == kEmpty)
  {
    table_[slot] = {key, static_cast<int> (cell_keys_.size ())};
    cell_keys_.push_back (key);
  }
  return table_[slot].cell;
}

void
PointGrid::reserveCells (std::size_t cells, int threads)
{
  std::size_t capacity = table_.size ();
  while ((cells + 1) * 2 > capacity)
    capacity *= 2;
  if (capacity > table_.size ())
    rehash (capacity, threads);
}

void
PointGrid::rehash (std::size_t capacity, int threads)
{
  std::vector<Slot> old;
  resizeTouched (old, capacity, threads, Slot{kEmpty, -1});
  old.swap (table_);
  const std::size_t mask = capacity - 1;
  for (const Slot &entry : old)
  {
    if (entry.key == kEmpty)
      continue;
    std::size_t slot = mix (entry.key) & mask;
    while (table_[slot].key != kEmpty)
      slot = (slot + 1) & mask;
    table_[slot] = entry;
  }
}

void
PointGrid::build (const std::vector<Eigen::Vector3f> &points, const std::vector<int> *ids, int threads)
{
  reset (cell_size_);
  const auto n = static_cast<std::ptrdiff_t> (points.size ());
  // The cell of every point, in parallel (kNoCell for non-finite points) ...
  constexpr CellKey kNoCell = ~CellKey (0);
  std::vector<CellKey> keys;
  resizeTouched (keys, points.size (), threads);
  int lo[3] = {kCoordinateLimit, kCoordinateLimit, kCoordinateLimit};
  int hi[3] = {-kCoordinateLimit, -kCoordinateLimit, -kCoordinateLimit};
#pragma omp parallel for num_threads(std::max (1, threads)) schedule(static) \
    reduction(min : lo[:3]) reduction(max : hi[:3])
  for (std::ptrdiff_t i = 0; i < n; ++i)
  {
    keys[i] = kNoCell;
    if (!points[i].allFinite ())
      continue;
    int c[3];
    cellCoordinates (points[i], c[0], c[1], c[2]);
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::min (lo[d], c[d]);
      hi[d] = std::max (hi[d], c[d]);
    }
    keys[i] = keyOf (c[0], c[1], c[2]);
  }
  if (lo[0] <= hi[0])  // some point is finite
    for (int d = 0; d < 3; ++d)
    {
      min_cell_[d] = lo[d];
      max_cell_[d] = hi[d];
    }
  // ... a table big enough for the cells from the start: grown by doubling
  // as they appeared, it moved every cell again and again (a third of the
  // serial time of a 4,000,000-point detection on 2 cores). Runs of equal
  // keys are at least as many as the cells; a quarter of the points bounds
  // the table when the points come in no spatial order ...
  std::size_t key_runs = 0;
#pragma omp parallel for num_threads(std::max (1, threads)) schedule(static) reduction(+ : key_runs)
  for (std::ptrdiff_t i = 0; i < n; ++i)
    key_runs += keys[i] != kNoCell && (i == 0 || keys[i] != keys[i - 1]) ? 1 : 0;
  reserveCells (std::min (key_runs, points.size () / 4), threads);
  // ... then cells numbered in order of first appearance, as one insert()
  // after another would (consecutive points often share a cell: the last
  // one is tried before the table) ...
  std::vector<int> cell_of;
  resizeTouched (cell_of, points.size (), threads, -1);
  std::vector<std::uint32_t> counts;
  CellKey last_key = kNoCell;
  int last_cell = -1;
  for (std::ptrdiff_t i = 0; i < n; ++i)
  {
    if (keys[i] == kNoCell)
      continue;
    if (keys[i] != last_key)
    {
      last_key = keys[i];
      last_cell = findOrAddCell (last_key);
      if (static_cast<std::size_t> (last_cell) >= counts.size ())
        counts.resize (last_cell + 1, 0);
    }
    cell_of[i] = last_cell;
    ++counts[last_cell];
  }
  // ... and the points stored cell after cell, in their order within a cell.
  counts.resize (cell_keys_.size (), 0);
  bulk_begin_.assign (cell_keys_.size () + 1, 0);
  for (std::size_t c = 0; c < counts.size (); ++c)
    bulk_begin_[c + 1] = bulk_begin_[c] + counts[c];
  resizeTouched (bulk_, bulk_begin_.back (), threads);
  std::vector<std::uint32_t> next (bulk_begin_.begin (), bulk_begin_.end () - 1);
  for (std::ptrdiff_t i = 0; i < n; ++i)
    if (cell_of[i] >= 0)
      bulk_[next[cell_of[i]]++] = {points[i].x (), points[i].y (), points[i].z (),
                                   ids ? (*ids)[i] : static_cast<int> (i)};
  size_ = bulk_.size ();
}

PointGrid::CellSpan
PointGrid::cell (int index) const
{
  CellSpan span;
  if (static_cast<std::size_t> (index) + 1 < bulk_begin_.size ())
  {
    span.bulk = bulk_.data () + bulk_begin_[index];
    span.bulk_count = bulk_begin_[index + 1] - bulk_begin_[index];
  }
  if (static_cast<std::size_t> (index) < extra_.size ())
  {
    span.extra = extra_[index].data ();
    span.extra_count = extra_[index].size ();
  }
  return span;
}

void
PointGrid::insert (const Eigen::Vector3f &position, int id)
{
  if (!position.allFinite ())
    return;
  int c[3];
  cellCoordinates (position, c[0], c[1], c[2]);
  for (int d = 0; d < 3; ++d)
  {
    min_cell_[d] = std::min (min_cell_[d], c[d]);
    max_cell_[d] = std::max (max_cell_[d], c[d]);
  }
  const int index = findOrAddCell (keyOf (c[0], c[1], c[2]));
  if (static_cast<std::size_t> (index) >= extra_.size ())
    extra_.resize (cell_keys_.size ());
  extra_[index].push_back ({position.x (), position.y (), position.z (), id});
  ++size_;
}

void
PointGrid::collectShell (int cx, int cy, int cz, int ring, const Eigen::Vector3f &query,
                         float max_sqr, std::vector<Neighbour> &out) const
{
  // Clip the shell to the occupied range: cells outside it are empty.
  const int lo[3] = {std::max (cx - ring, min_cell_[0]), std::max (cy - ring, min_cell_[1]),
                     std::max (cz - ring, min_cell_[2])};
  const int hi[3] = {std::min (cx + ring, max_cell_[0]), std::min (cy + ring, max_cell_[1]),
                     std::min (cz + ring, max_cell_[2])};
  // Cells wholly outside the ball are not looked up: on a surface most
  // cells of a wide shell are empty, and each lookup is a cache miss (a
  // radius of 4 cells reads 729 cells, of which the ball meets about 60 %).
  // The slack keeps every cell that a point at exactly the radius could lie in.
  const bool bounded = std::isfinite (max_sqr);
  const float reach = bounded ? max_sqr * (1.f + 1e-4f) + 1e-12f : 0.f;
  const auto gap = [this] (float v, int c) {
    if (std::abs (c) >= kCoordinateLimit)
      return 0.f;  // a clamped cell holds points beyond its box
    const float below = c * cell_size_ - v, above = v - (c + 1) * cell_size_;
    return std::max ({below, above, 0.f});
  };
  for (int ix = lo[0]; ix <= hi[0]; ++ix)
  {
    const float gx = gap (query.x (), ix);
    if (bounded && gx * gx > reach)
      continue;
    for (int iy = lo[1]; iy <= hi[1]; ++iy)
    {
      const float gy = gap (query.y (), iy), gxy = gx * gx + gy * gy;
      if (bounded && gxy > reach)
        continue;
      const bool on_xy_face = std::abs (ix - cx) == ring || std::abs (iy - cy) == ring;
      // Inside the shell's x/y faces only the two z caps belong to this ring.
      const int step = on_xy_face ? 1 : std::max (1, 2 * ring);
      for (int iz = on_xy_face ? lo[2] : cz - ring; iz <= hi[2]; iz += step)
      {
        if (iz < lo[2])
          continue;
        if (bounded)
        {
          const float gz = gap (query.z (), iz);
          if (gxy + gz * gz > reach)
            continue;
        }
        const int index = findCell (keyOf (ix, iy, iz));
        if (index < 0)
          continue;
        // Written without a branch into a buffer that only grows, then the
        // points within appended: on a surface a third of a cell's points
        // are, and the branch that chose them mispredicted (a search of the
        // fill's radius reads about 700 points).
        thread_local std::vector<Neighbour> scratch;
        const CellSpan span = cell (index);
        if (scratch.size () < span.bulk_count + span.extra_count)
          scratch.resize (span.bulk_count + span.extra_count);
        std::size_t kept = 0;
        span.forEach ([&] (const Entry &e) {
          const float dx = e.x - query.x (), dy = e.y - query.y (), dz = e.z - query.z ();
          const float d2 = dx * dx + dy * dy + dz * dz;
          scratch[kept] = {e.id, d2};
          kept += d2 <= max_sqr ? 1 : 0;
        });
        out.insert (out.end (), scratch.begin (), scratch.begin () + static_cast<std::ptrdiff_t> (kept));
      }
    }
  }
}

float
PointGrid::faceMargin (float x, float y, float z, int cx, int cy, int cz) const
{
  const float margin = std::min ({x - cx * cell_size_, (cx + 1) * cell_size_ - x, y - cy * cell_size_,
                                  (cy + 1) * cell_size_ - y, z - cz * cell_size_, (cz + 1) * cell_size_ - z});
  return std::clamp (margin, 0.f, cell_size_);
}

void
PointGrid::nearestK (const Eigen::Vector3f &query, int k, std::vector<Neighbour> &result) const
{
  result.clear ();
  if (k <= 0 || size_ == 0 || !query.allFinite ())
    return;
  int cx, cy, cz;
  cellCoordinates (query, cx, cy, cz);
  const float inf = std::numeric_limits<float>::infinity ();
  // The query's distance to its own cell's nearest face (0 in a clamped cell,
  // whose box does not hold it): the rings seen so far reach that much
  // farther than whole cells. With cells of a search radius (the fill's),
  // most nearest-point queries end in their own cell instead of reading 27.
  const float margin = faceMargin (query.x (), query.y (), query.z (), cx, cy, cz);
  // Once k points are in hand, the k-th nearest so far bounds the search:
  // the next shell's cells beyond it are not looked up (a shell of 2 cells
  // has 98, and most lie outside that ball).
  float bound = inf;
  for (int ring = 0; ring <= kMaxRings; ++ring)
  {
    collectShell (cx, cy, cz, ring, query, bound, result);
    if (static_cast<int> (result.size ()) >= k)
    {
      // Every point within ring cells and the margin of the query has been seen.
      std::nth_element (result.begin (), result.begin () + (k - 1), result.end (), lessByDistance);
      const float reach = ring * cell_size_ + margin;
      if (result[k - 1].sqr_distance <= reach * reach)
      {
        keepNearest (result, static_cast<std::size_t> (k));
        return;
      }
      bound = result[k - 1].sqr_distance;
    }
  }
  nearestKAmongCells (query, static_cast<std::size_t> (k), result);
}

void
PointGrid::nearestKAmongCells (const Eigen::Vector3f &query, std::size_t k, std::vector<Neighbour> &result) const
{
  // An isolated query (a stray point far from the surface): the occupied
  // cells nearest first, until the k-th point found is nearer than the next
  // cell. Scanning every point instead made a thousand stray points cost a
  // thousand passes over the cloud.
  std::vector<std::pair<float, int>> cells (cell_keys_.size ());
  for (std::size_t c = 0; c < cell_keys_.size (); ++c)
  {
    const int coordinate[3] = {decode (cell_keys_[c], 42), decode (cell_keys_[c], 21), decode (cell_keys_[c], 0)};
    float sqr = 0.f;
    for (int d = 0; d < 3; ++d)
    {
      // The cell's box, widened a little against the rounding of floor (v / cell).
      const float lo = (coordinate[d] - 1e-3f) * cell_size_;
      const float gap = std::max ({0.f, lo - query (d), query (d) - (lo + 1.002f * cell_size_)});
      sqr += gap * gap;
    }
    cells[c] = {sqr, static_cast<int> (c)};
  }
  std::sort (cells.begin (), cells.end ());
  result.clear ();
  // A max-heap of the k nearest so far.
  for (const auto &[cell_sqr, c] : cells)
  {
    if (result.size () >= k && result.front ().sqr_distance <= cell_sqr)
      break;
    cell (c).forEach ([&] (const Entry &e) {
      const float dx = e.x - query.x (), dy = e.y - query.y (), dz = e.z - query.z ();
      const Neighbour found{e.id, dx * dx + dy * dy + dz * dz};
      if (result.size () < k)
      {
        result.push_back (found);
        std::push_heap (result.begin (), result.end (), lessByDistance);
      }
      else if (lessByDistance (found, result.front ()))
      {
        std::pop_heap (result.begin (), result.end (), lessByDistance);
        result.back () = found;
        std::push_heap (result.begin (), result.end (), lessByDistance);
      }
    });
  }
  keepNearest (result, k);
}

void
PointGrid::forEachNearestK (int k, int threads,
                            const std::function<void (int id, const Neighbour *neighbours, int count)> &visit) const
{
  if (k <= 0)
    return;
#pragma omp parallel num_threads(std::max (threads, 1))
  {
    std::vector<Entry> block;
    std::vector<Neighbour> candidates;
    std::vector<Neighbour> fallback;
    std::vector<Entry> own;  // the cell's points; one buffer per thread, reused
    std::vector<Neighbour> edge;
#pragma omp for schedule(dynamic, 64)
    for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t> (cell_keys_.size ()); ++c)
    {
      const int cx = decode (cell_keys_[c], 42), cy = decode (cell_keys_[c], 21), cz = decode (cell_keys_[c], 0);
      block.clear ();
      // The 27 lookups miss the cache in a table of a million cells; asked
      // for all at once first, they wait for memory together.
      CellKey keys[27];
      for (int b = 0; b < 27; ++b)
      {
        keys[b] = keyOf (cx - 1 + b / 9, cy - 1 + b / 3 % 3, cz - 1 + b % 3);
        prefetch (&table_[mix (keys[b]) & (table_.size () - 1)]);
      }
      for (const CellKey key : keys)
      {
        const int index = findCell (key);
        if (index >= 0)
          cell (index).forEach ([&block] (const Entry &e) { block.push_back (e); });
      }
      own.clear ();
      cell (static_cast<int> (c)).forEach ([&own] (const Entry &e) { own.push_back (e); });
      candidates.resize (block.size ());
      const auto is_self = [] (int id) { return [id] (const Neighbour &n) { return n.id == id; }; };
      for (const Entry &self : own)
      {
        // Every point nearer to self than the block's nearest face lies in
        // the block (one cell edge plus self's distance to its own cell's
        // nearest face), so if at least k + 1 of them (self included) are
        // that near, the k nearest are among them: select there. Counting to
        // the face, not one cell edge: on uniformly random samples a ball of
        // one cell edge holds only k points on average (suggestCellSize), and
        // every point short of k + 1 took the search from scratch below.
        // The compaction has no branch, which matters more here than the
        // instruction count.
        const float reach = cell_size_ + faceMargin (self.x, self.y, self.z, cx, cy, cz);
        const float inner = reach * reach;
        std::size_t near_count = 0;
        for (const Entry &e : block)
        {
          const float dx = e.x - self.x, dy = e.y - self.y, dz = e.z - self.z;
          const float d2 = dx * dx + dy * dy + dz * dz;
          candidates[near_count] = {e.id, d2};
          near_count += d2 <= inner ? 1 : 0;
        }
        const Eigen::Vector3f p (self.x, self.y, self.z);
        if (near_count > static_cast<std::size_t> (k))
        {
          if (near_count > static_cast<std::size_t> (k) + 1)
            selectNearest (candidates.data (), near_count, static_cast<std::size_t> (k) + 1, inner, edge);
          // The k + 1 nearest hold self unless k + 1 copies of it came first.
          const auto kept = std::remove_if (candidates.begin (), candidates.begin () + (k + 1), is_self (self.id));
          visit (self.id, candidates.data (), std::min (static_cast<int> (kept - candidates.begin ()), k));
          continue;
        }
        nearestK (p, k + 1, fallback);
        fallback.erase (std::remove_if (fallback.begin (), fallback.end (), is_self (self.id)), fallback.end ());
        if (static_cast<int> (fallback.size ()) > k)
          fallback.resize (k);
        visit (self.id, fallback.data (), static_cast<int> (fallback.size ()));
      }
    }
  }
}

void
PointGrid::withinRadius (const Eigen::Vector3f &query, float radius, std::vector<Neighbour> &result,
                         std::size_t max_results) const
{
  result.clear ();
  if (!(radius > 0.f) || size_ == 0 || !query.allFinite ())
    return;
  int centre[3];
  cellCoordinates (query, centre[0], centre[1], centre[2]);
  const float sqr = radius * radius;
  const int rings = static_cast<int> (std::min (std::ceil (radius * inverse_cell_size_), 1e6f));
  // Cells of the ball's box that the occupied range holds.
  int lo[3], hi[3];
  double box_cells = 1.0;
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = std::max (centre[d] - rings, min_cell_[d]);
    hi[d] = std::min (centre[d] + rings, max_cell_[d]);
    box_cells *= std::max (0, hi[d] - lo[d] + 1);
  }
  if (box_cells > static_cast<double> (cell_keys_.size ()))
  {
    // A ball much larger than the cells (an isolated point asking for its
    // own, large, scale): looking at every occupied cell once is cheaper
    // than visiting the empty ones of the ball (a stray point 5 units off a
    // 1,000,000-point cloud would visit 10^10 of them).
    for (std::size_t c = 0; c < cell_keys_.size (); ++c)
    {
      const int coordinate[3] = {decode (cell_keys_[c], 42), decode (cell_keys_[c], 21), decode (cell_keys_[c], 0)};
      if (coordinate[0] < lo[0] || coordinate[0] > hi[0] || coordinate[1] < lo[1] || coordinate[1] > hi[1] ||
          coordinate[2] < lo[2] || coordinate[2] > hi[2])
        continue;
      cell (static_cast<int> (c)).forEach ([&] (const Entry &e) {
        const float dx = e.x - query.x (), dy = e.y - query.y (), dz = e.z - query.z ();
        const float d2 = dx * dx + dy * dy + dz * dz;
        if (d2 <= sqr)
          result.push_back ({e.id, d2});
      });
    }
  }
  else
  {
    // Beyond the farthest occupied coordinate every shell is empty.
    int farthest = 0;
    for (int d = 0; d < 3; ++d)
      farthest = std::max ({farthest, std::abs (centre[d] - min_cell_[d]), std::abs (centre[d] - max_cell_[d])});
    for (int ring = 0; ring <= std::min (rings, farthest); ++ring)
      collectShell (centre[0], centre[1], centre[2], ring, query, sqr, result);
  }
  if (max_results > 0)
    keepNearest (result, max_results);
}

std::vector<int>
PointGrid::spatialOrder (const std::vector<Eigen::Vector3f> &points, float cell_size, int threads)
{
  // Spread the low 21 bits of v so that two zero bits follow each one.
  const auto spread = [] (std::uint64_t v) {
    v &= 0x1FFFFFULL;
    v = (v | v << 32) & 0x1F00000000FFFFULL;
    v = (v | v << 16) & 0x1F0000FF0000FFULL;
    v = (v | v << 8) & 0x100F00F00F00F00FULL;
    v = (v | v << 4) & 0x10C30C30C30C30C3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  PointGrid frame (cell_size);
  std::vector<std::pair<std::uint64_t, int>> keyed;
  resizeTouched (keyed, points.size (), threads);
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t> (points.size ());
  // Within a cell, equal positions end up next to each other (see below).
#pragma omp parallel for num_threads(std::max (threads, 1)) schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i)
  {
    std::uint64_t key = kNonFiniteKey;
    if (points[i].allFinite ())
    {
      int c[3];
      frame.cellCoordinates (points[i], c[0], c[1], c[2]);
      key = spread (static_cast<std::uint64_t> (c[0] + kCoordinateBias)) |
            spread (static_cast<std::uint64_t> (c[1] + kCoordinateBias)) << 1 |
            spread (static_cast<std::uint64_t> (c[2] + kCoordinateBias)) << 2;
    }
    keyed[i] = {key, static_cast<int> (i)};
  }
  const auto before = [&points] (const auto &a, const auto &b) {
    if (a.first != b.first)
      return a.first < b.first;
    const Eigen::Vector3f &p = points[a.second], &q = points[b.second];
    if (p.x () != q.x ())
      return p.x () < q.x ();
    if (p.y () != q.y ())
      return p.y () < q.y ();
    if (p.z () != q.z ())
      return p.z () < q.z ();
    return a.second < b.second;
  };
  // Sorted by cell first, runs side by side, then merged; then the points of
  // each cell by position. Comparing positions only within a cell's few
  // points spares the sort of a million points its reads of scattered
  // positions. The order is total, so the result is the one sort of the
  // whole would give. (A radix sort took 0.03 s less on a million points and
  // 16 MB more memory, at the detection's peak.)
  const auto by_cell = [] (const auto &a, const auto &b) { return a.first < b.first; };
  const int runs = static_cast<int> (std::clamp<std::ptrdiff_t> (threads, 1, std::max<std::ptrdiff_t> (1, n / 65536)));
  std::vector<std::ptrdiff_t> bounds (runs + 1);
  for (int r = 0; r <= runs; ++r)
    bounds[r] = n * r / runs;
#pragma omp parallel for num_threads(runs) schedule(static, 1)
  for (int r = 0; r < runs; ++r)
    std::sort (keyed.begin () + bounds[r], keyed.begin () + bounds[r + 1], by_cell);
  if (runs > 1)
  {
    // Merged by every thread (a serial merge of the runs was a sixth of the
    // serial time of a 4,000,000-point detection on 2 cores).
    std::vector<std::pair<std::uint64_t, int>> merged;
    resizeTouched (merged, keyed.size (), threads);
    for (int r = 1; r < runs; ++r)
    {
      mergeInParallel (keyed.data (), keyed.data () + bounds[r], keyed.data () + bounds[r + 1], merged.data (),
                       threads, by_cell);
      std::copy (merged.begin (), merged.begin () + bounds[r + 1], keyed.begin ());
    }
  }
#pragma omp parallel for num_threads(std::max (threads, 1)) schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i)
  {
    // Each run of one cell, from its first element (whoever sees it). The
    // non-finite points go by index: positions with a NaN do not order (a
    // sort given them may read past the run, and the order depended on the
    // number of threads).
    if (i > 0 && keyed[i - 1].first == keyed[i].first)
      continue;
    std::ptrdiff_t end = i + 1;
    while (end < n && keyed[end].first == keyed[i].first)
      ++end;
    if (keyed[i].first == kNonFiniteKey)
      std::sort (keyed.begin () + i, keyed.begin () + end, [] (const auto &a, const auto &b) { return a.second < b.second; });
    else
      std::sort (keyed.begin () + i, keyed.begin () + end, before);
  }
  std::vector<int> order;
  resizeTouched (order, points.size (), threads);
#pragma omp parallel for num_threads(std::max (threads, 1)) schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i)
    order[i] = keyed[i].second;
  return order;
}

std::size_t
PointGrid::countOccupiedCells (const std::vector<Eigen::Vector3f> &points, const Eigen::Vector3f &lo,
                               const Eigen::Vector3f &hi, float cell_size)
{
  PointGrid probe (cell_size);
  int first[3], last[3];
  probe.cellCoordinates (lo, first[0], first[1], first[2]);
  probe.cellCoordinates (hi, last[0], last[1], last[2]);
  double box_cells = 1.0;
  for (int d = 0; d < 3; ++d)
    box_cells *= static_cast<double> (last[d] - first[d] + 1);
  std::size_t occupied = 0;
  if (box_cells > 32.0 * static_cast<double> (points.size ()) + 4096.0)
  {
    // A box too large for a bit a cell: the hash grid.
    for (const auto &p : points)
      if (p.allFinite ())
      {
        int ix, iy, iz;
        probe.cellCoordinates (p, ix, iy, iz);
        const std::size_t before = probe.cell_keys_.size ();
        probe.findOrAddCell (probe.keyOf (ix, iy, iz));
        occupied += probe.cell_keys_.size () - before;
      }
    return occupied;
  }
  // A bit a cell of the box: a million random points set their bits in a
  // tenth of the time their hash cells took (cache misses on the table).
  const auto nx = static_cast<std::size_t> (last[0] - first[0] + 1);
  const auto ny = static_cast<std::size_t> (last[1] - first[1] + 1);
  std::vector<std::uint64_t> bits ((static_cast<std::size_t> (box_cells) + 63) / 64, 0);
  for (const auto &p : points)
    if (p.allFinite ())
    {
      int c[3];
      probe.cellCoordinates (p, c[0], c[1], c[2]);
      const std::size_t at = static_cast<std::size_t> (c[0] - first[0]) +
                             nx * (static_cast<std::size_t> (c[1] - first[1]) +
                                   ny * static_cast<std::size_t> (c[2] - first[2]));
      const std::uint64_t bit = std::uint64_t (1) << (at % 64);
      occupied += (bits[at / 64] & bit) ? 0 : 1;
      bits[at / 64] |= bit;
    }
  return occupied;
}

float
PointGrid::suggestCellSize (const std::vector<Eigen::Vector3f> &points, int k)
{
  Eigen::Vector3f lo = Eigen::Vector3f::Constant (std::numeric_limits<float>::max ());
  Eigen::Vector3f hi = -lo;
  std::size_t finite = 0;
  for (const auto &p : points)
    if (p.allFinite ())
    {
      lo = lo.cwiseMin (p);
      hi = hi.cwiseMax (p);
      ++finite;
    }
  if (finite == 0)
    return 0.f;
  const float diagonal = (hi - lo).norm ();
  if (finite < 2 || !(diagonal > 0.f))
    return 1.f;
  // A coarse grid with about 32 points a cell if the cloud were a square
  // sheet; its occupied cells measure the surface area.
  const float coarse = diagonal / std::sqrt (static_cast<float> (finite) / 32.f);
  const std::size_t occupied = countOccupiedCells (points, lo, hi, coarse);
  const float area = static_cast<float> (occupied) * coarse * coarse;
  const float density = static_cast<float> (finite) / std::max (area, 1e-30f);
  // A disc of radius cell holds pi * cell^2 * density points: ask for 2k so
  // that the k nearest are inside the first ring most of the time.
  const float cell = std::sqrt (1.f * std::max (k, 1) / (3.14159265f * density));
  return std::isfinite (cell) && cell > 0.f ? cell : diagonal;
}

}  // namespace pcl_holefill::detail
