/*
 * pcl_holefill: shape controllable hole filling for oriented point clouds.
 * SPDX-License-Identifier: BSD-3-Clause
 */
#pragma once

#include <pcl_holefill/detail/first_touch.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace pcl_holefill::detail
{
/** \brief out = value (i) for every i in [0, n) with keep (i), in increasing
  * order of i, found by \a threads threads.
  *
  * The serial filter of a large cloud (its usable points, its repeated
  * positions) ran on one core while the other waited: a tenth of a
  * 4,000,000-point detection on 2 cores. Each thread tests one contiguous
  * block, the blocks' counts give each its place in \a out, and each copies
  * its kept values there: the same \a out for any number of threads. */
template <typename Keep, typename Value, typename Out>
void
selectInOrder (std::ptrdiff_t n, int threads, const Keep &keep, const Value &value, std::vector<Out> &out)
{
  const int blocks = std::max (1, threads);
  std::vector<unsigned char> kept;
  resizeTouched (kept, static_cast<std::size_t> (std::max<std::ptrdiff_t> (n, 0)), blocks);
  std::vector<std::size_t> first (blocks + 1, 0);  // block b's first place in out, after the prefix sum
  const auto begin = [n, blocks] (int b) { return n * b / blocks; };
#pragma omp parallel for num_threads(blocks) schedule(static, 1)
  for (int b = 0; b < blocks; ++b)
  {
    std::size_t count = 0;  // local: first[] shares a cache line between the threads
    for (std::ptrdiff_t i = begin (b); i < begin (b + 1); ++i)
    {
      kept[i] = keep (i) ? 1 : 0;
      count += kept[i];
    }
    first[b + 1] = count;
  }
  for (int b = 0; b < blocks; ++b)
    first[b + 1] += first[b];
  out.clear ();
  resizeTouched (out, first[blocks], blocks);
#pragma omp parallel for num_threads(blocks) schedule(static, 1)
  for (int b = 0; b < blocks; ++b)
  {
    std::size_t at = first[b];
    for (std::ptrdiff_t i = begin (b); i < begin (b + 1); ++i)
      if (kept[i])
        out[at++] = value (i);
  }
}

}  // namespace pcl_holefill::detail
