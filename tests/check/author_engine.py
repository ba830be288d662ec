#!/usr/bin/env python3
"""An engine author's engine, written from docs/protocol.md alone, for tests/check/planted_bugs.sh.

Boxes and spheres that never turn, on a static box floor, with the seed's step and ours' contact
law (ours/collision.hpp), declared as ours declares it. Per step, with contacts found where the last
step ended (a touch counts: gap <= 0), for each body of approach a = -v_y and overlap d:
    v = (v + g*h)*phi
    v_y = max(v_y, e*a if a > 0 else 0); N = how much v_y rose   (the normal impulse per unit mass)
    the slip (v_x, v_z) loses min(|slip|, mu*N)                   (Coulomb's cone)
    x = x + h*v; x_y = x_y + d                                    (the overlap pushed out)
MODE plants one bug an author could make (the name stays "author", so baselines blessed with
MODE correct are the ones a buggy build is compared with):
    correct                  as above
    friction_after_position  x moves before the contact is resolved
    grip_whole_gravity       the friction bounded by mu*|g|*h: the normal force ignores the incline
    restitution_twice        the rebound e*a added once more after the contact
Usage: author_engine.py MODE
"""
import math
import os
import sys

sys.dont_write_bytecode = True  # nothing written beside the sources
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "adapters"))
from contact_engine_io import floor_top, serve  # noqa: E402

MODE = sys.argv[1]
assert MODE in ("correct", "friction_after_position", "grip_whole_gravity", "restitution_twice")


def resolve(b, scene, approach):
    """The contact: the normal push to e times the approach, then Coulomb's cone on the slip."""
    h, g, mu, e = scene["h"], scene["g"], scene["mu"], scene["e"]
    before = b["v"][1]
    b["v"][1] = max(b["v"][1], e * approach if approach > 0.0 else 0.0)
    normal = b["v"][1] - before
    if MODE == "grip_whole_gravity":
        normal = math.sqrt(sum(c * c for c in g)) * h
    slip = math.hypot(b["v"][0], b["v"][2])
    if slip > 0.0:
        keep = max(slip - mu * normal, 0.0) / slip
        b["v"][0] *= keep
        b["v"][2] *= keep
    if MODE == "restitution_twice" and approach > 0.0:
        b["v"][1] += e * approach


def step(scene):
    h, g = scene["h"], scene["g"]
    for b in scene["bodies"]:
        if b["static"]:
            continue
        top = floor_top(scene, b)
        gap = b["x"][1] - b["he"][1] - top if top is not None else 1.0
        approach = -b["v"][1]
        b["v"] = [(b["v"][k] + g[k] * h) * scene["phi"] for k in range(3)]
        move = MODE == "friction_after_position"
        if move:
            b["x"] = [b["x"][k] + h * b["v"][k] for k in range(3)]
        if gap <= 0.0:
            resolve(b, scene, approach)
        if not move:
            b["x"] = [b["x"][k] + h * b["v"][k] for k in range(3)]
        if gap < 0.0:
            b["x"][1] -= gap


serve(["name author", "version 1 (" + MODE + ")", "scalar f64", "law after-forces",
       "capabilities contacts friction restitution spheres", "friction-model cone",
       "bounce-law 1 inf position 0 0 0 step-start approach inf 0 touch"], step)
