#!/usr/bin/env python3
"""A misbehaving external engine for tests/adapters/exec_test.cpp: the seed engine of
examples/python/seed_engine.py that goes wrong at step STEP in the way MODE names:
  crash         dies of SIGSEGV           hang     stops answering (sleeps)
  garbage       answers 'hello world'     bodies   answers one body too few
  nan           answers NaN positions     exit     exits with status 0
  error         answers 'error out of memory'
  handshake     announces protocol 2 instead of 1 (STEP unused)
  silent        never reads nor writes (STEP unused)
  fail          exits with status 1 when the scene arrives (STEP unused)
  none          never misbehaves (the seed engine)
With TAG, it first starts a helper: a second Python process that sleeps 300 s with TAG among its
arguments, in the engine's process group (tests/harness/run/engine_processes_test.cpp finds
both in /proc by TAG, and checks that neither outlives the run).
Usage: bad_engine.py MODE STEP [TAG]
"""
import os
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "python"))
import seed_engine  # noqa: E402

MODE, AT = sys.argv[1], int(sys.argv[2])
TAG = sys.argv[3] if len(sys.argv) > 3 else None


def reply(line):
    sys.stdout.write(line + "\n")
    sys.stdout.flush()


def misbehave(step, world):
    if MODE == "crash":
        os.kill(os.getpid(), signal.SIGSEGV)
    if MODE == "hang":
        time.sleep(60)
    if MODE == "garbage":
        return reply("hello world")
    if MODE == "bodies":
        return reply("state %d %s" % (step, seed_engine.fmt(world["bodies"][1:])))
    if MODE == "nan":
        return reply("state %d %s" % (step, " ".join(["nan"] * (6 * len(world["bodies"])))))
    if MODE == "exit":
        sys.exit(0)
    if MODE == "error":
        return reply("error out of memory")


def main():
    if TAG:
        subprocess.Popen([sys.executable, "-c", "import time; time.sleep(300)", TAG],
                         stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    if MODE == "silent":
        time.sleep(60)
    reply("dropcheck-engine %d" % (2 if MODE == "handshake" else 1))
    for line in ["name bad-engine", "version 0", "scalar f64", "law after-forces", "ready"]:
        reply(line)
    world = None
    for line in sys.stdin:
        t = line.split()
        if t[0] == "scene":
            if MODE == "fail":
                sys.exit(1)
            world = seed_engine.read_scene(line)
            reply("state 0 " + seed_engine.fmt(world["bodies"]))
        elif t[0] == "step":
            n = int(t[1])
            if n == AT and MODE != "none":
                misbehave(n, world)
                continue
            forces = [float(c) for c in t[2:]]
            for i, body in enumerate(world["bodies"]):
                seed_engine.step_seed(body, world["g"], forces[3 * i:3 * i + 3], world["h"], world["phi"])
            reply("state %d %s" % (n, seed_engine.fmt(world["bodies"])))
        elif t[0] == "quit":
            return


main()
