#!/usr/bin/env python3
"""An external engine for tests/adapters/exec_test.cpp that bounces spheres (docs/protocol.md).

Semi-implicit Euler in free flight (law "after-forces"), and for each dynamic sphere over a static
box the bounce law of harness/core/bounce_law.hpp, with contacts found where the last step ended:
    v_free = v - g*h; while the sphere's gap to the box top is below 0:
    rest = e*(-v) if -v > 0 else 0
    MODE ideal: v = max(v_free, rest)
    MODE split: v = max(v_free, rest) and the sphere moves 0.2*depth more (a split-impulse push)
ANNOUNCE is the bounce-law line it sends: "own" (its true law) or "ideal" (whatever it does).
Usage: bounce_engine.py MODE ANNOUNCE
"""
import sys

MODE, ANNOUNCE = sys.argv[1], sys.argv[2]
LAWS = {"ideal": "0 inf velocity 0 0 0", "split": "0.2 inf position 0 0 0"}


def reply(line):
    sys.stdout.write(line + "\n")
    sys.stdout.flush()


def state(n, bodies):
    return "state %d " % n + " ".join(repr(c) for b in bodies for c in b["x"] + b["v"])


def read_scene(first):
    n = int(first.split()[1])
    scene = {"bodies": [], "e": 0.0}
    for line in sys.stdin:
        t = line.split()
        if t[0] == "end":
            return scene
        if t[0] == "h":
            scene["h"] = float(t[1])
        elif t[0] == "gravity":
            scene["g"] = [float(c) for c in t[1:4]]
        elif t[0] == "damping":
            scene["phi"] = float(t[2])
        elif t[0] == "material":
            scene["e"] = 0.0 if t[2] == "-" else float(t[2])
        elif t[0] == "body":
            numbers = [float(c) for c in t[2:12]]
            scene["bodies"].append({"static": t[1] == "static", "he": numbers[1:4],
                                    "x": numbers[4:7], "v": numbers[7:10],
                                    "sphere": t[-1] == "sphere"})
    assert len(scene["bodies"]) == n
    return scene


def floor_top(scene, b):
    tops = [f["x"][1] + f["he"][1] for f in scene["bodies"] if f["static"]
            and abs(b["x"][0] - f["x"][0]) <= f["he"][0] and abs(b["x"][2] - f["x"][2]) <= f["he"][2]]
    return max(tops) if tops else None


def step(scene):
    h, g, e = scene["h"], scene["g"], scene["e"]
    for b in scene["bodies"]:
        if b["static"]:
            continue
        top = floor_top(scene, b) if b["sphere"] else None
        gap = b["x"][1] - b["he"][1] - top if top is not None else 1.0
        v_start = b["v"][1]
        b["v"] = [(b["v"][k] + g[k] * h) * scene["phi"] for k in range(3)]
        moved = 0.0
        if gap < 0.0:
            rest = e * -v_start if -v_start > 0.0 else 0.0
            b["v"][1] = max(b["v"][1], rest)
            if MODE == "split":
                moved = 0.2 * -gap
        b["x"] = [b["x"][k] + h * b["v"][k] for k in range(3)]
        b["x"][1] += moved


def main():
    reply("dropcheck-engine 1")
    reply("name bounce-" + MODE + "-" + ANNOUNCE)
    reply("version 1")
    reply("scalar f64")
    reply("law after-forces")
    reply("capabilities contacts restitution spheres")
    reply("bounce-law " + LAWS[MODE if ANNOUNCE == "own" else "ideal"])
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
