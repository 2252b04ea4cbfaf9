// The structure an MLCP must have (findex, row blocks), as one set of rules that the file reader
// and writer (io/) and validate() (validation.h) share, so that a problem one of them accepts the
// others accept too. Index space: the problem's own rows.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace ode_bpp {

/// A structural defect at entry `index` of an array; reason names the entry and the rule.
struct StructureIssue {
    std::size_t index = 0;
    std::string reason;
};

/// findex (n entries): each -1, or a row j != i in [0, n) that is not itself a friction row
/// (findex[j] = -1: a friction row's normal is a normal).
std::optional<StructureIssue> check_findex(const int* findex, int n);
/// block_row (num_blocks + 1 entries): 0 first, n last, strictly increasing (no empty block).
std::optional<StructureIssue> check_block_row(const int* block_row, int num_blocks, int n);
/// True when a problem has row blocks (num_blocks > 0, both arrays given) and they tile rows
/// 0 .. n-1 by check_block_row: only then do its blocks describe its rows (numbering them, A's
/// structural pattern).
bool blocks_tile_rows(int n, int num_blocks, const int* block_row, const int* block_body);
/// block_body (2 num_blocks entries): each -1 (static environment) or in [0, num_bodies).
std::optional<StructureIssue> check_block_body(const int* block_body, int num_blocks, int num_bodies);

}  // namespace ode_bpp
