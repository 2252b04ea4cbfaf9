#include "pivoting/free_solver.h"

#include <cmath>
#include <limits>

#include "pivoting/strategies.h"

namespace ode_bpp::pivoting {

double FreeSolver::factor_error(const std::vector<char>&) const { return std::numeric_limits<double>::quiet_NaN(); }

std::unique_ptr<FreeSolver> make_free_solver(Method method, const linalg::SymmetricRows& Ap, StrategyBuffers& buffers) {
    switch (method) {
        case Method::BppChol: return make_dense_refactor_solver(Ap, buffers.dense);
        case Method::BppDown: return make_skyline_solver(Ap, SkylineVariant::DenseDelete, buffers.skyline);
        case Method::BppSky: return make_skyline_solver(Ap, SkylineVariant::SkylineDelete, buffers.skyline);
        case Method::Bpp: return make_skyline_solver(Ap, SkylineVariant::CostModel, buffers.skyline);
        default: return nullptr;
    }
}

}  // namespace ode_bpp::pivoting
