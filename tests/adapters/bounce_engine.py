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

sys.dont_write_bytecode = True  # nothing written beside the sources
from contact_engine_io import floor_top, serve  # noqa: E402

MODE, ANNOUNCE = sys.argv[1], sys.argv[2]
LAWS = {"ideal": "0 inf velocity 0 0 0", "split": "0.2 inf position 0 0 0"}


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


serve(["name bounce-" + MODE + "-" + ANNOUNCE, "version 1", "scalar f64", "law after-forces",
       "capabilities contacts restitution spheres",
       "bounce-law " + LAWS[MODE if ANNOUNCE == "own" else "ideal"]], step)
