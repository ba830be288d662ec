#!/usr/bin/env python3
"""The seed engine (Part III, semi-implicit Euler with per-step drag) as an external dropcheck engine.

Speaks docs/protocol.md on stdin/stdout; standard library only; double precision (Python floats).
Per step and dynamic body, in exactly the order of ours/physics.hpp:
    v += g*h            (ApplyGravity)
    v += (F/m)*h        (IntegrateLinearForce)
    v *= phi            (drag, phi = exp(-k*h) as sent by dropcheck)
    x += v*h
i.e. the law "after-forces": v = phi*(v + a*h); x += h*v.
"""
import sys

LAW = "after-forces"  # wrong_order.py imports this module and declares the same law


def reply(line):
    sys.stdout.write(line + "\n")
    sys.stdout.flush()


def fmt(bodies):
    return " ".join(repr(c) for b in bodies for c in b["x"] + b["v"])


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
    world = {"bodies": [], "n": int(header.split()[1])}
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
        elif t[0] == "contacts" and t[1] == "1":
            reply("error contacts are not supported (capabilities: free flight only)")
            sys.exit(1)
        elif t[0] == "body":
            n = [float(c) for c in t[2:]]
            world["bodies"].append({"static": t[1] == "static", "m": n[0], "x": n[4:7], "v": n[7:10]})
    sys.exit(0)  # end of input inside a scene: dropcheck went away


def main(name="seed-python", law=LAW, step=step_seed):
    reply("dropcheck-engine 1")
    reply("name " + name)
    reply("version 1.0 (Python %d.%d)" % sys.version_info[:2])
    reply("scalar f64")
    reply("law " + law)
    reply("capabilities")
    reply("ready")
    world = None
    for line in sys.stdin:
        t = line.split()
        if not t:
            continue
        if t[0] == "scene":
            world = read_scene(line)
            reply("state 0 " + fmt(world["bodies"]))
        elif t[0] == "step":
            forces = [float(c) for c in t[2:]]
            for i, body in enumerate(world["bodies"]):
                if not body["static"]:
                    step(body, world["g"], forces[3 * i:3 * i + 3], world["h"], world["phi"])
            reply("state " + t[1] + " " + fmt(world["bodies"]))
        elif t[0] == "quit":
            return
        else:
            reply("error unknown request " + t[0])


if __name__ == "__main__":
    main()
