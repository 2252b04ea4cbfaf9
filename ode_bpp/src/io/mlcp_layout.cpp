#include "io/mlcp_layout.h"

namespace ode_bpp::io {

Layout layout_of(const Header& h) {
    const std::uint64_t n = h.n;
    const bool has_blocks = (h.flags & flag::kBlocks) != 0;
    Layout l;
    l.b = l.a + 8 * triangle_entries(n);
    l.lo = l.b + 8 * n;
    l.hi = l.lo + 8 * n;
    l.findex = l.hi + 8 * n;
    l.block_row = l.findex + ((h.flags & flag::kFindex) ? 4 * n : 0);
    l.block_body = l.block_row + (has_blocks ? 4 * (std::uint64_t{h.num_blocks} + 1) : 0);
    l.x = l.block_body + (has_blocks ? 8 * std::uint64_t{h.num_blocks} : 0);
    l.meta = l.x + ((h.flags & flag::kReferenceX) ? 8 * n : 0);
    l.checksum = l.meta + h.meta_bytes;
    l.total = l.checksum + kChecksumBytes;
    return l;
}

}  // namespace ode_bpp::io
