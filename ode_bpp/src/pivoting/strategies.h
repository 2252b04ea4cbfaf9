// Constructors of the factor strategies (free_solver.h), one per BPP method.
#pragma once

#include <memory>

#include "pivoting/free_solver.h"

namespace ode_bpp::pivoting {

/// Alg. 1: gathers A_FF densely and factors it afresh (Eigen LLT) at every step; no L0.
std::unique_ptr<FreeSolver> make_dense_refactor_solver(const linalg::SymmetricRows& Ap);

/// How the skyline-based strategies obtain L_FF from L0.
enum class SkylineVariant {
    DenseDelete,    ///< BppDown (Alg. 2): dense storage, copy all of L0, delete every tight row
    SkylineDelete,  ///< BppSky (Alg. 2 + 3): envelope storage, copy L0's tail, delete tight rows
    CostModel,      ///< Bpp: envelope storage, per step the cheaper of deletion and partial refactoring
};

/// Alg. 2 (+3) and ours, on Ap's envelope (dense storage for DenseDelete).
std::unique_ptr<FreeSolver> make_skyline_solver(const linalg::SymmetricRows& Ap, SkylineVariant variant);

}  // namespace ode_bpp::pivoting
