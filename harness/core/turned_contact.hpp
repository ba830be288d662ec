// Where an engine's contact acts on a turned or turning box (EngineInfo::turned_contact): the
// member that lets a tumbling landing be judged step by step instead of only compared
// (harness/judge/turned_verdict.hpp, docs/contact.md "Tumbling landings").
//
// mean_corner: per step, from the state the last step left (x, v, q, w of a box of mass m and
// principal moments I, over static boxes):
//   contact  the box's corners at or below a static box's face (the face along the axis of least
//            overlap of the box's bounding box), within that face; the depth d is the deepest
//            corner's, the point p the mean of those corners, r = p - x, and the approach
//            a = -(v + w x r).n
//   free     v = phi*(v + g*h);  w = phi_a*G(w)  (the engine's linear and rotational members)
//   normal   j_n = max(target - u.n, 0)/(n.K n), target = e*a when a > 0 else 0,
//            u = v + w x r the point's velocity, K d = d/m + I_w^-1*(r x d) x r
//   friction the slip u_t = u - (u.n)n after j_n, t = u_t/|u_t|: j_t = min(|u_t|/(t.K t), mu*j_n)
//            against t; each impulse j changes v by j/m and w by I_w^-1*(r x j)
//   pose     x += h*v, q = Q(q, w) (the rotational member), then x += d*n
// contacts taken in the order of their static box's height. A box neither turned nor turning is
// pushed through its centre (r = 0), as the flat landing, slide and stack laws say.
#pragma once

#include <string>

namespace dropcheck {

enum class TurnedContact {
  not_declared,  // the engine's solver acts at its own points: a tumbling landing is compared
  mean_corner,   // one impulse at the mean of the corners in the floor (the comment above; ours)
};

// "one impulse at the mean of the corners in the floor", "not declared".
std::string describe(TurnedContact c);

}  // namespace dropcheck
