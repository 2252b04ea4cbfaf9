// The sparse world step against the dense one: every scene stepped twice from the same start, once
// with "bpp" in the sparse form (ODE hands over J, J M^-1 and the CFM; A is assembled from them,
// ode/assemble.h) and once with the same solver fed ODE's dense A (ode_bpp_register_dense_form).
// Each island's x must agree to 1e-10 relative, and the trajectories must stay together for 100
// steps. (The assembly sums every entry in ODE's order, so in practice they agree bit for bit.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "ode_bpp/ode.h"
#include "scenes/scene.h"
#include "scene_test_support.h"

namespace ode_bpp::scenes {
namespace {

constexpr const char* kDenseForm = "bpp-dense-form";
constexpr int kSteps = 100;

/// Each island's x, in the order the world step solved them (single-threaded: deterministic).
struct Solutions {
    std::vector<std::vector<double>> islands;
    int sparse_islands = 0;  ///< islands that came in the sparse form (A null)
};

void record(const dMLCP* p, const dMLCPIslandStats* stats, void* data) {
    auto& out = *static_cast<Solutions*>(data);
    if (stats == nullptr) {
        out.sparse_islands += p->A == nullptr ? 1 : 0;
        return;
    }
    std::vector<double> x(static_cast<std::size_t>(p->m));
    for (int i = 0; i < p->m; ++i) x[i] = p->pairsbx[2 * i + 1];
    out.islands.push_back(std::move(x));
}

struct SceneRun {
    explicit SceneRun(const std::string& scene_name, const std::string& solver)
        : scene(make_scene(scene_name)), world(params_for(solver)) {
        scene->build(world);
        dWorldSetMLCPObserver(world.world(), &record, &solutions);
    }
    static SceneParams params_for(const std::string& solver) {
        SceneParams params;
        params.solver = solver;
        return params;
    }
    bool step() {
        solutions.islands.clear();
        scene->control(world, world.time());
        return world.step();
    }
    std::unique_ptr<Scene> scene;
    SceneWorld world;
    Solutions solutions;
};

double largest_relative_difference(const Solutions& a, const Solutions& b) {
    double worst = 0;
    for (std::size_t k = 0; k < a.islands.size(); ++k) {
        const std::vector<double>&xa = a.islands[k], &xb = b.islands[k];
        double scale = 1;
        for (double v : xa) scale = std::max(scale, std::abs(v));
        for (std::size_t i = 0; i < xa.size(); ++i) worst = std::max(worst, std::abs(xa[i] - xb[i]) / scale);
    }
    return worst;
}

class SparseForm : public ::testing::TestWithParam<std::string> {
protected:
    static void SetUpTestSuite() { ASSERT_EQ(ode_bpp_register_dense_form("bpp", kDenseForm), 1); }
};

TEST_P(SparseForm, GivesTheDenseFormsAnswersAndTrajectory) {
    SceneRun sparse(GetParam(), "bpp"), dense(GetParam(), kDenseForm);
    int islands = 0;
    for (int s = 0; s < kSteps; ++s) {
        ASSERT_TRUE(sparse.step()) << "sparse form, step " << s;
        ASSERT_TRUE(dense.step()) << "dense form, step " << s;
        ASSERT_EQ(sparse.solutions.islands.size(), dense.solutions.islands.size()) << "step " << s;
        for (std::size_t k = 0; k < sparse.solutions.islands.size(); ++k)
            ASSERT_EQ(sparse.solutions.islands[k].size(), dense.solutions.islands[k].size()) << "step " << s;
        islands += static_cast<int>(sparse.solutions.islands.size());
        EXPECT_LE(largest_relative_difference(sparse.solutions, dense.solutions), 1e-10) << "step " << s;
        ASSERT_LE(largest_position_difference(sparse.world, dense.world), 1e-9) << "step " << s;
    }
    RecordProperty("islands", islands);
    RecordProperty("largest_position_difference", largest_position_difference(sparse.world, dense.world) == 0 ? "0 (bit for bit)" : "non-zero");
    EXPECT_GT(islands, 0) << "no island was solved: the comparison compared nothing";
    EXPECT_EQ(sparse.solutions.sparse_islands, islands) << "the sparse run must get every island in the sparse form";
    EXPECT_EQ(dense.solutions.sparse_islands, 0) << "the dense-form solver must get ODE's dense A";
}

INSTANTIATE_TEST_SUITE_P(EveryScene, SparseForm, ::testing::ValuesIn(scene_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace ode_bpp::scenes
