#include "structure_rules.h"

namespace ode_bpp {

std::optional<StructureIssue> check_findex(const int* findex, int n) {
    for (int i = 0; i < n; ++i) {
        const int f = findex[i];
        if (f == -1) continue;
        if (f < -1 || f >= n)
            return StructureIssue{std::size_t(i), "findex[" + std::to_string(i) + "] = " + std::to_string(f) +
                                             " out of range (-1 or 0.." + std::to_string(n - 1) + ")"};
        if (f == i)
            return StructureIssue{std::size_t(i), "findex[" + std::to_string(i) + "] refers to its own row"};
        if (findex[f] != -1)
            return StructureIssue{std::size_t(i), "findex[" + std::to_string(i) + "] = " + std::to_string(f) +
                                                      " refers to a friction row (findex[" + std::to_string(f) + "] = " +
                                                      std::to_string(findex[f]) + ")"};
    }
    return std::nullopt;
}

std::optional<StructureIssue> check_block_row(const int* block_row, int num_blocks, int n) {
    if (block_row[0] != 0)
        return StructureIssue{0, "block_row[0] = " + std::to_string(block_row[0]) + ", must be 0"};
    for (int k = 1; k <= num_blocks; ++k) {
        if (block_row[k] <= block_row[k - 1])
            return StructureIssue{std::size_t(k), "non-increasing block_row: block_row[" + std::to_string(k) +
                                             "] = " + std::to_string(block_row[k]) + " <= block_row[" +
                                             std::to_string(k - 1) + "] = " + std::to_string(block_row[k - 1])};
    }
    if (block_row[num_blocks] != n)
        return StructureIssue{std::size_t(num_blocks), "block_row[" + std::to_string(num_blocks) + "] = " +
                                                  std::to_string(block_row[num_blocks]) + ", must be n = " +
                                                  std::to_string(n)};
    return std::nullopt;
}

// check_block_row's test without its message: on an island of a few rows the message's
// std::optional<StructureIssue> cost more than the loop.
bool blocks_tile_rows(int n, int num_blocks, const int* block_row, const int* block_body) {
    if (num_blocks <= 0 || block_row == nullptr || block_body == nullptr || block_row[0] != 0) return false;
    for (int k = 1; k <= num_blocks; ++k)
        if (block_row[k] <= block_row[k - 1]) return false;
    return block_row[num_blocks] == n;
}

std::optional<StructureIssue> check_block_body(const int* block_body, int num_blocks, int num_bodies) {
    for (int k = 0; k < 2 * num_blocks; ++k) {
        const int body = block_body[k];
        if (body < -1 || body >= num_bodies)
            return StructureIssue{std::size_t(k), "block_body[" + std::to_string(k) + "] = " + std::to_string(body) +
                                             " out of range (-1 or 0.." + std::to_string(num_bodies - 1) + ")"};
    }
    return std::nullopt;
}

}  // namespace ode_bpp
