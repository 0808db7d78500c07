#pragma once
// Builds a compressed-row list (offsets + column indices) with OpenMP threads: each thread fills a
// contiguous block of rows into its own buffer and the blocks are joined in row order, so the result
// is the same on any thread count.
#include <cstddef>
#include <exception>
#include <functional>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace sph {

// make_row_filler() is called once on each thread and returns that thread's fill_row(i, out), which
// appends row i's entries to `out` (a per-thread buffer); each thread fills its rows
// in increasing order, so a filler may keep state from one row to the next (work shared by a run of
// rows). On return offset has n_rows + 1 entries and index holds the rows back to back. An exception
// (std::bad_alloc as a buffer grows) is carried out of the threads and rethrown here: one escaping an
// OpenMP region would end the program without the run's failure message.
template <class MakeRowFiller>
void build_compressed_rows_per_thread(std::size_t n_rows, std::vector<std::size_t>& offset, std::vector<int>& index,
                                      MakeRowFiller&& make_row_filler) {
  // Each thread's buffer starts at its share of the last list's length (lists change little between
  // builds), so that it seldom doubles, and the last list is freed first: the peak memory of a build
  // (docs/performance.md, "Memory per particle").
  const double last_row_length = offset.size() > 1 ? double(index.size()) / double(offset.size() - 1) : 0.0;
  std::vector<int>().swap(index);
  offset.assign(n_rows + 1, 0);
  std::vector<std::vector<int>> block_index;
  std::exception_ptr failure;
#pragma omp parallel
  {
    int thread = 0, threads = 1;
#ifdef _OPENMP
    thread = omp_get_thread_num();
    threads = omp_get_num_threads();
#endif
#pragma omp single
    block_index.resize(threads);  // implicit barrier: every thread sees the resized vector
    const std::size_t lo = n_rows * thread / threads, hi = n_rows * (thread + 1) / threads;
    std::vector<int>& out = block_index[thread];
    try {
      out.reserve(static_cast<std::size_t>(1.05 * last_row_length * double(hi - lo)));
      auto fill_row = make_row_filler();
      for (std::size_t i = lo; i < hi; ++i) {
        const std::size_t start = out.size();
        fill_row(i, out);
        offset[i + 1] = out.size() - start;  // the row's length; prefix-summed below
      }
    } catch (...) {
#pragma omp critical(compressed_rows_failure)
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
  for (std::size_t i = 0; i < n_rows; ++i) offset[i + 1] += offset[i];
  if (block_index.size() == 1) {
    index.swap(block_index[0]);
    return;
  }
  index.reserve(offset[n_rows]);
  for (auto& b : block_index) {
    index.insert(index.end(), b.begin(), b.end());
    std::vector<int>().swap(b);
  }
}

// The same with one stateless fill_row(i, out) shared by every thread.
template <class FillRow> void build_compressed_rows(std::size_t n_rows, std::vector<std::size_t>& offset,
                                                    std::vector<int>& index, FillRow&& fill_row) {
  build_compressed_rows_per_thread(n_rows, offset, index, [&] { return std::ref(fill_row); });
}

}  // namespace sph
