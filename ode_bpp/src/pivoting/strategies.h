// Constructors of the factor strategies (free_solver.h), one per BPP method.
#pragma once

#include <memory>

#include "pivoting/free_solver.h"
#include "pivoting/kept_buffers.h"

namespace ode_bpp::pivoting {

/// The buffers of the dense refactoring (dense_refactor_solver.cpp), kept by the caller so that
/// their capacity outlives one solve. One strategy per buffers at a time.
struct DenseRefactorVectors;
using DenseRefactorBuffers = KeptBuffers<DenseRefactorVectors>;
extern template class KeptBuffers<DenseRefactorVectors>;  // instantiated where DenseRefactorVectors is defined

/// Alg. 1: gathers A_FF densely and factors it afresh (Eigen LLT) at every step; no L0.
/// buffers: where it works; they must outlive the strategy.
std::unique_ptr<FreeSolver> make_dense_refactor_solver(const linalg::SymmetricRows& Ap, DenseRefactorBuffers& buffers);

/// The buffers of the skyline strategies (skyline_solver.cpp: the envelope's shape and cost
/// model, A's envelope, L0 and the working factor), kept by the caller so that their capacity
/// outlives one solve, and the shape and cost model with them while the matrix's envelope stays
/// the same (an island of unchanged structure, step after step). One strategy per buffers at a time.
struct SkylineStorage;
using SkylineBuffers = KeptBuffers<SkylineStorage>;
extern template class KeptBuffers<SkylineStorage>;  // instantiated where SkylineStorage is defined

/// The buffers of every factor strategy (make_free_solver).
struct StrategyBuffers {
    DenseRefactorBuffers dense;
    SkylineBuffers skyline;
};

/// How the skyline-based strategies obtain L_FF from L0.
enum class SkylineVariant {
    DenseDelete,    ///< BppDown (Alg. 2): dense storage, copy all of L0, delete every tight row
    SkylineDelete,  ///< BppSky (Alg. 2 + 3): envelope storage, copy L0's tail, delete tight rows
    CostModel,      ///< Bpp: envelope storage, per step the cheaper of deletion and partial refactoring
};

/// Alg. 2 (+3) and ours, on Ap's envelope (dense storage for DenseDelete). buffers: where it
/// works; they must outlive the strategy.
std::unique_ptr<FreeSolver> make_skyline_solver(const linalg::SymmetricRows& Ap, SkylineVariant variant,
                                                SkylineBuffers& buffers);

}  // namespace ode_bpp::pivoting
