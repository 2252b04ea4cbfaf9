// Growing a reused buffer to exactly what the largest island needs.
//
// std::vector grows its capacity geometrically: libstdc++'s resize from s to n > capacity
// allocates max(2 s, n), and push_back doubles. A buffer kept across islands (docs/architecture.md,
// conventions: memory) then holds up to twice what the largest island met needs, and its size
// jumps by that much at the first island a few entries larger than any before: on the winch,
// the assembly's list of A's lower entries went from 128 kB to 256 kB at step 4,200 of a soak
// (docs/soak.md). Grown exactly, a buffer holds what the largest island needs, and a larger
// island adds only its extra entries.
#pragma once

#include <cstddef>
#include <vector>

namespace ode_bpp::linalg {

/// v.resize(n), with v's capacity raised to exactly n where it must grow (otherwise unchanged).
/// v: in/out.
template <class T>
void resize_exact(std::vector<T>& v, std::size_t n) {
    if (n > v.capacity()) v.reserve(n);
    v.resize(n);
}

/// Capacity for exactly n elements where v has less (otherwise unchanged); v's contents are kept.
template <class T>
void reserve_exact(std::vector<T>& v, std::size_t n) {
    if (n > v.capacity()) v.reserve(n);
}

}  // namespace ode_bpp::linalg
