// The buffers of one stage of a solve, kept by the caller (ode_bpp/workspace.h) so that their
// capacity outlives one run, while their type stays private to the stage's .cpp file: a header
// names KeptBuffers<struct LoopBuffers>, and the .cpp that defines LoopBuffers instantiates the
// class there (kept_buffers_impl.h).
#pragma once

#include <memory>

namespace ode_bpp::pivoting {

/// Owns one Contents, made with it. One run per buffers at a time.
template <class Contents>
class KeptBuffers {
public:
    KeptBuffers();
    ~KeptBuffers();
    KeptBuffers(const KeptBuffers&) = delete;
    KeptBuffers& operator=(const KeptBuffers&) = delete;

    Contents& contents() { return *contents_; }

private:
    std::unique_ptr<Contents> contents_;
};

}  // namespace ode_bpp::pivoting
