#pragma once
// The one multi-threaded loop of the batch paths: [0, n) cut into `threads` contiguous
// chunks, the first run on the calling thread and the others on std::threads. Every
// point is computed by the same code whatever the chunk it falls in, so the result is
// bit for bit the same for any number of threads.

#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace libcam {

// Calls body(begin, end) on disjoint chunks covering [0, n). Chunk boundaries are
// multiples of `grain` (keep it a multiple of the SIMD width and of a cache line's
// worth of points, so that threads never share a written cache line). An exception
// thrown by any chunk is rethrown here after every thread has finished.
template <class Body>
void parallel_chunks(std::size_t n, int threads, std::size_t grain, Body&& body) {
    const std::size_t blocks = (n + grain - 1) / grain;
    const std::size_t workers = std::clamp<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), 1, std::max<std::size_t>(blocks, 1));
    if (workers == 1) {
        body(std::size_t{0}, n);
        return;
    }
    const auto chunk_begin = [&](std::size_t worker) { return std::min(n, blocks * worker / workers * grain); };
    std::vector<std::exception_ptr> errors(workers);
    const auto run = [&](std::size_t worker) {
        try {
            body(chunk_begin(worker), chunk_begin(worker + 1));
        } catch (...) {
            errors[worker] = std::current_exception();
        }
    };
    std::vector<std::thread> pool;
    pool.reserve(workers - 1);
    for (std::size_t worker = 1; worker < workers; ++worker) pool.emplace_back(run, worker);
    run(0);
    for (std::thread& thread : pool) thread.join();
    for (const std::exception_ptr& error : errors) {
        if (error) std::rethrow_exception(error);
    }
}

}  // namespace libcam
