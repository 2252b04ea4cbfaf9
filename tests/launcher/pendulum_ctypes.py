#!/usr/bin/env python3
"""A plain ODE program in Python for the launcher tests: it loads libode.so.8 with ctypes (by
soname, or by the path given as first argument) and knows nothing of ode-bpp.

A chain of spheres hangs from a fixed point by ball joints and swings under gravity, stepped with
dWorldStep (every step solves the joints' MLCP). It prints each link's final distance from its
anchor ("link I DIST"), which the joints keep at the link length.
"""
import ctypes
import sys

LINKS = 5
LENGTH = 0.4      # m between consecutive joint anchors
STEP = 0.01       # s
STEPS = 200

ode = ctypes.CDLL(sys.argv[1] if len(sys.argv) > 1 else "libode.so.8")
c_double_p = ctypes.POINTER(ctypes.c_double)


class dMass(ctypes.Structure):
    # ODE double precision: mass, centre (dVector3 = 4 dReal), inertia (dMatrix3 = 12 dReal)
    _fields_ = [("mass", ctypes.c_double), ("c", ctypes.c_double * 4), ("I", ctypes.c_double * 12)]


def declare(name, restype, *argtypes):
    fn = getattr(ode, name)
    fn.restype = restype
    fn.argtypes = list(argtypes)
    return fn


vp, d = ctypes.c_void_p, ctypes.c_double
dInitODE2 = declare("dInitODE2", ctypes.c_int, ctypes.c_uint)
dCloseODE = declare("dCloseODE", None)
dWorldCreate = declare("dWorldCreate", vp)
dWorldDestroy = declare("dWorldDestroy", None, vp)
dWorldSetGravity = declare("dWorldSetGravity", None, vp, d, d, d)
dWorldStep = declare("dWorldStep", ctypes.c_int, vp, d)
dBodyCreate = declare("dBodyCreate", vp, vp)
dBodySetMass = declare("dBodySetMass", None, vp, ctypes.POINTER(dMass))
dBodySetPosition = declare("dBodySetPosition", None, vp, d, d, d)
dBodyGetPosition = declare("dBodyGetPosition", c_double_p, vp)
dMassSetSphere = declare("dMassSetSphere", None, ctypes.POINTER(dMass), d, d)
dJointCreateBall = declare("dJointCreateBall", vp, vp, vp)
dJointAttach = declare("dJointAttach", None, vp, vp, vp)
dJointSetBallAnchor = declare("dJointSetBallAnchor", None, vp, d, d, d)


def main():
    dInitODE2(0)
    world = dWorldCreate()
    dWorldSetGravity(world, 0, 0, -9.81)
    anchors, bodies = [], []
    previous = None
    for i in range(LINKS):
        # the chain starts horizontal along x, so it swings down
        anchor = (i * LENGTH, 0.0, 2.0)
        body = dBodyCreate(world)
        mass = dMass()
        dMassSetSphere(ctypes.byref(mass), 1000.0, 0.05)
        dBodySetMass(body, ctypes.byref(mass))
        dBodySetPosition(body, anchor[0] + LENGTH, 0.0, 2.0)
        joint = dJointCreateBall(world, None)
        dJointAttach(joint, body, previous)
        dJointSetBallAnchor(joint, *anchor)
        anchors.append(anchor)
        bodies.append(body)
        previous = body
    for _ in range(STEPS):
        dWorldStep(world, STEP)
    # link i hangs from body i-1 (or from the fixed point for i = 0)
    for i, body in enumerate(bodies):
        p = dBodyGetPosition(body)
        q = (0.0, 0.0, 2.0) if i == 0 else tuple(dBodyGetPosition(bodies[i - 1])[k] for k in range(3))
        dist = sum((p[k] - q[k]) ** 2 for k in range(3)) ** 0.5
        print(f"link {i} {dist:.6f}")
    dWorldDestroy(world)
    dCloseODE()


main()
