// demos/scenes/scene.h: a scene is written once and shared by the demos, the viewer,
// the benchmarks and the tests (as in Box2D v3's samples).
//
// A Scene builds bodies and joints into a SceneWorld, drives its actuators before every
// step, and judges its own success criterion. Collision, contacts (mu, CFM) and stepping are
// common to all scenes and live in SceneWorld, so a scene holds only what its phenomenon needs.
#pragma once

#include <ode/ode.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace ode_bpp::scenes {

/// Simulation parameters (paper Table 1 by default, except the CFM: ODE's default).
struct SceneParams {
    double step = 1.0 / 60.0;      ///< h [s]
    double seconds = 20.0;         ///< simulated time [s]
    double mu = 1.0;               ///< Coulomb friction coefficient
    double gravity = 9.81;         ///< [m/s^2]
    /// ODE CFM of joints and contacts. ODE's double-precision default is 1e-10; the paper's
    /// compliance c maps to CFM = c / h (docs/modelling.md, compliance), see cfm_from_compliance().
    double cfm = 1e-10;
    double erp = 0.2;              ///< ODE's default ERP
    std::string solver = "bpp";    ///< MLCP solver name for dWorldSetMLCPSolver
    /// "step": dWorldStep with the MLCP solver above; "quickstep": ODE's dWorldQuickStep
    /// (iterative, world level; the MLCP solver is then unused).
    std::string stepper = "step";
};
inline double cfm_from_compliance(double compliance, double step) { return compliance / step; }

/// A scene's own line of the paper's Table 2, measured or quoted.
struct TableTwo {
    double mass_ratio = 0;         ///< largest ratio of body masses coupled in one island
    int rows = 0;                  ///< most constraint rows in one island
    double cond = 0;               ///< largest cond(A) estimate
};

struct SuccessReport {
    bool ok = false;
    std::string detail;            ///< what was measured against what threshold
};

/// Owns the ODE world, the collision space and the contact group of one scene run.
class SceneWorld {
public:
    /// Creates the world (gravity, ERP, CFM from params), a hash space and the ground plane,
    /// and selects params.solver; throws std::invalid_argument if no such solver is registered.
    /// Calls dInitODE2 itself (ODE counts nested initialisations) and dCloseODE when destroyed.
    explicit SceneWorld(const SceneParams& params);
    ~SceneWorld();
    SceneWorld(const SceneWorld&) = delete;
    SceneWorld& operator=(const SceneWorld&) = delete;

    dWorldID world() const { return world_; }
    dSpaceID space() const { return space_; }
    dGeomID ground() const { return ground_; }       ///< the plane z = 0
    const SceneParams& params() const { return params_; }
    double time() const { return time_; }
    long steps() const { return steps_; }

    /// Collide, create contact joints (mu, CFM, soft ERP from params), dWorldStep(h), clear contacts.
    /// Returns false if dWorldStep failed or a body position became non-finite.
    bool step();

    /// Geoms that never collide with each other (e.g. bodies joined by a joint); checked by the
    /// near callback in addition to ODE's dAreConnectedExcluding.
    void exclude_pair(dGeomID a, dGeomID b);
    /// Per-pair contact override (e.g. a lower mu for a skidding wheel); return false to keep default.
    using ContactTuner = std::function<bool(dGeomID, dGeomID, dContact&)>;
    void set_contact_tuner(ContactTuner tuner) { tuner_ = std::move(tuner); }
    int max_contacts_per_pair = 4;

    /// Creates a body that the world tracks: step() checks its position for finiteness.
    dBodyID create_body();
    const std::vector<dBodyID>& bodies() const { return bodies_; }
    /// Registers a joint whose anchors must coincide (ball, hinge, universal); see max_joint_error().
    void track_joint(dJointID joint);
    /// Largest anchor gap [m] (joint_gap.h) over the tracked joints: the constraint drift a
    /// sound simulation keeps small.
    double max_joint_error() const;
    /// Wall time [s] of the last step()'s dWorldStep or dWorldQuickStep call alone (collision
    /// and contact creation excluded): what the benchmarks compare between methods.
    double last_step_seconds() const { return last_step_seconds_; }
    /// Contact joints created by the last step().
    int last_contacts() const { return last_contacts_; }

private:
    static void near_callback(void* data, dGeomID a, dGeomID b);
    void collide_pair(dGeomID a, dGeomID b);

    SceneParams params_;
    dWorldID world_ = nullptr;
    dSpaceID space_ = nullptr;
    dJointGroupID contacts_ = nullptr;
    dGeomID ground_ = nullptr;
    std::vector<dBodyID> bodies_;
    std::vector<dJointID> tracked_joints_;
    int last_contacts_ = 0;
    std::vector<std::pair<dGeomID, dGeomID>> excluded_;
    std::vector<dContact> contact_buffer_;  ///< dCollide's output, reused from pair to pair
    ContactTuner tuner_;
    double time_ = 0;
    long steps_ = 0;
    double last_step_seconds_ = 0;
};

class Scene {
public:
    virtual ~Scene() = default;
    virtual std::string name() const = 0;          ///< command-line name, e.g. "crane"
    virtual std::string description() const = 0;   ///< one line
    /// Adds bodies, geoms and joints to the world.
    virtual void build(SceneWorld& w) = 0;
    /// Drives motors and applies forces before the step at time t.
    virtual void control(SceneWorld& w, double t) { (void)w; (void)t; }
    /// The scene's success criterion, judged at the end of the run (or at any time).
    virtual SuccessReport success(const SceneWorld& w) const = 0;
    /// The paper's Table 2 line for this scene, or all zeros when the scene is not from the paper.
    virtual TableTwo paper_table_two() const { return {}; }
    /// Seconds the scene needs to show its phenomenon (the paper's scenes: 20 s).
    virtual double default_seconds() const { return 20.0; }
};

/// True if an MLCP solver of that name is registered with ODE (see dListMLCPSolvers()).
bool is_solver_registered(const std::string& name);
/// The registered MLCP solver names.
std::vector<std::string> registered_solvers();

/// All scenes by name: the paper's six (crane, winch, parkour, offshore, forklift, forwarder),
/// ODE's classic demos, ported, and the contact-rich scenes (pyramid, stack, bin, rockpile).
std::vector<std::string> scene_names();
std::unique_ptr<Scene> make_scene(const std::string& name);  ///< nullptr for an unknown name

/// Each scene's .cpp defines a factory (e.g. `std::unique_ptr<Scene> make_crane();`), and
/// scene.cpp lists them all explicitly: self-registering statics would be dropped by the
/// linker from a static library.

}  // namespace ode_bpp::scenes
