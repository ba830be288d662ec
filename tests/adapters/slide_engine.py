#!/usr/bin/env python3
"""An external engine for tests/adapters/exec_test.cpp that slides boxes on a level floor
(docs/protocol.md).

Semi-implicit Euler (law "after-forces"), and for each dynamic box resting on a static box, with
contacts found where the last step ended:
    v = v + g*h; while the box's bottom is at or below the floor's top and v_y < 0:
    N = -v_y (the normal impulse per unit mass: v_y becomes 0)
    the slip (v_x, v_z) loses min(|slip|, MU*N) along itself (Coulomb's cone, exactly)
then x = x + h*v. MODE "coulomb" uses the scene's mu, "mu_off" 1.02 times it.
ANNOUNCE is the contact-solver line it sends: "exact" (none: the default), "sequential"
(sequential impulses, 10 iterations, median bound 1e-3) or "soft" (median bound 1e-3).
Usage: slide_engine.py MODE ANNOUNCE
"""
import math
import sys

MODE, ANNOUNCE = sys.argv[1], sys.argv[2]
SOLVERS = {"sequential": "contact-solver sequential-impulses 10 0.001",
           "soft": "contact-solver soft 0.001"}


def reply(line):
    sys.stdout.write(line + "\n")
    sys.stdout.flush()


def state(n, bodies):
    return "state %d " % n + " ".join(repr(c) for b in bodies for c in b["x"] + b["v"])


def read_scene(first):
    n = int(first.split()[1])
    scene = {"bodies": [], "mu": 0.0}
    for line in sys.stdin:
        t = line.split()
        if t[0] == "end":
            break
        if t[0] == "h":
            scene["h"] = float(t[1])
        elif t[0] == "gravity":
            scene["g"] = [float(c) for c in t[1:4]]
        elif t[0] == "material":
            scene["mu"] = 0.0 if t[1] == "-" else float(t[1])
        elif t[0] == "body":
            numbers = [float(c) for c in t[2:12]]
            scene["bodies"].append({"static": t[1] == "static", "he": numbers[1:4],
                                    "x": numbers[4:7], "v": numbers[7:10]})
    assert len(scene["bodies"]) == n
    return scene


def floor_top(scene, b):
    tops = [f["x"][1] + f["he"][1] for f in scene["bodies"] if f["static"]
            and abs(b["x"][0] - f["x"][0]) <= f["he"][0] and abs(b["x"][2] - f["x"][2]) <= f["he"][2]]
    return max(tops) if tops else None


def step(scene):
    h, g = scene["h"], scene["g"]
    mu = scene["mu"] * (1.02 if MODE == "mu_off" else 1.0)
    for b in scene["bodies"]:
        if b["static"]:
            continue
        top = floor_top(scene, b)
        touching = top is not None and b["x"][1] - b["he"][1] <= top
        b["v"] = [b["v"][k] + g[k] * h for k in range(3)]
        if touching and b["v"][1] < 0.0:
            normal = -b["v"][1]
            b["v"][1] = 0.0
            slip = math.hypot(b["v"][0], b["v"][2])
            if slip > 0.0:
                keep = max(slip - mu * normal, 0.0) / slip
                b["v"][0] *= keep
                b["v"][2] *= keep
        b["x"] = [b["x"][k] + h * b["v"][k] for k in range(3)]


def main():
    reply("dropcheck-engine 1")
    reply("name slide-" + MODE + "-" + ANNOUNCE)
    reply("version 1")
    reply("scalar f64")
    reply("law after-forces")
    reply("capabilities contacts friction")
    if ANNOUNCE in SOLVERS:
        reply(SOLVERS[ANNOUNCE])
    reply("ready")
    scene = None
    for line in sys.stdin:
        t = line.split()
        if not t or t[0] == "quit":
            return
        if t[0] == "scene":
            scene = read_scene(line)
            reply(state(0, scene["bodies"]))
        elif t[0] == "step":
            step(scene)
            reply(state(int(t[1]), scene["bodies"]))


main()
