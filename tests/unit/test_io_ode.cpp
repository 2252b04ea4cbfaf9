// Capturing the islands of a real ODE world step: the file holds exactly what ODE built.
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include <ode/mlcp.h>
#include <ode/ode.h>

#include "ode_bpp/capture.h"
#include "test_io_support.h"

namespace {

// The raw island, copied straight from the observer as the oracle for the capture.
struct Raw {
    int m = 0, nub = 0, nb = 0;
    std::vector<double> A_lower, b, lo, hi;
    std::vector<int> findex, joint_row, joint_m, joint_body;
};

struct Captured {
    std::vector<Raw> raw;
    std::vector<ode_bpp::MlcpFile> files;
    std::vector<ode_bpp::ReadResult> reread;
    std::vector<std::string> errors;
    std::string dir;
};

Raw copy_raw(const dMLCP& p) {
    Raw r;
    r.m = p.m, r.nub = p.nub, r.nb = p.nb;
    for (int i = 0; i < p.m; ++i) {
        if (p.A != nullptr)  // the dense form; the sparse form has no A to copy
            for (int j = 0; j <= i; ++j) r.A_lower.push_back(p.A[i * p.skip + j]);
        r.b.push_back(p.pairsbx[2 * i]);
        r.lo.push_back(p.pairslh[2 * i]);
        r.hi.push_back(p.pairslh[2 * i + 1]);
        r.findex.push_back(p.findex ? p.findex[i] : -1);
    }
    for (int k = 0; k < p.nj; ++k) {
        r.joint_row.push_back(p.joints[k].row);
        r.joint_m.push_back(p.joints[k].m);
        r.joint_body.push_back(p.joints[k].body[0]);
        r.joint_body.push_back(p.joints[k].body[1]);
    }
    return r;
}

void observe(const dMLCP* problem, const dMLCPIslandStats* stats, void* userdata) {
    if (stats) return;  // after the solve A may be destroyed; capture happens before
    auto* c = static_cast<Captured*>(userdata);
    c->raw.push_back(copy_raw(*problem));
    ode_bpp::Metadata meta;
    meta.set("scene", "box on a hinge");
    meta.set("island", std::to_string(c->files.size()));
    std::string error;
    auto file = ode_bpp::capture_from_ode(*problem, meta, &error);
    if (!file) c->errors.push_back(error);
    if (file) c->files.push_back(*file);
    const std::string path = c->dir + "/island" + std::to_string(c->reread.size()) + ".mlcp";
    if (!ode_bpp::write_mlcp_from_ode(path, *problem, meta, &error)) c->errors.push_back(error);
    c->reread.push_back(ode_bpp::read_mlcp(path));
}

// Two boxes on a hinge, the lower one on the ground, stepped with the named solver; every island
// is captured through the observer.
struct HingedBoxes {
    explicit HingedBoxes(const char* solver) {
        dInitODE2(0);
        captured.dir = (std::filesystem::temp_directory_path() /
                        ("ode_bpp_capture_" + std::to_string(::getpid()) + "_" + solver))
                           .string();
        std::filesystem::create_directories(captured.dir);
        world = dWorldCreate();
        dWorldSetGravity(world, 0, 0, -9.81);
        dWorldSetCFM(world, 1e-9);
        space = dSimpleSpaceCreate(nullptr);
        ground = dCreatePlane(space, 0, 0, 1, 0);
        contacts = dJointGroupCreate(0);
        lower = make_box(0.49);
        upper = make_box(1.6);
        dJointID hinge = dJointCreateHinge(world, nullptr);
        dJointAttach(hinge, lower, upper);
        dJointSetHingeAnchor(hinge, 0, 0, 1.05);
        dJointSetHingeAxis(hinge, 0, 1, 0);
        dWorldSetMLCPObserver(world, observe, &captured);
        solver_known = dWorldSetMLCPSolver(world, solver) != 0;
    }
    ~HingedBoxes() {
        dJointGroupDestroy(contacts);
        dSpaceDestroy(space);
        dWorldDestroy(world);
        dCloseODE();
        std::filesystem::remove_all(captured.dir);
    }
    HingedBoxes(const HingedBoxes&) = delete;
    HingedBoxes& operator=(const HingedBoxes&) = delete;

    dBodyID make_box(double z) {
        dBodyID body = dBodyCreate(world);
        dMass mass;
        dMassSetBoxTotal(&mass, 2.0, 1, 1, 1);
        dBodySetMass(body, &mass);
        dBodySetPosition(body, 0, 0, z);
        dGeomSetBody(dCreateBox(space, 1, 1, 1), body);
        return body;
    }
    // Contacts of the lower box with the ground, with pyramid friction (findex rows).
    void collide_and_step(double h) {
        dJointGroupEmpty(contacts);
        dContact contact[8];
        dGeomID box = dBodyGetFirstGeom(lower);
        const int count = dCollide(box, ground, 8, &contact[0].geom, sizeof(dContact));
        for (int i = 0; i < count; ++i) {
            contact[i].surface.mode = dContactApprox1;
            contact[i].surface.mu = 0.5;
            dJointAttach(dJointCreateContact(world, contacts, &contact[i]), lower, nullptr);
        }
        dWorldStep(world, h);
    }

    dWorldID world{};
    dSpaceID space{};
    dGeomID ground{};
    dJointGroupID contacts{};
    dBodyID lower{}, upper{};
    Captured captured;
    bool solver_known = false;
};

// ODE's own Dantzig: the island comes in the dense form, so the observer's copy of A is an oracle.
class OdeCapture : public ::testing::Test {
protected:
    HingedBoxes scene{"dantzig"};
    dWorldID& world = scene.world;
    Captured& captured = scene.captured;
    void collide_and_step(double h) { scene.collide_and_step(h); }
};

TEST_F(OdeCapture, FileHoldsWhatOdeBuilt) {
    collide_and_step(0.01);
    ASSERT_TRUE(captured.errors.empty()) << captured.errors.front();
    ASSERT_EQ(captured.files.size(), 1u);
    const Raw& raw = captured.raw[0];
    const ode_bpp::MlcpFile& f = captured.files[0];
    ASSERT_EQ(f.n, raw.m);
    ASSERT_GT(f.n, 5);
    EXPECT_EQ(f.nub, raw.nub);
    for (int i = 0, t = 0; i < f.n; ++i)
        for (int j = 0; j <= i; ++j, ++t) {
            EXPECT_EQ(f.A[i * f.n + j], raw.A_lower[t]);
            EXPECT_EQ(f.A[j * f.n + i], raw.A_lower[t]);
        }
    EXPECT_EQ(f.b, raw.b);
    EXPECT_EQ(f.lo, raw.lo);
    EXPECT_EQ(f.hi, raw.hi);
    EXPECT_EQ(f.findex, raw.findex);
    EXPECT_NE(std::count_if(f.findex.begin(), f.findex.end(), [](int v) { return v >= 0; }), 0);
    // joint k is block k
    ASSERT_EQ(f.num_blocks(), static_cast<int>(raw.joint_row.size()));
    for (int k = 0; k < f.num_blocks(); ++k) {
        EXPECT_EQ(f.block_row[k], raw.joint_row[k]);
        EXPECT_EQ(f.block_row[k + 1] - f.block_row[k], raw.joint_m[k]);
    }
    EXPECT_EQ(f.block_body, raw.joint_body);
    EXPECT_EQ(f.num_bodies, raw.nb);
}

TEST_F(OdeCapture, BlocksExplainTheSparsityOfA) {
    // docs/ode-world-step.md: block (i,j) of A is non-zero only where joints i and j share a body.
    collide_and_step(0.01);
    ASSERT_EQ(captured.files.size(), 1u);
    const ode_bpp::MlcpFile& f = captured.files[0];
    auto share_body = [&](int k, int l) {
        for (int a = 0; a < 2; ++a)
            for (int c = 0; c < 2; ++c)
                if (f.block_body[2 * k + a] >= 0 && f.block_body[2 * k + a] == f.block_body[2 * l + c]) return true;
        return false;
    };
    int coupled_pairs = 0;
    for (int k = 0; k < f.num_blocks(); ++k)
        for (int l = 0; l < k; ++l) {
            bool nonzero = false;
            for (int i = f.block_row[k]; i < f.block_row[k + 1]; ++i)
                for (int j = f.block_row[l]; j < f.block_row[l + 1]; ++j) nonzero |= f.A[i * f.n + j] != 0.0;
            if (!share_body(k, l)) {
                EXPECT_FALSE(nonzero) << "blocks " << k << ", " << l;
            }
            coupled_pairs += nonzero;
        }
    EXPECT_GT(coupled_pairs, 0);
}

TEST_F(OdeCapture, MetadataRecordsTheStep) {
    collide_and_step(0.01);
    ASSERT_EQ(captured.files.size(), 1u);
    const ode_bpp::Metadata& meta = captured.files[0].meta;
    ASSERT_NE(meta.find("step_size"), nullptr);
    EXPECT_EQ(std::stod(*meta.find("step_size")), 0.01);
    ASSERT_NE(meta.find("cfm"), nullptr);
    EXPECT_EQ(std::stod(*meta.find("cfm")), 1e-9);
    ASSERT_NE(meta.find("erp"), nullptr);
    EXPECT_EQ(std::stod(*meta.find("erp")), dWorldGetERP(world));
    ASSERT_NE(meta.find("scene"), nullptr);
    EXPECT_EQ(*meta.find("scene"), "box on a hinge");
}

TEST_F(OdeCapture, WrittenFileReadsBackIdentical) {
    for (int step = 0; step < 3; ++step) collide_and_step(0.01);
    ASSERT_TRUE(captured.errors.empty()) << captured.errors.front();
    ASSERT_EQ(captured.files.size(), 3u);  // one island a step
    ASSERT_EQ(captured.reread.size(), captured.files.size());
    for (std::size_t k = 0; k < captured.files.size(); ++k) {
        ASSERT_TRUE(captured.reread[k].ok) << captured.reread[k].error;
        EXPECT_EQ(io_test::encode(captured.reread[k].file), io_test::encode(captured.files[k]));
    }
}

TEST(OdeCaptureInput, JointsThatDoNotTileTheRowsAreRefused) {
    std::vector<double> A(4 * 4, 1.0), pairs(8, 0.0);
    dMLCPJoint joints[2] = {};
    joints[0].row = 0, joints[0].m = 2, joints[0].body[0] = 0, joints[0].body[1] = -1;
    joints[1].row = 3, joints[1].m = 1, joints[1].body[0] = 0, joints[1].body[1] = -1;  // row 2 is orphaned
    dMLCP p{};
    p.m = 3, p.skip = 4, p.A = A.data(), p.pairsbx = pairs.data(), p.pairslh = pairs.data();
    p.nj = 2, p.joints = joints, p.nb = 1;
    std::string error;
    EXPECT_FALSE(ode_bpp::capture_from_ode(p, {}, &error));
    EXPECT_NE(error.find("joint 1"), std::string::npos) << error;
}

}  // namespace

TEST(OdeCaptureForms, TheSparseFormCapturesTheFileTheDenseFormDoes) {
    // ode-bpp's "bpp" gets J, J M^-1 and the CFM instead of A (docs/ode-world-step.md); capture
    // builds A from them, and the first step (same state in both worlds) must give the same file
    HingedBoxes dense("dantzig"), sparse("bpp");
    ASSERT_TRUE(sparse.solver_known) << "bpp is not registered: link libode_bpp";
    dense.collide_and_step(0.01);
    sparse.collide_and_step(0.01);
    ASSERT_TRUE(sparse.captured.errors.empty()) << sparse.captured.errors.front();
    ASSERT_EQ(sparse.captured.files.size(), 1u);
    ASSERT_EQ(dense.captured.files.size(), 1u);
    const ode_bpp::MlcpFile &s = sparse.captured.files[0], &d = dense.captured.files[0];
    ASSERT_GT(s.n, 5);
    EXPECT_TRUE(sparse.captured.raw[0].A_lower.empty()) << "bpp's island came with a dense A";
    EXPECT_EQ(s.A, d.A);
    EXPECT_EQ(s.b, d.b);
    EXPECT_EQ(s.lo, d.lo);
    EXPECT_EQ(s.hi, d.hi);
    EXPECT_EQ(s.findex, d.findex);
    EXPECT_EQ(s.block_row, d.block_row);
    EXPECT_EQ(s.block_body, d.block_body);
}
