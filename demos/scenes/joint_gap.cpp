// demos/scenes/joint_gap.cpp: anchor gaps of ball, hinge, universal and hinge-2 joints.
#include "scenes/joint_gap.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace ode_bpp::scenes {

namespace {

double dot(const dVector3 a, const dVector3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// The hinge-2 gap d minus its component along the unit axis 1 (the suspension's direction).
double across_axis(dVector3 d, dJointID joint) {
    dVector3 axis;
    dJointGetHinge2Axis1(joint, axis);
    const double along = dot(d, axis);
    for (int k = 0; k < 3; ++k) d[k] -= along * axis[k];
    return std::sqrt(dot(d, d));
}

}  // namespace

std::optional<double> anchor_gap(dJointID joint) {
    dVector3 a1, a2;
    switch (dJointGetType(joint)) {
    case dJointTypeBall: dJointGetBallAnchor(joint, a1); dJointGetBallAnchor2(joint, a2); break;
    case dJointTypeHinge: dJointGetHingeAnchor(joint, a1); dJointGetHingeAnchor2(joint, a2); break;
    case dJointTypeUniversal: dJointGetUniversalAnchor(joint, a1); dJointGetUniversalAnchor2(joint, a2); break;
    case dJointTypeHinge2: dJointGetHinge2Anchor(joint, a1); dJointGetHinge2Anchor2(joint, a2); break;
    default: return std::nullopt;
    }
    dVector3 d = {a1[0] - a2[0], a1[1] - a2[1], a1[2] - a2[2]};
    if (dJointGetType(joint) == dJointTypeHinge2) return across_axis(d, joint);
    return std::sqrt(dot(d, d));
}

double max_anchor_gap(const std::vector<dBodyID>& bodies) {
    std::unordered_set<dJointID> seen;
    double worst = 0;
    for (dBodyID body : bodies) {
        for (int k = 0, n = dBodyGetNumJoints(body); k < n; ++k) {
            dJointID joint = dBodyGetJoint(body, k);
            if (!seen.insert(joint).second) continue;
            if (const std::optional<double> gap = anchor_gap(joint)) worst = std::max(worst, *gap);
        }
    }
    return worst;
}

}  // namespace ode_bpp::scenes
