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

sys.dont_write_bytecode = True  # nothing written beside the sources
from contact_engine_io import floor_top, serve  # noqa: E402

MODE, ANNOUNCE = sys.argv[1], sys.argv[2]
SOLVERS = {"sequential": "contact-solver sequential-impulses 10 0.001",
           "soft": "contact-solver soft 0.001"}


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


serve(["name slide-" + MODE + "-" + ANNOUNCE, "version 1", "scalar f64", "law after-forces",
       "capabilities contacts friction"] + ([SOLVERS[ANNOUNCE]] if ANNOUNCE in SOLVERS else []),
      step)
