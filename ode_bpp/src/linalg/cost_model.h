// Operation counts of the skyline kernels, for choosing per pivot step between copying L0 and
// deleting the tight rows (Alg. 2) or refactoring from the first changed column (docs/maths.md: what deletion and refactoring cost).
#pragma once

#include <cstddef>
#include <vector>

#include "linalg/skyline.h"

namespace ode_bpp::linalg {

/// Built once per factor shape (O(n)); every query is O(1). Index space: the shape's.
/// Units: delete_cost counts entries rotated (each costs two multiply-adds over two vector
/// passes); refactor_cost counts multiply-adds of the column updates plus one per entry scaled;
/// copy_cost counts entries copied. Compare them only through timings per unit measured on
/// the same machine (bench/bench_kernels.cpp reports them).
class CostModel {
public:
    explicit CostModel(const SkylineShape& shape);

    /// Entries touched by one skyline_delete_row at i: sum over k > i of (sky[k] - k + 1).
    /// Exact when sigma is dense in its support; the kernel skips columns where sigma_k = 0.
    double delete_cost(int i) const;
    /// Multiply-adds of skyline_cholesky from column k0 with nothing removed:
    /// sum over k >= k0 of [ sum over j < k with sky[j] >= k of (sky[j] - k + 1) ] + (sky[k] - k + 1).
    /// Removed indices and exact zeros L(k,j) = 0 are skipped by the kernel, so with a removed set
    /// this is an upper bound.
    double refactor_cost(int k0) const;
    /// The same with the indices `removed` (ascending) left out, as skyline_cholesky skips them:
    /// sum over kept k >= k0 of [ sum over kept j < k with sky[j] >= k of (sky[j] - k + 1) ] +
    /// (sky[k] - k + 1). O(n - first column holding row k0) per call. Without it the model priced
    /// a refactor of a tail whose rows were 70 % tight as if none were, and chose deletions that
    /// took twice as long (a forklift frame: bpp 0.7x bpp-chol; refactoring: 1.4x).
    double refactor_cost(int k0, const std::vector<int>& removed) const;
    /// Entries copied by SkylineMatrix::copy_tail_from(other, k0).
    double copy_cost(int k0) const;

private:
    std::vector<double> delete_suffix_;    ///< n + 1: delete_suffix_[k] = sum_{k' >= k} height(k')
    std::vector<double> refactor_suffix_;  ///< n + 1: refactor_suffix_[k] = sum_{k' >= k} cost of column k'
    std::vector<std::ptrdiff_t> colptr_;   ///< n + 1
    std::vector<int> sky_;                 ///< n: the shape's sky
    std::vector<int> first_column_;        ///< n: first column j with sky[j] >= k (nondecreasing)
};

/// CostModel(shape).refactor_cost(0), the multiply-adds of factoring the whole envelope, without
/// building the model: O(n), nothing allocated. Pricing an ordering starts with it (its factor
/// is a lower bound of its price: ordering/ordering_choice.cpp).
double full_refactor_cost(const SkylineShape& shape);

}  // namespace ode_bpp::linalg
