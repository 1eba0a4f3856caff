/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <vector>

namespace pcl_holefill::detail
{
/** \brief A uniform hash grid over 3D points that supports exact k-nearest and
  * radius queries and cheap insertion of new points.
  *
  * Why not a kd-tree: points sampled on a surface fill a hash grid evenly, so a
  * query touches a few dozen contiguous entries, and new points (the filler
  * adds some every pass) go in without a rebuild. Each cell stores the
  * coordinates next to the ids, so a query reads memory in order.
  *
  * The grid is not thread-safe for insertion; concurrent queries are fine.
  */
class PointGrid
{
public:
  /** \brief One neighbour: its id (as given to insert()) and squared distance. */
  struct Neighbour
  {
    int id;
    float sqr_distance;
  };

  /** \brief An empty grid with cells of edge \a cell_size (must be > 0). */
  explicit PointGrid (float cell_size = 1.0f);

  /** \brief Removes every point and sets a new cell size (> 0). */
  void
  reset (float cell_size);

  /** \brief Replaces the content by \a points (ids 0..n-1, or \a ids when
    * given), counting per cell first so that every cell is allocated once at
    * its exact size: the memory of a bulk load is the points' and no more.
    * The same grid for any number of \a threads. */
  void
  build (const std::vector<Eigen::Vector3f> &points, const std::vector<int> *ids = nullptr, int threads = 1);

  /** \brief Adds one point with the caller's id. Non-finite points are ignored. */
  void
  insert (const Eigen::Vector3f &position, int id);

  /** \brief The \a k nearest points to \a query, nearest first (fewer if the
    * grid holds fewer than \a k points). Exact. */
  void
  nearestK (const Eigen::Vector3f &query, int k, std::vector<Neighbour> &result) const;

  /** \brief The \a k nearest neighbours of every stored point (itself
    * excluded), in no particular order: visit(id, neighbours, count) is called once
    * per point, from \a threads threads at once, cell by cell. This is a
    * kNN per point as nearestK() gives it, but each cell's 3x3x3 block is
    * gathered once for all of its points, and points are visited in spatial
    * order: several times faster on a whole cloud. */
  void
  forEachNearestK (int k, int threads,
                   const std::function<void (int id, const Neighbour *neighbours, int count)> &visit) const;

  /** \brief All points within \a radius of \a query, unordered; at most
    * \a max_results of them when that is > 0 (then the nearest are kept). */
  void
  withinRadius (const Eigen::Vector3f &query, float radius, std::vector<Neighbour> &result,
                std::size_t max_results = 0) const;

  /** \brief Number of points stored. */
  std::size_t
  size () const { return size_; }

  float
  cellSize () const { return cell_size_; }

  /** \brief A cell size at which a cell block of 3x3x3 holds about \a k
    * neighbours of a point sampled on a surface, estimated from the points
    * themselves (occupied cells of a coarse grid give the surface area).
    * Returns 0 when no finite point is given. */
  static float
  suggestCellSize (const std::vector<Eigen::Vector3f> &points, int k);

  /** \brief A permutation of \a points that visits them cell by cell along a
    * Morton (Z-order) curve over cells of edge \a cell_size: neighbours in
    * space become neighbours in memory, which is what makes a pass over a
    * large cloud fast. Non-finite points come last; points at the same
    * position come one after the other, in index order. The order is the
    * same for any number of \a threads (a total order: ties go by index). */
  static std::vector<int>
  spatialOrder (const std::vector<Eigen::Vector3f> &points, float cell_size, int threads = 1);

private:
  struct Entry
  {
    float x, y, z;
    int id;
  };

  using CellKey = std::uint64_t;

  CellKey
  keyOf (int ix, int iy, int iz) const;

  void
  cellCoordinates (const Eigen::Vector3f &p, int &ix, int &iy, int &iz) const;

  /** The slot of the cell with this key, or -1. */
  int
  findCell (CellKey key) const;

  /** The slot of the cell with this key, created if needed. */
  int
  findOrAddCell (CellKey key);

  /** Grows the table to hold \a cells cells without a rehash. */
  void
  reserveCells (std::size_t cells, int threads);

  /** A table of \a capacity slots (a power of 2), its pages first touched
    * by \a threads threads. */
  void
  rehash (std::size_t capacity, int threads = 1);

  /** The points of one cell: those of the last build(), then those inserted since. */
  struct CellSpan
  {
    const Entry *bulk = nullptr;
    std::size_t bulk_count = 0;
    const Entry *extra = nullptr;
    std::size_t extra_count = 0;

    template <typename Visit>
    void
    forEach (Visit visit) const
    {
      for (std::size_t i = 0; i < bulk_count; ++i)
        visit (bulk[i]);
      for (std::size_t i = 0; i < extra_count; ++i)
        visit (extra[i]);
    }
  };

  CellSpan
  cell (int index) const;

  /** The number of cells of edge \a cell_size that the finite \a points
    * (within the box \a lo .. \a hi) occupy. */
  static std::size_t
  countOccupiedCells (const std::vector<Eigen::Vector3f> &points, const Eigen::Vector3f &lo,
                      const Eigen::Vector3f &hi, float cell_size);

  /** Distance from (x, y, z) in cell (cx, cy, cz) to that cell's nearest
    * face, within 0..cell size (0 in a clamped cell, whose box need not hold
    * its points). */
  float
  faceMargin (float x, float y, float z, int cx, int cy, int cz) const;

  /** Visits the cells of the shell at Chebyshev distance \a ring around
    * (cx, cy, cz) and collects the points within sqrt(max_sqr) of query. */
  void
  collectShell (int cx, int cy, int cz, int ring, const Eigen::Vector3f &query, float max_sqr,
                std::vector<Neighbour> &out) const;

  /** The k nearest points to \a query, sorted, visiting the occupied cells
    * nearest first: for queries farther from the points than the rings of
    * nearestK reach. */
  void
  nearestKAmongCells (const Eigen::Vector3f &query, std::size_t k, std::vector<Neighbour> &result) const;

  float cell_size_;
  float inverse_cell_size_;
  std::size_t size_ = 0;
  int min_cell_[3] = {0, 0, 0};
  int max_cell_[3] = {0, 0, 0};
  // Open addressing: a slot holds a key (or kEmpty) and its cell, side by
  // side: a lookup is one cache miss, not two (lookups were a tenth of the
  // detection of a million random samples).
  struct Slot
  {
    CellKey key;
    int cell;
  };
  std::vector<Slot> table_;
  std::vector<CellKey> cell_keys_;  //!< the key of each cell, to find its neighbours
  // Points of build() in one array, cell after cell (no per-cell allocation:
  // the grid of a million points costs its 16 bytes a point); points
  // inserted later go to small per-cell vectors.
  std::vector<Entry> bulk_;
  std::vector<std::uint32_t> bulk_begin_;  //!< cell c's bulk points: [bulk_begin_[c], bulk_begin_[c + 1])
  std::vector<std::vector<Entry>> extra_;
};

}  // namespace pcl_holefill::detail
