#!/usr/bin/env python3
"""Writes scenarios/friction/: the friction suite, contact scenes with exact answers.

  ramp_muM_tT      a unit cube at rest on an incline of T degrees, friction mu = M/10: it holds
                   iff tan(T) <= mu, else it slides at g*(sin T - mu*cos T); M in 1 3 5 7 10, T in 3
                   10 20 30 40
  stop_muM         a unit cube launched at 2 m/s on a level floor, friction mu = M/10 (M in 2 4 7),
                   g = 9.81, h = 1/1800: Coulomb's stop at v0^2/(2*mu*g), the clamp law's step
  bounce_phase_P   a sphere (e = 0.5) dropped so that its continuous impact falls at the P-th of
                   sixteen points inside a step (P = 0 .. 15): the contact step's phase varies

Every figure a description states is an [expect] entry the harness recomputes from the scene
(tests/scenarios/expectations_test.cpp), so this script only needs to round them. Run it from the
project root: python3 scripts/friction_suite.py
"""
import math
import os

OUT = os.path.join("scenarios", "friction")
FLOOR = """
[[body]]
name = "floor"
static = true
half_extents = [{half}, 0.5, {half}]
position = [0.0, -0.5, 0.0]
"""


def g_fmt(x, digits=6):
    return f"{x:.{digits}g}"


def clamp_law_slide(v0, pull, grip, h, steps):
    """The cone's clamp law (harness/oracles/contact_laws.cpp slide_step): the distance after
    `steps` steps."""
    s, v = 0.0, v0
    for _ in range(steps):
        v_free = v + pull * h
        v = 0.0 if abs(v_free) <= grip * h else v_free - math.copysign(grip * h, v_free)
        s += h * v
    return s


def ramp(mu_tenths, degrees):
    mu = mu_tenths / 10.0
    g = 9.8
    th = math.radians(degrees)
    pull, normal = g * math.sin(th), g * math.cos(th)
    h, duration = 1.0 / 60.0, 2.0
    steps = round(duration / h)
    holds = math.tan(th) <= mu
    verb = "holds: the friction it needs is within what is available" if holds else (
        "slides at g*(sin - mu*cos) = {slide_acceleration} m/s^2")
    text = f"""description = \"\"\"Friction suite: a unit cube at rest on an incline of {{incline}} degrees \\
(gravity of {{gravity}} m/s^2 tilted toward +x) with friction mu = {mu!r}. tan = {{tan_incline}} against \\
mu: it {verb}, needing {{friction_needed}} m/s^2 of the {{friction_available}} m/s^2 available. The \\
ideal discrete law moves it {{law_slide_distance}} m in {{steps}} steps, whatever the friction \\
model (docs/contact.md).\"\"\"
duration = {duration}
timestep = "1/60"

[expect]
incline = {degrees}
gravity = 9.8
tan_incline = {g_fmt(math.tan(th), 5)}
friction_needed = {g_fmt(pull, 5)}
friction_available = {g_fmt(mu * normal, 5)}
law_slide_distance = {g_fmt(clamp_law_slide(0.0, pull, mu * normal, h, steps), 5)}
steps = {steps}
"""
    if not holds:
        text += f"slide_acceleration = {g_fmt(pull - mu * normal, 5)}\n"
    text += f"""
[world]
gravity = [{pull!r}, {-normal!r}, 0.0]
contacts = true

[[body]]
name = "cube"
position = [0.0, 0.5, 0.0]
friction = {mu!r}
""" + FLOOR.format(half="20.0")
    return f"ramp_mu{mu_tenths:02d}_t{degrees:02d}.toml", text


def stop(mu_tenths):
    mu, g, v0, h = mu_tenths / 10.0, 9.81, 2.0, 1.0 / 1800.0
    grip_h = mu * g * h
    n = math.ceil(v0 / grip_h)
    moving = n - 1
    law = h * (moving * v0 - grip_h * moving * (moving + 1) / 2.0)
    text = f"""description = \"\"\"Friction suite: a unit cube launched at 2 m/s along a level floor with friction \\
mu = {mu!r} under a gravity of 9.81 m/s^2, stepped at h = 1/1800: Coulomb friction stops it \\
after {{stop_time}} s and {{stop_distance}} m; the ideal discrete law (mu*g*h off the speed each \\
step, never more than is left, then x += h*v) stops it at step {{law_stop_step}} after \\
{{law_stop_distance}} m, whatever the friction model (docs/contact.md).\"\"\"
duration = {g_fmt(math.ceil(v0 / (mu * g) * 10 + 1) / 10.0)}
timestep = "1/1800"

[expect]
stop_time = {g_fmt(v0 / (mu * g), 5)}
stop_distance = {g_fmt(v0 * v0 / (2 * mu * g), 5)}
law_stop_step = {n}
law_stop_distance = {g_fmt(law, 7)}

[world]
gravity = [0.0, -9.81, 0.0]
contacts = true

[[body]]
name = "cube"
position = [0.0, 0.5, 0.0]
velocity = [2.0, 0.0, 0.0]
friction = {mu!r}
""" + FLOOR.format(half="20.0")
    return f"stop_mu{mu_tenths:02d}.toml", text


def bounce_phase(p):
    g, h, n, e = 9.8, 1.0 / 60.0, 26, 0.5
    t = (n + (p + 0.5) / 16.0) * h  # the continuous impact, inside step n + 1
    drop = 0.5 * g * t * t
    # The ideal discrete law (semi-implicit): after step k the gap is drop - g*h^2*k*(k+1)/2; its
    # contact step is the first that ends in the floor, entered at g*h*k and left at e times that.
    k = 1
    while drop - g * h * h * k * (k + 1) / 2.0 >= 0.0:
        k += 1
    text = f"""description = \"\"\"Friction suite: a sphere of radius 0.5 m dropped from rest {{drop_height}} m above \\
the floor, restitution e = 0.5, under a gravity of 9.8 m/s^2: one of sixteen drops whose \\
continuous impacts fall at evenly spaced points inside one step, so that the contact step starts \\
at a different depth each time. The ideal discrete law hits at step {{law_contact_step}} at \\
{{law_speed_in}} m/s and leaves at {{law_speed_out}} m/s (docs/contact.md).\"\"\"
duration = 1.5
timestep = "1/60"

[expect]
drop_height = {g_fmt(drop, 8)}
law_contact_step = {k}
law_speed_in = {g_fmt(g * h * k, 6)}
law_speed_out = {g_fmt(e * g * h * k, 6)}

[world]
gravity = [0.0, -9.8, 0.0]
contacts = true

[[body]]
name = "ball"
shape = "sphere"
radius = 0.5
position = [0.0, {0.5 + drop!r}, 0.0]
restitution = 0.5
""" + FLOOR.format(half="20.0")
    return f"bounce_phase_{p:02d}.toml", text


def main():
    os.makedirs(OUT, exist_ok=True)
    scenes = [ramp(m, t) for m in (1, 3, 5, 7, 10) for t in (3, 10, 20, 30, 40)]
    scenes += [stop(m) for m in (2, 4, 7)]
    scenes += [bounce_phase(p) for p in range(16)]
    for name, text in scenes:
        with open(os.path.join(OUT, name), "w") as f:
            f.write(text)
    print(f"wrote {len(scenes)} scenes to {OUT}/")


if __name__ == "__main__":
    main()
