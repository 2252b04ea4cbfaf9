// bench/report/physical_limit.cpp
#include "physical_limit.h"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <limits>
#include <utility>

#include "linalg/envelope.h"
#include "linalg/skyline_cholesky.h"
#include "linalg/skyline_solve.h"
#include "ordering/ordering.h"

namespace ode_bpp::bench {

namespace {


/// The free rows in the file's Cuthill-McKee order: perm_F[new] = old (original row index).
std::vector<int> free_rows_in_order(const MlcpFile& file, const std::vector<RowState>& states) {
    const std::vector<int> order = ordering::order_rows(
        file.n, file.A.data(), file.n, file.num_blocks(), file.block_row.empty() ? nullptr : file.block_row.data(),
        file.block_body.empty() ? nullptr : file.block_body.data(), ordering::OrderingKind::CuthillMcKee, nullptr);
    std::vector<int> free;
    for (int old : order)
        if (states[static_cast<std::size_t>(old)] == RowState::Free) free.push_back(old);
    return free;
}

/// A_FF (n_F x n_F, row-major) with rows and columns in the order `rows`.
std::vector<double> submatrix(const MlcpFile& file, const std::vector<int>& rows) {
    const std::size_t m = rows.size();
    std::vector<double> sub(m * m);
    for (std::size_t i = 0; i < m; ++i)
        for (std::size_t j = 0; j < m; ++j)
            sub[i * m + j] = file.A[static_cast<std::size_t>(rows[i]) * file.n + static_cast<std::size_t>(rows[j])];
    return sub;
}

double microseconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

double physical_limit_us(const MlcpFile& file, const std::vector<RowState>& states, int repeat) {
    if (static_cast<int>(states.size()) != file.n) return std::numeric_limits<double>::quiet_NaN();
    const std::vector<int> rows = free_rows_in_order(file, states);
    const int m = static_cast<int>(rows.size());
    if (m == 0) return 0.0;
    const std::vector<double> a_ff = submatrix(file, rows);
    const linalg::SkylineMatrix loaded = linalg::load_skyline(a_ff.data(), m, m, nullptr);
    std::vector<double> rhs(static_cast<std::size_t>(m));
    for (int i = 0; i < m; ++i) rhs[static_cast<std::size_t>(i)] = file.b[static_cast<std::size_t>(rows[i])];
    const int copies = calls_per_round(loaded.shape().size() + m);
    std::vector<double> times;
    for (int round = 0; round < std::max(1, repeat); ++round) {
        std::vector<linalg::SkylineMatrix> factors(static_cast<std::size_t>(copies), loaded);
        std::vector<std::vector<double>> x(static_cast<std::size_t>(copies), rhs);
        const auto start = std::chrono::steady_clock::now();
        for (int c = 0; c < copies; ++c) {
            if (linalg::skyline_cholesky(factors[static_cast<std::size_t>(c)], 0, {}) >= 0)
                return std::numeric_limits<double>::quiet_NaN();
            linalg::skyline_solve(factors[static_cast<std::size_t>(c)], x[static_cast<std::size_t>(c)].data());
        }
        times.push_back(microseconds_since(start) / copies);
    }
    return median_round(std::move(times));
}

int calls_per_round(std::int64_t entries_per_call) {
    // about 2 MB of doubles per round, summed over the calls
    constexpr std::int64_t kEntriesPerRound = 1 << 18;
    constexpr std::int64_t kMaxCalls = 2000;
    return static_cast<int>(std::clamp<std::int64_t>(kEntriesPerRound / std::max<std::int64_t>(entries_per_call, 1), 1,
                                                     kMaxCalls));
}

double median_round(std::vector<double> times) {
    std::sort(times.begin(), times.end());
    return times[times.size() / 2];
}

}  // namespace ode_bpp::bench
