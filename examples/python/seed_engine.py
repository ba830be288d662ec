#!/usr/bin/env python3
"""The seed engine (Part III, semi-implicit Euler with per-step drag) as an external dropcheck engine.

Speaks docs/protocol.md on stdin/stdout; standard library only; double precision (Python floats).
Per step and dynamic body, in exactly the order of ours/physics.hpp:
    v += g*h            (ApplyGravity)
    v += (F/m)*h        (IntegrateLinearForce)
    v *= phi            (drag, phi = exp(-k*h) as sent by dropcheck)
    x += v*h
i.e. the law "after-forces": v = phi*(v + a*h); x += h*v.

It also turns bodies, as ours/physics.hpp's IntegrateAngularForce does (rotational member
"explicit/first-order"): with R the rotation of q and I the principal moments,
    w += R*((R^T*(tau - w x (R*(I .* (R^T*w))))) ./ I)*h     explicit gyroscopic term
    w *= phi_a                                               angular drag
    q = normalize(q + (h/2)*(0, w)*q)                        first-order quaternion update
"""
import math
import sys

LAW = "after-forces"  # wrong_order.py imports this module and declares the same law
ROTATION_LAW = "explicit/first-order"


def reply(line):
    sys.stdout.write(line + "\n")
    sys.stdout.flush()


def fmt(bodies, rotating=False):
    """Each body's x and v, and in a rotating scene its q (w, x, y, z) and world w."""
    return " ".join(repr(c) for b in bodies
                    for c in b["x"] + b["v"] + (b["q"] + b["w"] if rotating else []))


def rotation(q):
    """The rotation matrix of the unit quaternion q = [w, x, y, z], as rows."""
    w, x, y, z = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def times(m, v):
    return [sum(m[i][j] * v[j] for j in range(3)) for i in range(3)]


def times_transposed(m, v):
    return [sum(m[j][i] * v[j] for j in range(3)) for i in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def turn_seed(body, tau, h, phi_a):
    """One step of the explicit/first-order rotational member on one body."""
    w, q, inertia = body["w"], body["q"], body["I"]
    if all(c == 0.0 for c in w + tau):
        return  # neither turning nor twisted: the rotation stays exactly as it is
    r = rotation(q)
    momentum = times(r, [inertia[i] * c for i, c in enumerate(times_transposed(r, w))])
    net = [t - c for t, c in zip(tau, cross(w, momentum))]
    dw = times(r, [c / inertia[i] for i, c in enumerate(times_transposed(r, net))])
    for i in range(3):
        w[i] = (w[i] + dw[i] * h) * phi_a
    # (0, w)*q, the quaternion product, then q += (h/2)*(0, w)*q and normalise.
    qw, qx, qy, qz = q
    spin = [-(w[0] * qx + w[1] * qy + w[2] * qz),
            w[0] * qw + w[1] * qz - w[2] * qy,
            w[1] * qw + w[2] * qx - w[0] * qz,
            w[2] * qw + w[0] * qy - w[1] * qx]
    for i in range(4):
        q[i] = q[i] + spin[i] * (h / 2)
    norm = math.sqrt(sum(c * c for c in q))
    for i in range(4):
        q[i] = q[i] / norm


def step_seed(body, g, f, h, phi):
    """One step of the seed's law on one body (lists of 3 floats), in ours/physics.hpp's order."""
    v, x, m = body["v"], body["x"], body["m"]
    for i in range(3):
        v[i] = v[i] + g[i] * h
    for i in range(3):
        v[i] = v[i] + (f[i] / m) * h
    for i in range(3):
        v[i] = v[i] * phi
    for i in range(3):
        x[i] = x[i] + v[i] * h


def read_scene(header):
    """Reads the lines after 'scene N' up to 'end'; returns the world."""
    world = {"bodies": [], "n": int(header.split()[1]), "phi_a": 1.0, "rotating": False}
    for line in sys.stdin:
        t = line.split()
        if t[0] == "end":
            return world
        if t[0] == "h":
            world["h"] = float(t[1])
        elif t[0] == "gravity":
            world["g"] = [float(c) for c in t[1:4]]
        elif t[0] == "damping":
            world["phi"] = float(t[2])
        elif t[0] == "angular-damping":  # only in a rotating scene
            world["phi_a"] = float(t[2])
            world["rotating"] = True
        elif t[0] == "contacts" and t[1] == "1":
            reply("error contacts are not supported (capabilities: free flight only)")
            sys.exit(1)
        elif t[0] == "body":
            n = [float(c) for c in t[2:]]
            body = {"static": t[1] == "static", "m": n[0], "x": n[4:7], "v": n[7:10]}
            if len(n) == 20:  # a rotating scene: orientation, angular velocity, moments
                body.update({"q": n[10:14], "w": n[14:17], "I": n[17:20]})
            world["bodies"].append(body)
    sys.exit(0)  # end of input inside a scene: dropcheck went away


def main(name="seed-python", law=LAW, step=step_seed):
    reply("dropcheck-engine 1")
    reply("name " + name)
    reply("version 1.0 (Python %d.%d)" % sys.version_info[:2])
    reply("scalar f64")
    reply("law " + law)
    reply("capabilities rotation")
    reply("rotation-law " + ROTATION_LAW)
    reply("ready")
    world = None
    for line in sys.stdin:
        t = line.split()
        if not t:
            continue
        if t[0] == "scene":
            world = read_scene(line)
            reply("state 0 " + fmt(world["bodies"], world["rotating"]))
        elif t[0] == "step":
            numbers = [float(c) for c in t[2:]]
            n = len(world["bodies"])
            forces, torques = numbers[:3 * n], numbers[3 * n:]  # torques: rotating scenes only
            for i, body in enumerate(world["bodies"]):
                if not body["static"]:
                    step(body, world["g"], forces[3 * i:3 * i + 3], world["h"], world["phi"])
                    if world["rotating"]:
                        turn_seed(body, torques[3 * i:3 * i + 3], world["h"], world["phi_a"])
            reply("state " + t[1] + " " + fmt(world["bodies"], world["rotating"]))
        elif t[0] == "quit":
            return
        else:
            reply("error unknown request " + t[0])


if __name__ == "__main__":
    main()
