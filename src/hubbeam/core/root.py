"""A compliant root in the kernels: a torsional spring and damper between the hub and the beam's root.

The hub (the motor side: inertia ``J_h``, where the hub torque and the drive act) turns by ``phi``;
the beam's root, clamped in a bracket that turns by ``theta`` (with the clamp's rotary inertia
``J_c``), sits on the hub at the hub radius ``a = rA``, on a hinge whose torsional spring ``k`` and
damper ``c`` pass ``k (phi - theta) + c (phi' - theta')`` from the hub to the link
(``docs/compliant-root.md``). The beam stays clamped to the bracket: its deformation ``(u, v)`` is
measured in the frame turned by ``theta``, and every output that reads the beam keeps ``theta``.
With a compliant root the coordinates are ``y = (theta, q1, q2, phi)``: the hub angle is appended.

Kinematics. In the frame turned by ``theta`` the hinge sits at ``a (cos alpha, sin alpha)``,
``alpha = phi - theta``, and the point ``k`` of the point cloud (beam nodes and the tip body's
centre, weights ``w_k``) at ``(x_k + u_k, v_k)`` from it. The hinge moves with the hub; the point's
velocity is the hinge's, ``a phi' (-sin alpha, cos alpha)``, plus the velocity about the hinge
``(u' - theta' v, v' + theta' (x + u))``. The kinetic energy is therefore

    T = J_h phi'^2 / 2 + J_c theta'^2 / 2 + T_link + T_hinge,
    T_hinge = a^2 m phi'^2 / 2 + phi' (cos alpha (k' + theta' h) - sin alpha (h' - theta' k)),

``T_link`` the kinetic energy of the model's link about its hinge (every model's equations with
the hub radius set to zero: the matrices of ``hubbeam.model.root.link_matrices``, rotary inertia of
a tip body included), ``m = sum w`` and the hinge's levers, linear in the point-cloud sums
``a m``, ``a s0 = a sum w x``, ``p1 = a sum w f1``, ``p2 = a sum w f2``, ``E = a sum w S``:

    h = a sum w (x + u) = a s0 + p1 . q1 - c_S q2^T E q2 / 2,      k = a sum w v = p2 . q2,

with ``u = f1 q1 - c_S q2^T S q2 / 2`` the model's axial displacement (``c_S = 0`` for a model
without the foreshortening, TLAM: its ``softening_terms``). The hinge's kinematics is exact in every
model: CFOAM's kinetic energy is then exact, and the models' own truncations apply to the link.
Without a spring (``alpha = 0``, ``phi = theta``) ``T_link + T_hinge`` is the model's kinetic energy
with the hub radius, term for term.

Lagrange's equations of ``T_hinge`` (derivation in ``docs/compliant-root.md``) add to the mass
matrix the hub entry ``J_h + a^2 m``, the hub-root coupling ``cos alpha h + sin alpha k`` and the
hub's couplings to the elastic coordinates ``w = cos alpha dk/dq - sin alpha dh/dq = (-sin alpha
p1, cos alpha p2 + sin alpha c_S E q2)`` (nothing on the link's own block), and the forces, with
``lambda = cos alpha k - sin alpha h``,

    root angle:  -phi'^2 lambda + k (phi - theta) + c (phi' - theta'),
    elastic:      phi'^2 (cos alpha dh/dq + sin alpha dk/dq)
                = phi'^2 (cos alpha p1, sin alpha p2 - cos alpha c_S E q2),
    hub angle:    tau + theta'^2 lambda - 2 theta' (sin alpha k' + cos alpha h')
                  - sin alpha c_S q2'^T E q2' - k (phi - theta) - c (phi' - theta').

The rates' terms of the hub row are the hinge's Coriolis torques; SFOAM, which deletes the
velocity-dependent torque of the beam on the hub (Eq. 40, ``hub_velocity_force``), deletes them
too, so that a stiff root gives its equations back. The kernels receive the joint as a
:class:`~hubbeam.core.inputs.RootJoint` (``NO_ROOT``, empty arrays, is the rigid root, which
changes no floating-point operation) and the link's matrices about its hinge in ``sm`` (its ``Jh``
the clamp's inertia ``J_c``, its hub radius zero).
"""

import math

import numpy as np

from hubbeam.core.inputs import ModelTraits, RootJoint
from hubbeam.core.jit import borrowing_kernel, kernel

#: slots of ``RootJoint.scalars``: the spring's stiffness and damping, the hub's inertia (the motor
#: side), ``a^2 m`` and ``a s0`` (the beam's mass carried at the hinge and its first moment about
#: the hinge, times the hub radius)
STIFFNESS, DAMPING, HUB_INERTIA, HINGE_MASS, HINGE_MOMENT = range(5)
#: values of ``RootJoint.scalars``
JOINT_SCALARS = 5


@borrowing_kernel
def has_joint(root):
    """True for a compliant root, False for the rigid one (an empty ``RootJoint``)."""
    return root.scalars.shape[0] > 0


@borrowing_kernel
def hub_index(root, size):
    """Where the hub's angle sits among ``size`` coordinates (all of them, or the integrated ones
    of a free hub): the last with a compliant root (``phi`` is appended), 0 without (``theta`` is
    the hub's angle)."""
    if root.scalars.shape[0] > 0:
        return size - 1
    return 0


@borrowing_kernel
def spring_torque(root, y, v):
    """The torque the spring and damper pass from the hub to the link, ``k (phi - theta) + c (phi'
    - theta')``, in the full-length state ``(y, v)``."""
    hub = y.shape[0] - 1
    return root.scalars[STIFFNESS] * (y[hub] - y[0]) + root.scalars[DAMPING] * (v[hub] - v[0])


@borrowing_kernel
def spring_energy(root, y):
    """The spring's potential energy ``k (phi - theta)^2 / 2``."""
    twist = y[y.shape[0] - 1] - y[0]
    return 0.5 * root.scalars[STIFFNESS] * twist * twist


@borrowing_kernel
def damper_power(root, v):
    """The power the damper dissipates, ``c (phi' - theta')^2``."""
    rate = v[v.shape[0] - 1] - v[0]
    return root.scalars[DAMPING] * rate * rate


@borrowing_kernel
def hinge_terms(traits, root, y, v, coupling, force):
    """The hinge's terms of Lagrange's equations (module docstring) in the full-length state
    ``(y, v)`` of ``(theta, q1, q2, phi)``: writes the hub's couplings to ``(q1, q2)`` into
    ``coupling`` and the forces on ``(q1, q2)`` into ``force`` (``2 n`` each) and returns the
    hub-root coupling, the force on the root angle and the force on the hub angle, both without
    the spring, the damper and the hub torque."""
    n = root.p1.shape[0]
    o2 = 1 + n
    hub = 1 + 2 * n
    c_S = 1.0 if traits.softening_terms else 0.0
    alpha = y[hub] - y[0]
    ca = math.cos(alpha)
    sa = math.sin(alpha)
    thd = v[0]
    phd2 = v[hub] * v[hub]
    h = root.scalars[HINGE_MOMENT]
    k = 0.0
    h_rate = 0.0
    k_rate = 0.0
    stretch_rate = 0.0  # q2'^T E q2'
    for i in range(n):
        eq = 0.0
        eq_rate = 0.0
        for j in range(n):
            eq += root.Ea[i, j] * y[o2 + j]
            eq_rate += root.Ea[i, j] * v[o2 + j]
        eq *= c_S
        eq_rate *= c_S
        h += root.p1[i] * y[1 + i] - 0.5 * y[o2 + i] * eq
        k += root.p2[i] * y[o2 + i]
        h_rate += root.p1[i] * v[1 + i] - y[o2 + i] * eq_rate
        k_rate += root.p2[i] * v[o2 + i]
        stretch_rate += v[o2 + i] * eq_rate
        coupling[i] = -sa * root.p1[i]
        coupling[n + i] = ca * root.p2[i] + sa * eq
        force[i] = phd2 * ca * root.p1[i]
        force[n + i] = phd2 * (sa * root.p2[i] - ca * eq)
    lever = ca * k - sa * h
    hub_force = thd * thd * lever
    if traits.hub_velocity_force:
        hub_force -= 2.0 * thd * (sa * k_rate + ca * h_rate) + sa * stretch_rate
    return ca * h + sa * k, -phd2 * lever, hub_force


@borrowing_kernel
def add_joint(traits, root, y, v, tau, M, F, work):
    """Add the compliant root to the mass matrix ``M`` and force ``F`` of ``(theta, q1, q2, phi)``
    whose link block (every row and column but the last) holds the link's equations about its
    hinge with no torque on the root angle: the hinge's terms (:func:`hinge_terms`, through the
    rows of ``work``, shape ``(2, 2 n)``), the spring and damper between hub and root, and the hub
    torque ``tau`` on the hub angle."""
    n = root.p1.shape[0]
    hub = 1 + 2 * n
    coupling = work[0]
    force = work[1]
    root_hub, root_force, hub_force = hinge_terms(traits, root, y, v, coupling, force)
    twist = spring_torque(root, y, v)
    M[hub, hub] = root.scalars[HUB_INERTIA] + root.scalars[HINGE_MASS]
    M[0, hub] = root_hub
    M[hub, 0] = root_hub
    for i in range(2 * n):
        M[hub, 1 + i] = coupling[i]
        M[1 + i, hub] = coupling[i]
        F[1 + i] += force[i]
    F[0] += root_force + twist
    F[hub] = tau + hub_force - twist


#: A compliant root packed into one array, for the integrator's problems (each field of a problem
#: travels with every call of the integrator's kernels, so one array costs a rigid root's runs
#: nothing measurable where three fields more cost 6 %): rows of ``max(2 n + 2, 8)`` values, the
#: first holding the ``RootJoint``'s scalars, the model's foreshortening and hub-velocity flags
#: (1 or 0) and the number of modes ``n``; then ``p1``, ``p2`` and the ``n`` rows of ``E``; then the
#: problem's own rows from :func:`joint_rows`.
SOFTENING_FLAG, VELOCITY_FLAG, MODES = JOINT_SCALARS, JOINT_SCALARS + 1, JOINT_SCALARS + 2
LEVER_P1, LEVER_P2, LEVER_E = 1, 2, 3


@kernel
def packed_joint(traits, root, extra):
    """The compliant root ``root`` of a model with ``traits`` packed (layout above), with ``extra``
    rows of zeros after it for the problem's own work."""
    n = root.p1.shape[0]
    joint = np.zeros((LEVER_E + n + extra, max(2 * n + 2, MODES + 1)))
    joint[0, :JOINT_SCALARS] = root.scalars
    joint[0, SOFTENING_FLAG] = 1.0 if traits.softening_terms else 0.0
    joint[0, VELOCITY_FLAG] = 1.0 if traits.hub_velocity_force else 0.0
    joint[0, MODES] = n
    joint[LEVER_P1, :n] = root.p1
    joint[LEVER_P2, :n] = root.p2
    joint[LEVER_E:LEVER_E + n, :n] = root.Ea
    return joint


@borrowing_kernel
def joint_rows(joint):
    """The index of the first of a packed joint's own rows (after its root's)."""
    return LEVER_E + int(joint[0, MODES])


@borrowing_kernel
def unpacked_joint(joint):
    """``(traits, root)`` of a packed joint: the flags :func:`hinge_terms` reads, as
    ``ModelTraits``, and the ``RootJoint`` (views of the array)."""
    n = int(joint[0, MODES])
    traits = ModelTraits(True, joint[0, SOFTENING_FLAG] != 0.0, joint[0, VELOCITY_FLAG] != 0.0, False)
    root = RootJoint(joint[0, :JOINT_SCALARS], joint[LEVER_P1, :n], joint[LEVER_P2, :n], joint[LEVER_E:LEVER_E + n, :n])
    return traits, root
