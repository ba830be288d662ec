// The report's plots, as data (drawing is harness/report/plot.cpp's job): per scene a trajectory
// plot, a divergence plot and, with timings, a work-precision diagram.
#include "harness/report/report_plots.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "harness/oracles/contact_laws.hpp"
#include "harness/report/report.hpp"
#include "harness/report/report_format.hpp"

namespace dropcheck {
namespace {

constexpr int kAnalyticColour = 6;  // black in plot.cpp's palette

// Engines often coincide (same law): the first is drawn widest, each next one narrower on top.
double width_of(std::size_t engine, std::size_t engines) {
  return 1.0 + 0.5 * static_cast<double>(engines - 1 - std::min(engine, engines - 1));
}

std::vector<std::size_t> dynamic_bodies(const Scene& scene) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (!scene.bodies[i].is_static) out.push_back(i);
  return out;
}

// y(t) of one body of one trajectory.
PlotSeries height_series(const Trajectory& t, std::size_t body, const std::string& title) {
  PlotSeries s;
  s.title = title;
  for (std::size_t i = 0; i < t.samples(); ++i) {
    s.x.push_back(t.time(i));
    s.y.push_back(t.at(i, body).position.y());
  }
  return s;
}

// A slide scene's plot: the distance each sliding body has covered along its slip against time,
// per engine, with Coulomb's continuous answer (a cone: the physics, whatever an engine's model).
// Its height would be a flat line.
PlotSpec slide_plot(const SceneEvaluation& se, const std::vector<SlideSetup>& slides) {
  PlotSpec p;
  p.title = se.scene.name + ": distance slid along the slip at h = " + se.scene.timestep.text;
  p.xlabel = "t (s)";
  p.ylabel = "s (m)";
  const auto title = [&](const std::string& who, const SlideSetup& s) {
    return slides.size() > 1 ? who + ", " + se.scene.bodies[s.body].name : who;
  };
  for (std::size_t e = 0; e < se.engines.size(); ++e) {
    const EngineEvaluation& ev = se.engines[e];
    if (!ev.ran()) continue;
    const Trajectory& run = ev.at_default().run;
    for (std::size_t k = 0; k < slides.size(); ++k) {
      PlotSeries s;
      s.title = title(ev.name, slides[k]);
      s.x.reserve(run.samples());
      const SlidePath path = slide_path_of(run.body_states(slides[k].body), slides[k]);
      for (std::size_t i = 0; i < run.samples(); ++i) s.x.push_back(run.time(i));
      s.y = path.s;
      s.color = static_cast<int>(e);
      s.dash = static_cast<int>(k);
      s.width = width_of(e, se.engines.size());
      p.series.push_back(std::move(s));
    }
  }
  // The closed form on a fine grid of the scene's duration.
  constexpr int kPoints = 400;
  for (const SlideSetup& sl : slides) {
    PlotSeries s;
    s.title = title("closed form", sl);
    const double grip = slide_grip(sl.mu, sl.g, FrictionModel::cone, sl.angle);
    for (int i = 0; i <= kPoints; ++i) {
      const double t = se.scene.duration * i / kPoints;
      s.x.push_back(t);
      s.y.push_back(slide_distance_continuous(sl.v0, sl.pull, grip, t));
    }
    s.color = kAnalyticColour;
    s.dash = 2;
    p.series.push_back(std::move(s));
  }
  return p;
}

// Height against time at the default step, per engine and dynamic body, with the closed form; a
// slide scene's distance slid instead (slide_plot).
PlotSpec trajectory_plot(const SceneEvaluation& se) {
  const std::vector<SlideSetup> slides = slide_setups(se.scene);
  if (!slides.empty()) return slide_plot(se, slides);
  PlotSpec p;
  p.title = se.scene.name + ": height of each body at h = " + se.scene.timestep.text;
  p.xlabel = "t (s)";
  p.ylabel = "y (m)";
  const std::vector<std::size_t> bodies = dynamic_bodies(se.scene);
  for (std::size_t e = 0; e < se.engines.size(); ++e) {
    const EngineEvaluation& ev = se.engines[e];
    if (!ev.ran()) continue;
    for (std::size_t k = 0; k < bodies.size(); ++k) {
      const std::string title =
          bodies.size() > 1 ? ev.name + ", " + se.scene.bodies[bodies[k]].name : ev.name;
      PlotSeries s = height_series(ev.at_default().run, bodies[k], title);
      s.color = static_cast<int>(e);
      s.dash = static_cast<int>(k);
      s.width = width_of(e, se.engines.size());
      p.series.push_back(std::move(s));
    }
  }
  for (std::size_t k = 0; se.analytic && k < bodies.size(); ++k) {
    const std::string& body = se.scene.bodies[bodies[k]].name;
    PlotSeries s = height_series(*se.analytic, bodies[k],
                                 bodies.size() > 1 ? "closed form, " + body : "closed form");
    s.color = kAnalyticColour;
    s.dash = 2;
    p.series.push_back(std::move(s));
  }
  return p;
}

// max over bodies of |x_E(t) - x_R(t)|, at the samples both runs have (same h, same steps).
PlotSeries distance_series(const Trajectory& e, const Trajectory& r, const std::string& title) {
  PlotSeries s;
  s.title = title;
  for (std::size_t i = 0; i < std::min(e.samples(), r.samples()); ++i) {
    double d = 0.0;
    for (std::size_t b = 0; b < e.bodies(); ++b)
      d = std::max(d, (e.at(i, b).position - r.at(i, b).position).norm());
    s.x.push_back(e.time(i));
    s.y.push_back(d);
  }
  return s;
}

PlotSpec divergence_plot(const SceneEvaluation& se) {
  PlotSpec p;
  p.title = se.scene.name + ": distance from " + se.reference +
            " at h = " + se.scene.timestep.text + " (worst body; zero is not drawn)";
  p.xlabel = "t (s)";
  p.ylabel = "|x - x_" + se.reference + "| (m)";
  p.log_y = true;
  const EngineEvaluation* ref = se.find(se.reference);
  for (std::size_t e = 0; ref && e < se.engines.size(); ++e) {
    const EngineEvaluation& ev = se.engines[e];
    if (!ev.ran() || ev.name == se.reference) continue;
    PlotSeries s = distance_series(ev.at_default().run, ref->at_default().run, ev.name);
    s.color = static_cast<int>(e);
    s.width = width_of(e, se.engines.size());
    p.series.push_back(std::move(s));
  }
  return p;
}

// Guide lines of each law order present: an order-p law's error goes as h^p and its run time as
// 1/h, so its points lie on error ~ time^(-p), a line of slope -p here. Each guide passes through
// the coarsest point of the first engine of that order and spans every point's time range.
void add_order_guides(const SceneEvaluation& se, PlotSpec& p) {
  double lo = INFINITY, hi = 0.0;
  for (const PlotSeries& s : p.series)
    for (double x : s.x) lo = std::min(lo, x), hi = std::max(hi, x);
  if (!(hi > lo)) return;
  std::set<int> drawn;
  const std::size_t engines = p.series.size();
  for (std::size_t e = 0, k = 0; e < se.engines.size() && k < engines; ++e) {
    const EngineEvaluation& ev = se.engines[e];
    if (!ev.ran()) continue;
    const PlotSeries& s = p.series[k++];
    const int order = order_of(ev.info.law);
    if (order == 0) continue;  // error-controlled: its error follows its accuracy, not h
    // An engine at rounding level (RK4 is exact in free fall) shows no slope to anchor on.
    const bool converging = s.x.size() > 1 && s.y.front() > 0.0 && s.y.back() < s.y.front() / 2;
    if (!converging || !drawn.insert(order).second) continue;
    PlotSeries guide;
    guide.title = "order " + std::to_string(order) + " (slope -" + std::to_string(order) + ")";
    for (double x : {lo, hi}) {
      guide.x.push_back(x);
      guide.y.push_back(s.y.front() * std::pow(x / s.x.front(), -order));
    }
    guide.color = kAnalyticColour;
    guide.dash = order == 1 ? 1 : 3;
    guide.width = 1.0;
    p.series.push_back(std::move(guide));
  }
}

// Error against the continuous reference vs wall time per simulated second, one point per step.
PlotSpec work_precision_plot(const SceneEvaluation& se) {
  PlotSpec p;
  p.title = se.scene.name + ": work-precision (wall time; points labelled by h)";
  p.xlabel = "wall time per simulated second (s, minimum of samples)";
  p.ylabel = se.no_analytic.empty() ? "max |x - closed form| (m)"
                                    : "max |x - same engine at h = " + se.fine_step.text + "| (m)";
  p.log_x = p.log_y = p.points = true;
  for (std::size_t e = 0; e < se.engines.size(); ++e) {
    const EngineEvaluation& ev = se.engines[e];
    if (!ev.ran()) continue;
    PlotSeries s;
    s.title = ev.name;
    s.color = static_cast<int>(e);
    s.width = width_of(e, se.engines.size());
    for (const StepEvaluation& st : ev.sweep) {
      if (!st.timing) continue;
      s.x.push_back(st.timing->headline());
      s.y.push_back(st.continuous_error());
      s.labels.push_back(st.h.text);
    }
    p.series.push_back(std::move(s));
  }
  add_order_guides(se, p);
  return p;
}

}  // namespace

std::vector<std::vector<ReportPlot>> report_plots(const ReportInput& input) {
  std::vector<std::vector<ReportPlot>> out;
  std::set<std::string> used;
  for (const SceneEvaluation& se : input.scenes) {
    std::string slug = file_slug(se.scene.name);
    for (int n = 2; used.count(slug); ++n)
      slug = file_slug(se.scene.name) + "-" + std::to_string(n);
    used.insert(slug);
    std::vector<ReportPlot> plots;
    plots.push_back(
        {slug + "-trajectory.svg", se.scene.name + " trajectories", trajectory_plot(se)});
    if (!se.reference.empty())
      plots.push_back(
          {slug + "-divergence.svg", se.scene.name + " divergence", divergence_plot(se)});
    if (input.timing && (se.no_analytic.empty() || se.uses_fine))
      plots.push_back({slug + "-work-precision.svg",
                       se.scene.name + " work-precision (⏱ wall time)", work_precision_plot(se)});
    out.push_back(std::move(plots));
  }
  return out;
}

}  // namespace dropcheck
