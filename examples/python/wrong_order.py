#!/usr/bin/env python3
"""A deliberately wrong engine: it applies the drag BEFORE gravity and forces,
    v = phi*v + a*h; x += h*v          (the law "before-forces", Bullet's)
while declaring the seed's law "after-forces". `dropcheck check` must fail on it and
`dropcheck identify` must name its true law, before-forces.
"""
import seed_engine


def step_drag_first(body, g, f, h, phi):
    v, x, m = body["v"], body["x"], body["m"]
    for i in range(3):
        v[i] = v[i] * phi + (g[i] + f[i] / m) * h
        x[i] = x[i] + v[i] * h


if __name__ == "__main__":
    seed_engine.main(name="wrong-order", law="after-forces", step=step_drag_first)
