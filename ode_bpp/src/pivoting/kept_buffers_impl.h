// KeptBuffers' members, for the one .cpp file where Contents is complete; that file then writes
// `template class KeptBuffers<Contents>;` (kept_buffers.h).
#pragma once

#include "pivoting/kept_buffers.h"

namespace ode_bpp::pivoting {

template <class Contents>
KeptBuffers<Contents>::KeptBuffers() : contents_(std::make_unique<Contents>()) {}

template <class Contents>
KeptBuffers<Contents>::~KeptBuffers() = default;

}  // namespace ode_bpp::pivoting
