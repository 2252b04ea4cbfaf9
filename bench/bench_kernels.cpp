// Speed of the linear-algebra kernels (paper Alg. 2, Alg. 3 and Sec. 3.4).
//
//   BM_Factor/<storage>/<m>           load A into L and factor it (eigen_llt: Eigen's dense LLT);
//                                     dense_spd / eigen_llt_spd: Fig. 4's random dense SPD matrix
//   BM_Delete/<storage>/<m>/<where>   restore what a deletion writes (columns >= i and row i),
//                                     then delete row i at begin (0), middle (m/2) or end (9m/10)
//   BM_Solve/<storage>/<m>            one forward and backward substitution
// <storage>: skyline (band of half-width 12, like ODE chains), dense (the same matrix in dense
// storage, the same kernels), dense_loop (Delete only: a plain column-major loop, the reference
// the dense path must not lose to). Counter ns_per_unit: time per CostModel unit.
// Fig. 4 is in bench_fig4.cpp. For a table: --benchmark_out=kernels.csv --benchmark_out_format=csv
#include <benchmark/benchmark.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "kernel_fixtures.h"
#include "linalg/cost_model.h"
#include "linalg/row_delete.h"
#include "linalg/skyline.h"
#include "linalg/skyline_cholesky.h"
#include "linalg/skyline_solve.h"

namespace {

using namespace ode_bpp::bench;

/// Counter ns_per_unit: time per CostModel unit (refactor_cost or delete_cost), the calibration
/// the pivoting loop's price of a step needs (restoring copies included in the time).
void report_time_per_unit(benchmark::State& state, double units_per_iteration) {
    if (units_per_iteration <= 0) return;
    state.counters["ns_per_unit"] = benchmark::Counter(units_per_iteration / 1e9,
        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void factor(benchmark::State& state, bool dense_matrix, bool dense_storage, int m) {
    const Fixture& f = fixture(dense_matrix, dense_storage, m);
    SkylineMatrix L = f.A_lower;
    for (auto _ : state) {
        L.copy_tail_from(f.A_lower, 0);
        benchmark::DoNotOptimize(ode_bpp::linalg::skyline_cholesky(L, 0, {}));
        benchmark::ClobberMemory();
    }
    report_time_per_unit(state, ode_bpp::linalg::CostModel(L.shape()).refactor_cost(0));
}

void factor_eigen(benchmark::State& state, bool dense_matrix, int m) {
    const MatrixXd A = to_eigen(fixture(dense_matrix, true, m).A, m);
    Eigen::LLT<MatrixXd> llt(m);
    for (auto _ : state) {
        llt.compute(A);
        benchmark::DoNotOptimize(llt.matrixLLT().data());
        benchmark::ClobberMemory();
    }
}

int delete_position(int m, const std::string& where) {
    if (where == "begin") return 0;
    if (where == "middle") return m / 2;
    return 9 * m / 10;
}

void delete_row(benchmark::State& state, bool dense, int m, int i) {
    const Fixture& f = fixture(false, dense, m);
    SkylineMatrix L = f.L0;
    std::vector<double> work(static_cast<std::size_t>(m));
    const std::vector<int> rows{i};
    for (auto _ : state) {
        L.copy_tail_from(f.L0, i);
        L.copy_rows_from(f.L0, rows, i);
        ode_bpp::linalg::skyline_delete_row(L, i, work);
        benchmark::ClobberMemory();
    }
    report_time_per_unit(state, ode_bpp::linalg::CostModel(L.shape()).delete_cost(i));
}

/// The reference: the same rank-1 update as one fused Givens loop over a column-major dense
/// matrix, restoring the same entries (rows >= k of columns k >= i, row i before column i).
void delete_row_dense_loop(benchmark::State& state, int m, int i) {
    const MatrixXd L0 = MatrixXd(to_eigen(fixture(false, true, m).A, m).llt().matrixL());
    MatrixXd L = L0;
    std::vector<double> sigma(static_cast<std::size_t>(m));
    for (auto _ : state) {
        for (int k = i; k < m; ++k) std::copy(&L0(k, k), &L0(0, k) + m, &L(k, k));
        for (int j = 0; j < i; ++j) L(i, j) = L0(i, j);
        for (int r = i + 1; r < m; ++r) sigma[r] = L(r, i);
        for (int k = i + 1; k < m; ++k) {
            const double y = L(k, k), x = sigma[k];
            const double r = std::sqrt(y * y + x * x), c = y / r, s = x / r;
            L(k, k) = r;
            double* column = &L(0, k);
            for (int row = k + 1; row < m; ++row) {
                const double l = column[row];
                column[row] = c * l + s * sigma[row];
                sigma[row] = c * sigma[row] - s * l;
            }
        }
        for (int r = i; r < m; ++r) L(r, i) = r == i ? 1.0 : 0.0;
        for (int j = 0; j < i; ++j) L(i, j) = 0.0;
        benchmark::ClobberMemory();
    }
}

void solve(benchmark::State& state, bool dense, int m) {
    const Fixture& f = fixture(false, dense, m);
    std::vector<double> rhs(static_cast<std::size_t>(m), 1.0), x(rhs);
    for (auto _ : state) {
        std::copy(rhs.begin(), rhs.end(), x.begin());
        ode_bpp::linalg::skyline_solve(f.L0, x.data());
        benchmark::DoNotOptimize(x.data());
    }
}

void register_all() {
    for (int m : kSizes) {
        const std::string size = "/" + std::to_string(m);
        benchmark::RegisterBenchmark(("BM_Factor/skyline" + size).c_str(), factor, false, false, m)
            ->Unit(benchmark::kMicrosecond);
        benchmark::RegisterBenchmark(("BM_Factor/dense" + size).c_str(), factor, false, true, m)
            ->Unit(benchmark::kMicrosecond);
        benchmark::RegisterBenchmark(("BM_Factor/eigen_llt" + size).c_str(), factor_eigen, false, m)
            ->Unit(benchmark::kMicrosecond);
        benchmark::RegisterBenchmark(("BM_Factor/dense_spd" + size).c_str(), factor, true, true, m)
            ->Unit(benchmark::kMicrosecond);
        benchmark::RegisterBenchmark(("BM_Factor/eigen_llt_spd" + size).c_str(), factor_eigen, true, m)
            ->Unit(benchmark::kMicrosecond);
    }
    for (int m : kSizes)
        for (const char* where : {"begin", "middle", "end"}) {
            const int i = delete_position(m, where);
            const std::string suffix = "/" + std::to_string(m) + "/" + where;
            benchmark::RegisterBenchmark(("BM_Delete/skyline" + suffix).c_str(), delete_row, false, m, i)
                ->Unit(benchmark::kMicrosecond);
            benchmark::RegisterBenchmark(("BM_Delete/dense" + suffix).c_str(), delete_row, true, m, i)
                ->Unit(benchmark::kMicrosecond);
            benchmark::RegisterBenchmark(("BM_Delete/dense_loop" + suffix).c_str(), delete_row_dense_loop, m, i)
                ->Unit(benchmark::kMicrosecond);
        }
    for (int m : kSizes)
        for (bool dense : {false, true}) {
            const std::string storage = dense ? "dense" : "skyline";
            benchmark::RegisterBenchmark(("BM_Solve/" + storage + "/" + std::to_string(m)).c_str(), solve, dense, m)
                ->Unit(benchmark::kMicrosecond);
        }
}

}  // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    register_all();
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
