"""The protocol side shared by the contact test engines (bounce_engine.py, slide_engine.py):
answers, the scene reader and the serving loop of docs/protocol.md. The engine supplies its
handshake lines and its step."""
import sys


def reply(line):
    sys.stdout.write(line + "\n")
    sys.stdout.flush()


def state(n, bodies):
    return "state %d " % n + " ".join(repr(c) for b in bodies for c in b["x"] + b["v"])


def read_scene(first):
    """The scene after its 'scene N' line: h, gravity, the material (mu and e, 0 when '-'), and
    every body's half extents, position, velocity and shape."""
    n = int(first.split()[1])
    scene = {"bodies": [], "mu": 0.0, "e": 0.0, "phi": 1.0}
    for line in sys.stdin:
        t = line.split()
        if t[0] == "end":
            break
        if t[0] == "h":
            scene["h"] = float(t[1])
        elif t[0] == "gravity":
            scene["g"] = [float(c) for c in t[1:4]]
        elif t[0] == "damping":
            scene["phi"] = float(t[2])
        elif t[0] == "material":
            scene["mu"] = 0.0 if t[1] == "-" else float(t[1])
            scene["e"] = 0.0 if t[2] == "-" else float(t[2])
        elif t[0] == "body":
            numbers = [float(c) for c in t[2:12]]
            scene["bodies"].append({"static": t[1] == "static", "he": numbers[1:4],
                                    "x": numbers[4:7], "v": numbers[7:10],
                                    "sphere": t[-1] == "sphere"})
    assert len(scene["bodies"]) == n
    return scene


def floor_top(scene, b):
    """The highest top of a static box under body b's centre, or None."""
    tops = [f["x"][1] + f["he"][1] for f in scene["bodies"] if f["static"]
            and abs(b["x"][0] - f["x"][0]) <= f["he"][0] and abs(b["x"][2] - f["x"][2]) <= f["he"][2]]
    return max(tops) if tops else None


def serve(handshake, step):
    """Sends the handshake lines and 'ready', then answers scenes and steps until 'quit'."""
    reply("dropcheck-engine 1")
    for line in handshake:
        reply(line)
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
