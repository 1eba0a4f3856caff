/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl/point_cloud.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace pcl_holefill::detail
{
/** \brief Asks the kernel to back the 2 MiB-aligned part of [\a begin,
  * \a begin + \a bytes) with huge pages (Linux; a hint, nothing elsewhere).
  *
  * A fresh block faults in a page at a time, and page faults take a lock
  * that every thread of the process shares: on a 2-core virtual machine the
  * command on 3,900,000 points (a cap of 100,000 cut) took 360,000 faults, 12 %
  * of its samples with 2 threads, the threads waiting on each other. A
  * 2 MiB page faults once where 512 small ones did: advised, the faults
  * halved. Only whole huge pages inside the block are advised, so no memory
  * outside it changes. */
inline void
adviseHugePages (void *begin, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHugePage = std::uintptr_t (2) << 20;
  const auto start = reinterpret_cast<std::uintptr_t> (begin);
  const std::uintptr_t first = (start + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t last = (start + bytes) & ~(kHugePage - 1);
  if (last > first)
    madvise (reinterpret_cast<void *> (first), last - first, MADV_HUGEPAGE);  // refused: small pages, as before
#else
  (void) begin;
  (void) bytes;
#endif
}

/** \brief Reserves room for \a capacity elements in \a v and has \a threads
  * threads touch each page of the room beyond v's elements.
  *
  * A large fresh block comes from the kernel a page at a time, on its first
  * write, and a serial pass that fills it pays every page fault on one core:
  * on a 2-core virtual machine the faults were half the time of the serial
  * steps of a 1,000,000-point fill (the output copy, the search's grid).
  * Touched from every thread first, the faults run in parallel, and the
  * serial pass finds its pages present. Only storage that holds no element
  * yet is written. */
template <typename T, typename Allocator>
void
reserveTouched (std::vector<T, Allocator> &v, std::size_t capacity, int threads)
{
  v.reserve (capacity);
  if (capacity <= v.size ())
    return;
  constexpr std::ptrdiff_t kPage = 4096;
  char *room = reinterpret_cast<char *> (v.data () + v.size ());
  const auto bytes = static_cast<std::ptrdiff_t> ((capacity - v.size ()) * sizeof (T));
  adviseHugePages (room, static_cast<std::size_t> (bytes));
  if (threads < 2 || bytes < 64 * kPage)
    return;
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::ptrdiff_t offset = 0; offset < bytes; offset += kPage)
    room[offset] = 0;
}

/** \brief reserveTouched, then resize to \a size (new elements
  * default-inserted: left unset where the type has no initialiser, as
  * Eigen's vectors). */
template <typename T, typename Allocator>
void
resizeTouched (std::vector<T, Allocator> &v, std::size_t size, int threads)
{
  reserveTouched (v, size, threads);
  v.resize (size);
}

/** \brief The same, new elements set to \a value. */
template <typename T, typename Allocator>
void
resizeTouched (std::vector<T, Allocator> &v, std::size_t size, int threads, const T &value)
{
  reserveTouched (v, size, threads);
  v.resize (size, value);
}

/** \brief The positions of the points of \a cloud at \a indices (of every
  * point when \a indices is null), gathered by \a threads threads into a
  * buffer touched as reserveTouched does: the one copy of a large cloud's
  * positions that detection and the search make before ordering or gridding. */
template <typename PointT>
std::vector<Eigen::Vector3f>
gatherPositions (const pcl::PointCloud<PointT> &cloud, const pcl::Indices *indices, int threads)
{
  const std::size_t count = indices ? indices->size () : cloud.size ();
  std::vector<Eigen::Vector3f> positions;
  resizeTouched (positions, count, threads);  // Eigen leaves them unset: no pass over the memory
#pragma omp parallel for num_threads(threads < 1 ? 1 : threads) schedule(static)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t> (count); ++i)
    positions[i] = cloud[indices ? (*indices)[i] : i].getVector3fMap ();
  return positions;
}

}  // namespace pcl_holefill::detail
