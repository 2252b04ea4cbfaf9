// Prices of one pivot step's ways to L_FF, from linalg::CostModel's operation counts; shared by
// the Bpp strategy (which way to take) and the ordering choice (which ordering makes steps cheap).
#pragma once

#include <vector>

#include "linalg/cost_model.h"

namespace ode_bpp::linalg {

/// Relative prices of the CostModel's units (linalg/cost_model.h): a rotated entry costs two
/// multiply-adds (Alg. 3 lines 13-14), a refactor unit one, a copied entry a fraction of one.
constexpr double kDeleteUnit = 2.0;
constexpr double kRefactorUnit = 1.0;
constexpr double kCopyUnit = 0.25;

/// Copy L0 from column copy_from, then delete the tight rows (ascending, permuted space).
inline double deletion_price(const CostModel& cost, const std::vector<int>& tight_rows, int copy_from) {
    double price = kCopyUnit * cost.copy_cost(copy_from);
    for (int i : tight_rows) price += kDeleteUnit * cost.delete_cost(i);
    return price;
}

/// Copy L0 from column copy_from (and Ap's tail), then refactor from the first tight row,
/// skipping the tight ones (ascending, permuted space, at least one).
inline double refactor_price(const CostModel& cost, const std::vector<int>& tight_rows, int copy_from) {
    return kCopyUnit * cost.copy_cost(copy_from) + kRefactorUnit * cost.refactor_cost(tight_rows.front(), tight_rows);
}

}  // namespace ode_bpp::linalg
