#pragma once
// The one multi-threaded loop of the batch paths: [0, n) cut into pieces, taken in turn by
// `threads` workers (the calling thread and std::threads) from a shared counter. Every
// point is computed by the same code whatever the piece it falls in, so the result is
// bit for bit the same for any number of threads.
//
// Why pieces and not one contiguous chunk per thread: a batch takes as long as its
// slowest worker, and a worker is slowed by whatever else runs on its core (on a shared
// machine, often) or by a harder part of the image (pixels the full solver settles).
// With several pieces per worker, a worker that falls behind takes fewer of them.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace libcam {

// The workers a `threads` option asks for: that many, or one per core for 0 or less (at
// least one where the system does not say how many cores it has).
inline int worker_count(int threads) {
    if (threads > 0) return threads;
    return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// Pieces per worker: enough to even out a slowed worker, few enough that each piece of
// a megapixel batch is thousands of points.
inline constexpr std::size_t kPiecesPerWorker = 8;

// Calls body(begin, end) on disjoint pieces covering [0, n). Piece boundaries are
// multiples of `grain` (keep it a multiple of the SIMD width and of a cache line's
// worth of points, so that threads never share a written cache line). A worker may call
// body several times. An exception thrown by any piece is rethrown here after every
// thread has finished (the worker that threw takes no more pieces).
template <class Body>
void parallel_chunks(std::size_t n, int threads, std::size_t grain, Body&& body) {
    const std::size_t blocks = (n + grain - 1) / grain;
    const std::size_t workers = std::clamp<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), 1, std::max<std::size_t>(blocks, 1));
    if (workers == 1) {
        body(std::size_t{0}, n);
        return;
    }
    const std::size_t pieces = std::min(blocks, workers * kPiecesPerWorker);
    const auto piece_begin = [&](std::size_t piece) { return std::min(n, blocks * piece / pieces * grain); };
    std::atomic<std::size_t> next_piece{0};
    std::vector<std::exception_ptr> errors(workers);
    const auto run = [&](std::size_t worker) {
        try {
            for (std::size_t piece = next_piece++; piece < pieces; piece = next_piece++) {
                body(piece_begin(piece), piece_begin(piece + 1));
            }
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
