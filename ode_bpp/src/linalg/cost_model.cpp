#include "linalg/cost_model.h"

#include <algorithm>

namespace ode_bpp::linalg {

namespace {

/// Calls column(k, j_first, cost_k) for k = 0 .. n-1, where j_first is the first column j with
/// sky[j] >= k and cost_k the multiply-adds spent on column k by the left-looking update (for
/// every earlier column j reaching row k, rows k .. sky[j]) plus its height(k) scalings:
/// cost_k = sum_{j_first <= j < k} (sky[j] - k + 1) + height(k), from a running window sum of sky.
template <class Column>
void for_each_column_cost(const SkylineShape& shape, Column&& column) {
    double window_sky = 0;  // sum of sky[j] over j_first <= j < k
    int j_first = 0;
    for (int k = 0; k < shape.n; ++k) {
        for (; shape.sky[j_first] < k; ++j_first) window_sky -= shape.sky[j_first];
        const double update = window_sky - static_cast<double>(k - j_first) * (k - 1);
        column(k, j_first, update + shape.height(k));
        window_sky += shape.sky[k];
    }
}

}  // namespace

CostModel::CostModel(const SkylineShape& shape)
    : delete_suffix_(static_cast<std::size_t>(shape.n) + 1, 0.0),
      refactor_suffix_(static_cast<std::size_t>(shape.n) + 1, 0.0),
      colptr_(shape.colptr),
      sky_(shape.sky),
      first_column_(static_cast<std::size_t>(shape.n), 0) {
    const int n = shape.n;
    std::vector<double> column_cost(static_cast<std::size_t>(n), 0.0);
    for_each_column_cost(shape, [&](int k, int j_first, double cost) {
        first_column_[k] = j_first;
        column_cost[k] = cost;
    });
    for (int k = n - 1; k >= 0; --k) {
        delete_suffix_[k] = delete_suffix_[k + 1] + shape.height(k);
        refactor_suffix_[k] = refactor_suffix_[k + 1] + column_cost[k];
    }
}

double full_refactor_cost(const SkylineShape& shape) {
    double total = 0;
    for_each_column_cost(shape, [&total](int, int, double cost) { total += cost; });
    return total;
}

double CostModel::delete_cost(int i) const {
    const int n = static_cast<int>(delete_suffix_.size()) - 1;
    return delete_suffix_[std::min(i + 1, n)];
}

double CostModel::refactor_cost(int k0) const { return refactor_suffix_[k0]; }

double CostModel::refactor_cost(int k0, const std::vector<int>& removed) const {
    const int n = static_cast<int>(sky_.size());
    if (k0 >= n) return 0;
    // removed[] cursors for the window's two ends, both moving forward
    std::size_t at_front = 0, at_back = 0;
    const auto removed_at = [&](std::size_t& cursor, int j) {
        while (cursor < removed.size() && removed[cursor] < j) ++cursor;
        return cursor < removed.size() && removed[cursor] == j;
    };
    // window: the kept columns j in [back, k) that reach row k, as their count and sum of sky[j]
    int back = first_column_[k0];
    double count = 0, sky_sum = 0, cost = 0;
    for (int j = back; j < k0; ++j)
        if (!removed_at(at_front, j)) {
            count += 1;
            sky_sum += sky_[j];
        }
    for (int k = k0; k < n; ++k) {
        for (; back < first_column_[k]; ++back)
            if (!removed_at(at_back, back)) {
                count -= 1;
                sky_sum -= sky_[back];
            }
        if (removed_at(at_front, k)) continue;
        cost += sky_sum - count * (k - 1) + (sky_[k] - k + 1);  // sum_j (sky[j] - k + 1) + height(k)
        count += 1;
        sky_sum += sky_[k];
    }
    return cost;
}

double CostModel::copy_cost(int k0) const { return static_cast<double>(colptr_.back() - colptr_[k0]); }

}  // namespace ode_bpp::linalg
