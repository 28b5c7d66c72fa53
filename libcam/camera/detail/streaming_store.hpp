#pragma once
// Internal to libcam (camera/unprojector.cpp): filling and copying arrays with stores
// that bypass the cache, for outputs far larger than the cache and written once (a
// whole frame of rays). An ordinary store first reads the cache line it overwrites;
// these do not, so writing costs one pass over memory instead of two, as for memset.
// Without SSE2 they are ordinary std::fill_n and std::copy_n.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace libcam::detail {

#if defined(__SSE2__)

// The 16-byte register holding copies of `value` (double, float or byte).
template <class T>
__m128i splat(T value) {
    if constexpr (std::is_same_v<T, double>) {
        return _mm_castpd_si128(_mm_set1_pd(value));
    } else if constexpr (std::is_same_v<T, float>) {
        return _mm_castps_si128(_mm_set1_ps(value));
    } else {
        static_assert(std::is_same_v<T, std::uint8_t>);
        return _mm_set1_epi8(static_cast<char>(value));
    }
}

// Ordinary stores up to the first 16-byte boundary; returns how many.
template <class T>
std::size_t head_to_alignment(const T* out, std::size_t n) {
    const std::size_t misaligned = reinterpret_cast<std::uintptr_t>(out) % 16;
    if (misaligned % sizeof(T) != 0) return n;  // never aligned: all ordinary stores
    return std::min(n, misaligned == 0 ? 0 : (16 - misaligned) / sizeof(T));
}

template <class T>
void stream_fill(T* out, std::size_t n, T value) {
    constexpr std::size_t kLanes = 16 / sizeof(T);
    const std::size_t head = head_to_alignment(out, n);
    std::fill_n(out, head, value);
    const __m128i lanes = splat(value);
    std::size_t i = head;
    for (; i + kLanes <= n; i += kLanes) _mm_stream_si128(reinterpret_cast<__m128i*>(out + i), lanes);
    std::fill_n(out + i, n - i, value);
}

template <class T>
void stream_copy(T* out, const T* in, std::size_t n) {
    constexpr std::size_t kLanes = 16 / sizeof(T);
    const std::size_t head = head_to_alignment(out, n);
    std::copy_n(in, head, out);
    std::size_t i = head;
    for (; i + kLanes <= n; i += kLanes) {
        _mm_stream_si128(reinterpret_cast<__m128i*>(out + i), _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + i)));
    }
    std::copy_n(in + i, n - i, out + i);
}

// Makes the streamed stores visible to other threads (before the writer reports done).
inline void stream_fence() { _mm_sfence(); }

#else

template <class T>
void stream_fill(T* out, std::size_t n, T value) {
    std::fill_n(out, n, value);
}

template <class T>
void stream_copy(T* out, const T* in, std::size_t n) {
    std::copy_n(in, n, out);
}

inline void stream_fence() {}

#endif

}  // namespace libcam::detail
