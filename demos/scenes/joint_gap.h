// demos/scenes/joint_gap.h: the constraint drift of a joint, measured the same way for every
// scene and method: how far apart the two bodies' copies of the joint's anchor are.
#pragma once

#include <ode/ode.h>

#include <optional>
#include <vector>

namespace ode_bpp::scenes {

/// The anchor gap of one joint [m]: |anchor on body 1 - anchor on body 2| for ball, hinge and
/// universal joints (dJointGet*Anchor vs dJointGet*Anchor2, which ODE computes from each body's
/// own pose). For a hinge-2 joint only the part of the gap across its axis 1 counts: along that
/// axis ODE's suspension (dParamSuspensionERP/CFM) lets the anchors part by design.
/// Empty for every other joint type (contacts, sliders, fixed, motors, ...).
std::optional<double> anchor_gap(dJointID joint);

/// The largest anchor_gap over every joint attached to one of `bodies` (each joint once);
/// 0 when none of them has an anchor gap.
double max_anchor_gap(const std::vector<dBodyID>& bodies);

}  // namespace ode_bpp::scenes
