#!/usr/bin/env python3
"""An external engine that starts a helper process, for the no-process-left-behind tests of
tests/harness/process/engine_processes_test.cpp. The helper is a second Python process that sleeps
300 s with TAG among its arguments, so a test finds both in /proc by TAG. MODE:
  hang      answers the handshake and the scene, then sleeps at step 1 (never answers)
  fail      answers the handshake, then exits with status 1 when the scene arrives
  succeed   the seed engine: answers every step, exits at "quit"
  segv      answers the handshake and the scene, then dies of SIGSEGV at step 1
Usage: helper_engine.py MODE TAG
"""
import os
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "python"))
import seed_engine  # noqa: E402

MODE, TAG = sys.argv[1], sys.argv[2]


def reply(line):
    sys.stdout.write(line + "\n")
    sys.stdout.flush()


def main():
    # The helper: same process group, its own program, outlives this script unless it is killed.
    subprocess.Popen([sys.executable, "-c", "import time; time.sleep(300)", TAG],
                     stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    reply("dropcheck-engine 1")
    for line in ["name helper-" + MODE, "version 0", "scalar f64", "law after-forces", "ready"]:
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
            if MODE == "hang":
                time.sleep(300)
            if MODE == "segv":
                os.kill(os.getpid(), signal.SIGSEGV)
            forces = [float(c) for c in t[2:]]
            for i, body in enumerate(world["bodies"]):
                seed_engine.step_seed(body, world["g"], forces[3 * i:3 * i + 3], world["h"], world["phi"])
            reply("state %d %s" % (n, seed_engine.fmt(world["bodies"])))
        elif t[0] == "quit":
            return


main()
