// A = J M^-1 J^T + diag(cfm) assembled from an island's sparse form (ode/assemble.h): the
// joints' structural pattern, the same rows as ODE's dense A with its blocks, and the reuse of
// the stored pattern when the next island has the same structure: a reused assembly must hold
// what a fresh one holds, in every order, whether entries become zero or stop being zero.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "ode/assemble.h"

namespace ode_bpp::ode {
namespace {

/// A chain of bodies 0 .. nb-1 with one joint per neighbouring pair plus one joint to the
/// static environment on body 0, each of `rows_per_joint` rows, with random J, J M^-1 and cfm.
struct Island {
    Island(int nb, int rows_per_joint, unsigned seed) : rng(seed) {
        for (int k = 0; k < nb; ++k) {
            dMLCPJoint joint{};
            joint.row = k * rows_per_joint;
            joint.m = rows_per_joint;
            joint.body[0] = k == 0 ? 0 : k - 1;
            joint.body[1] = k == 0 ? -1 : k;
            joints.push_back(joint);
        }
        p.m = nb * rows_per_joint;
        p.nb = nb;
        p.nj = nb;
        p.joints = joints.data();
        J.resize(2 * static_cast<std::size_t>(p.m) * dMLCP_J_ROW);
        JinvM.resize(2 * static_cast<std::size_t>(p.m) * dMLCP_JINVM_ROW);
        cfm.resize(static_cast<std::size_t>(p.m));
        randomize();
        p.J = J.data();
        p.JinvM = JinvM.data();
        p.cfm = cfm.data();
    }
    /// New values, the same structure.
    void randomize() {
        std::uniform_real_distribution<double> value(-1.0, 1.0);
        for (double& v : J) v = value(rng);
        for (double& v : JinvM) v = value(rng);
        for (double& v : cfm) v = 1e-3 + std::abs(value(rng));
    }
    /// Row r's J (both sides) to zero: A(r, j) = 0 for every j != r.
    void zero_row(int r) {
        for (int side = 0; side < 2; ++side) {
            const dMLCPJoint& joint = joints[static_cast<std::size_t>(r / joints[0].m)];
            const int index = 2 * joint.row + side * joint.m + (r - joint.row);
            std::fill_n(J.begin() + static_cast<std::ptrdiff_t>(index) * dMLCP_J_ROW, dMLCP_J_ROW, 0.0);
            std::fill_n(JinvM.begin() + static_cast<std::ptrdiff_t>(index) * dMLCP_JINVM_ROW, dMLCP_JINVM_ROW, 0.0);
        }
    }
    /// Row r's J for its joint's second body to zero: A(i, r) = 0 for the rows i of the next
    /// joint (they share that body alone), while A(r, r) and r's own joint's block stay non-zero.
    void zero_second_body_of_row(int r) {
        const dMLCPJoint& joint = joints[static_cast<std::size_t>(r / joints[0].m)];
        const int index = 2 * joint.row + joint.m + (r - joint.row);
        std::fill_n(J.begin() + static_cast<std::ptrdiff_t>(index) * dMLCP_J_ROW, dMLCP_J_ROW, 0.0);
    }
    std::mt19937 rng;
    std::vector<dMLCPJoint> joints;
    std::vector<double> J, JinvM, cfm;
    dMLCP p{};
};

/// Rows assembled from scratch (fresh buffers, fresh matrix, no reuse).
linalg::SymmetricRows fresh_rows(const dMLCP& island, const std::vector<int>& order) {
    linalg::SymmetricRows rows;
    AssemblyBuffers buffers;
    assemble_rows(island, rows, buffers, order);
    return rows;
}

std::vector<double> lower_of(const linalg::SymmetricRows& rows) {
    std::vector<double> A(static_cast<std::size_t>(rows.n()) * rows.n(), 0.0);
    rows.to_dense_lower(A.data(), rows.n());
    return A;
}

/// Products with a vector: the same whatever zeros the pattern stores.
std::vector<double> product(const linalg::SymmetricRows& rows) {
    std::vector<double> x(static_cast<std::size_t>(rows.n())), y;
    std::iota(x.begin(), x.end(), 1.0);
    rows.multiply(x, 0.0, y);
    return y;
}

/// What a solve may see of A: values, products, the pattern and its row profile (which shapes
/// the envelope) must be a fresh assembly's.
void expect_as_fresh(const linalg::SymmetricRows& rows, const dMLCP& island, const std::vector<int>& order,
                     const char* when) {
    const linalg::SymmetricRows fresh = fresh_rows(island, order);
    EXPECT_EQ(lower_of(rows), lower_of(fresh)) << when;
    EXPECT_EQ(product(rows), product(fresh)) << when;
    EXPECT_EQ(rows.off_diagonal_entries(), fresh.off_diagonal_entries()) << when;
    EXPECT_EQ(rows.row_profile(), fresh.row_profile()) << when;
    EXPECT_EQ(rows.order(), fresh.order()) << when;
}

std::vector<int> reversed(int n) {
    std::vector<int> order(static_cast<std::size_t>(n));
    std::iota(order.rbegin(), order.rend(), 0);
    return order;
}

/// Entries the chain's joints form: each joint's own lower triangle and, for every joint after
/// the first, all its rows against the previous joint's (they share one body).
int structural_lower_entries(int joints, int rows_per_joint) {
    return joints * rows_per_joint * (rows_per_joint - 1) / 2 + (joints - 1) * rows_per_joint * rows_per_joint;
}

class OdeAssembly : public ::testing::TestWithParam<bool> {
protected:
    std::vector<int> order_for(int n) const { return GetParam() ? reversed(n) : std::vector<int>{}; }
};

TEST_P(OdeAssembly, ReusedPatternHoldsAFreshAssemblysValues) {
    Island island(12, 3, 7);
    const std::vector<int> order = order_for(island.p.m);
    linalg::SymmetricRows rows;
    AssemblyBuffers buffers;
    for (int step = 0; step < 4; ++step) {
        assemble_rows(island.p, rows, buffers, order);
        expect_as_fresh(rows, island.p, order, "after a step");
        island.randomize();
    }
}

TEST_P(OdeAssembly, StoresTheJointsPatternWhateverTheZeros) {
    Island island(10, 3, 11);
    const std::vector<int> order = order_for(island.p.m);
    linalg::SymmetricRows rows;
    AssemblyBuffers buffers;
    island.zero_row(4);  // A(4, j) = 0 for every j != 4
    assemble_rows(island.p, rows, buffers, order);
    EXPECT_EQ(rows.off_diagonal_entries(), 2 * structural_lower_entries(10, 3));
    expect_as_fresh(rows, island.p, order, "with row 4 zero");
    island.randomize();  // row 4 non-zero again, and row 13 zero
    island.zero_row(13);
    assemble_rows(island.p, rows, buffers, order);
    expect_as_fresh(rows, island.p, order, "with row 13 zero");
    island.randomize();
    island.zero_second_body_of_row(13);  // A(i, 13) = 0 for rows 15-17 only
    assemble_rows(island.p, rows, buffers, order);
    expect_as_fresh(rows, island.p, order, "with A(15..17, 13) zero");
}

TEST_P(OdeAssembly, OtherStructureOrOrderIsAssembledAfresh) {
    Island first(10, 3, 3), second(9, 3, 4);
    const std::vector<int> order = order_for(first.p.m);
    linalg::SymmetricRows rows;
    AssemblyBuffers buffers;
    assemble_rows(first.p, rows, buffers, order);
    assemble_rows(second.p, rows, buffers, {});
    expect_as_fresh(rows, second.p, {}, "another structure");
    assemble_rows(first.p, rows, buffers, reversed(first.p.m));
    assemble_rows(first.p, rows, buffers, {});  // the same island, another order
    expect_as_fresh(rows, first.p, {}, "another order");
}

TEST(OdeAssemblyForms, DenseAWithItsBlocksStoresTheSameRows) {
    Island island(10, 3, 17);
    island.zero_row(13);
    island.zero_second_body_of_row(4);
    const linalg::SymmetricRows sparse = fresh_rows(island.p, {});
    std::vector<double> A(static_cast<std::size_t>(island.p.m) * island.p.m, 0.0);
    AssemblyBuffers buffers;
    assemble_dense_lower(island.p, A.data(), island.p.m, buffers);
    std::vector<int> block_row, block_body;
    for (const dMLCPJoint& joint : island.joints) {
        block_row.push_back(joint.row);
        block_body.insert(block_body.end(), {joint.body[0], joint.body[1]});
    }
    block_row.push_back(island.p.m);
    Problem problem;
    problem.n = island.p.m;
    problem.A = A.data();
    problem.lda = island.p.m;
    problem.num_blocks = island.p.nj;
    problem.block_row = block_row.data();
    problem.block_body = block_body.data();
    const linalg::SymmetricRows dense(problem, {});
    ASSERT_EQ(dense.off_diagonal_entries(), sparse.off_diagonal_entries());
    for (int i = 0; i < dense.n(); ++i) {
        ASSERT_EQ(dense.diag(i), sparse.diag(i));
        ASSERT_EQ(dense.row_end(i) - dense.row_begin(i), sparse.row_end(i) - sparse.row_begin(i)) << "row " << i;
        for (int k = dense.row_begin(i), l = sparse.row_begin(i); k < dense.row_end(i); ++k, ++l) {
            EXPECT_EQ(dense.col(k), sparse.col(l)) << "row " << i;
            EXPECT_EQ(dense.val(k), sparse.val(l)) << "row " << i;
        }
    }
    problem.num_blocks = 0;  // without blocks, only the non-zeros
    EXPECT_LT(linalg::SymmetricRows(problem, {}).off_diagonal_entries(), sparse.off_diagonal_entries());
}

INSTANTIATE_TEST_SUITE_P(StoredOrders, OdeAssembly, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) {
                             return info.param ? std::string("Reordered") : std::string("IslandOrder");
                         });

}  // namespace
}  // namespace ode_bpp::ode
