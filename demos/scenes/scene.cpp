// demos/scenes/scene.cpp: the world every scene runs in, and the registry of scenes by name.
#include "scenes/scene.h"

#include <ode/mlcp.h>

#include "ode_bpp/ode.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "scenes/classic.h"
#include "scenes/contact.h"
#include "scenes/joint_gap.h"
#include "scenes/paper_scenes.h"

namespace ode_bpp::scenes {

namespace {

// Contacts closer than this are not corrected by ERP: resting contacts then keep touching
// instead of jittering in and out of existence from step to step.
constexpr double kContactSurfaceLayer = 0.001;  // [m]
// Caps the ERP push-out of deep contacts so that a heavy body that sinks in one step is not
// launched by the position correction of the next.
constexpr double kContactMaxCorrectingVel = 2.0;  // [m/s]

bool is_finite_position(dBodyID body) {
    const dReal* p = dBodyGetPosition(body);
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

}  // namespace

std::vector<std::string> registered_solvers() {
    ode_bpp_register_solvers();
    std::vector<std::string> names;
    std::istringstream list(dListMLCPSolvers());
    std::string name;
    while (std::getline(list, name, ',')) {
        name.erase(0, name.find_first_not_of(' '));
        if (!name.empty()) names.push_back(name);
    }
    return names;
}

bool is_solver_registered(const std::string& name) {
    const std::vector<std::string> names = registered_solvers();
    return std::find(names.begin(), names.end(), name) != names.end();
}

SceneWorld::SceneWorld(const SceneParams& params) : params_(params) {
    dInitODE2(0);
    ode_bpp_register_solvers();  // libode_bpp registers at load too; this keeps the link
    world_ = dWorldCreate();
    if (dWorldSetMLCPSolver(world_, params_.solver.c_str()) == 0) {
        const std::string list = dListMLCPSolvers();
        ode_bpp::forget_world(world_);
        dWorldDestroy(world_);
        dCloseODE();
        throw std::invalid_argument("unknown MLCP solver '" + params_.solver +
                                    "' (registered: " + list + ")");
    }
    dWorldSetGravity(world_, 0, 0, -params_.gravity);
    dWorldSetERP(world_, params_.erp);
    dWorldSetCFM(world_, params_.cfm);
    dWorldSetContactSurfaceLayer(world_, kContactSurfaceLayer);
    dWorldSetContactMaxCorrectingVel(world_, kContactMaxCorrectingVel);
    space_ = dHashSpaceCreate(nullptr);
    ground_ = dCreatePlane(space_, 0, 0, 1, 0);
    contacts_ = dJointGroupCreate(0);
}

SceneWorld::~SceneWorld() {
    dJointGroupDestroy(contacts_);
    dSpaceDestroy(space_);  // destroys the geoms it holds (cleanup mode on by default)
    ode_bpp::forget_world(world_);  // a later world at the same address must not start warm
    dWorldDestroy(world_);  // destroys bodies and the remaining joints
    dCloseODE();
}

dBodyID SceneWorld::create_body() {
    dBodyID body = dBodyCreate(world_);
    bodies_.push_back(body);
    return body;
}

void SceneWorld::track_joint(dJointID joint) { tracked_joints_.push_back(joint); }

double SceneWorld::max_joint_error() const {
    double worst = 0;
    for (dJointID j : tracked_joints_) worst = std::max(worst, anchor_gap(j).value_or(0.0));
    return worst;
}

void SceneWorld::exclude_pair(dGeomID a, dGeomID b) { excluded_.emplace_back(a, b); }

void SceneWorld::near_callback(void* data, dGeomID a, dGeomID b) {
    static_cast<SceneWorld*>(data)->collide_pair(a, b);
}

void SceneWorld::collide_pair(dGeomID a, dGeomID b) {
    if (dGeomIsSpace(a) || dGeomIsSpace(b)) {
        dSpaceCollide2(a, b, this, &SceneWorld::near_callback);
        return;
    }
    dBodyID ba = dGeomGetBody(a), bb = dGeomGetBody(b);
    if (ba == bb) return;  // two static geoms, or two geoms of one body
    // bodies joined by a joint: the joint, not a contact, decides their relative motion
    if (ba && bb && dAreConnectedExcluding(ba, bb, dJointTypeContact)) return;
    for (const auto& [x, y] : excluded_) {
        if ((x == a && y == b) || (x == b && y == a)) return;
    }
    contact_buffer_.resize(static_cast<size_t>(std::max(1, max_contacts_per_pair)));
    const int n = dCollide(a, b, static_cast<int>(contact_buffer_.size()), &contact_buffer_[0].geom, sizeof(dContact));
    for (int i = 0; i < n; ++i) {
        dContact& c = contact_buffer_[static_cast<size_t>(i)];
        // dContactApprox1: friction pyramid scaled by the normal impulse, i.e. findex rows
        c.surface.mode = dContactApprox1 | dContactSoftCFM | dContactSoftERP;
        c.surface.mu = params_.mu;
        c.surface.soft_cfm = params_.cfm;
        c.surface.soft_erp = params_.erp;
        if (tuner_) {
            dContact tuned = c;
            if (tuner_(a, b, tuned)) c = tuned;
        }
        dJointID joint = dJointCreateContact(world_, contacts_, &c);
        dJointAttach(joint, ba, bb);
        ++last_contacts_;
    }
}

bool SceneWorld::step() {
    last_contacts_ = 0;
    dSpaceCollide(space_, this, &SceneWorld::near_callback);
    const auto start = std::chrono::steady_clock::now();
    const int ok = params_.stepper == "quickstep" ? dWorldQuickStep(world_, params_.step)
                                                  : dWorldStep(world_, params_.step);
    last_step_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    dJointGroupEmpty(contacts_);
    time_ += params_.step;
    ++steps_;
    if (!ok) return false;
    return std::all_of(bodies_.begin(), bodies_.end(), is_finite_position);
}

std::vector<std::pair<std::string, SceneFactory>> paper_scenes() {
    return {{"crane", make_crane},       {"winch", make_winch},       {"parkour", make_parkour},
            {"offshore", make_offshore}, {"forklift", make_forklift}, {"forwarder", make_forwarder}};
}

std::vector<std::string> scene_names() {
    std::vector<std::string> names;
    for (const auto& [name, factory] : paper_scenes()) names.push_back(name);
    for (const auto& [name, factory] : classic_scenes()) names.push_back(name);
    for (const auto& [name, factory] : contact_scenes()) names.push_back(name);
    return names;
}

std::unique_ptr<Scene> make_scene(const std::string& name) {
    for (const auto& [scene_name, factory] : paper_scenes()) {
        if (scene_name == name) return factory();
    }
    for (const auto& [scene_name, factory] : classic_scenes()) {
        if (scene_name == name) return factory();
    }
    for (const auto& [scene_name, factory] : contact_scenes()) {
        if (scene_name == name) return factory();
    }
    return nullptr;
}

}  // namespace ode_bpp::scenes
