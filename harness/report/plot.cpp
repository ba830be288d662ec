#include "harness/report/plot.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "harness/core/number_format.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/process/signal_cleanup.hpp"

namespace dropcheck {
namespace {

// Colour-blind-safe palette (Okabe-Ito), then greys; index modulo its size.
const char* const kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                "#E69F00", "#56B4E9", "#000000", "#999999"};
// gnuplot dashtype patterns: solid, dashed, dotted, dash-dot.
const char* const kDashes[] = {"solid", "(8,4)", "(2,3)", "(8,3,2,3)"};

bool point_ok(const PlotSpec& s, double x, double y) {
  if (!std::isfinite(x) || !std::isfinite(y)) return false;
  return (!s.log_x || x > 0.0) && (!s.log_y || y > 0.0);
}

bool series_drawable(const PlotSpec& s, const PlotSeries& line) {
  for (std::size_t i = 0; i < line.x.size(); ++i)
    if (point_ok(s, line.x[i], line.y[i])) return true;
  return false;
}

// A string in gnuplot single quotes, where a quote is written twice. Single quotes expand neither
// backticks nor escapes; plot_text() has already removed the line breaks that would end the
// command.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : plot_text(text)) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// Length in bytes of the valid UTF-8 sequence starting at s[i], or 0 when it is not one
// (overlong forms, surrogates and code points above U+10FFFF are invalid too).
std::size_t utf8_length(const std::string& s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  std::size_t n = 0;
  unsigned min = 0, cp = 0;
  if (c < 0x80) return 1;
  if ((c & 0xE0) == 0xC0)
    n = 2, min = 0x80, cp = c & 0x1F;
  else if ((c & 0xF0) == 0xE0)
    n = 3, min = 0x800, cp = c & 0x0F;
  else if ((c & 0xF8) == 0xF0)
    n = 4, min = 0x10000, cp = c & 0x07;
  else
    return 0;
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (byte(i + k) & 0x3F);
  }
  if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  return n;
}

std::string axes(const PlotSpec& spec) {
  std::ostringstream s;
  s << "set title " << quoted(spec.title) << "\n";
  s << "set xlabel " << quoted(spec.xlabel) << "\nset ylabel " << quoted(spec.ylabel) << "\n";
  s << "set grid\nset key outside right top vertical Left reverse\n";
  if (spec.log_x) s << "set logscale x\nset format x '%.0e'\n";
  if (spec.log_y) s << "set logscale y\nset format y '%.0e'\n";
  return s.str();
}

// The plot command: one element per drawable series, plus its point labels.
std::string plot_command(const PlotSpec& spec, const std::string& data_file) {
  std::ostringstream s;
  s << "plot ";
  int block = 0;
  const char* sep = "";
  for (const PlotSeries& line : spec.series) {
    if (!series_drawable(spec, line)) continue;
    const char* colour = kPalette[line.color % std::size(kPalette)];
    const char* dash = kDashes[line.dash % std::size(kDashes)];
    s << sep << quoted(data_file) << " index " << block << " using 1:2 with "
      << (spec.points ? "linespoints pointtype 7 pointsize 0.6" : "lines") << " linewidth "
      << sig(line.width, 2) << " linecolor rgb '" << colour << "' dashtype " << dash << " title "
      << quoted(line.title);
    if (!line.labels.empty())
      s << ", " << quoted(data_file) << " index " << block
        << " using 1:2:3 with labels offset char 0.8,0.6 font 'sans,8' textcolor rgb '" << colour
        << "' notitle";
    sep = ", \\\n     ";
    ++block;
  }
  return s.str() + "\n";
}

// Runs `gnuplot SCRIPT` in `dir` with stdin from /dev/null and stderr into `log` (names relative
// to `dir`). No shell: every name is one argument, so no character of it is ever interpreted. The
// child is registered to be killed on SIGINT/SIGTERM/SIGHUP, so Ctrl-C stops dropcheck (std::system
// ignored SIGINT in the caller while gnuplot ran). Returns the wait status, or -1 when gnuplot
// could not be started (`why` then holds the reason).
int run_gnuplot(const std::string& dir, const std::string& script, const std::string& log,
                std::string& why) {
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addchdir_np(&files, dir.empty() ? "." : dir.c_str());
  posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&files, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) sigaddset(&defaults, sig);
  posix_spawnattr_setsigmask(&attr, &none);  // not the mask SignalsDeferred holds below
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  std::string program = "gnuplot";
  char* argv[] = {program.data(), const_cast<char*>(script.c_str()), nullptr};
  pid_t pid = -1;
  std::optional<SignalsDeferred> deferred(std::in_place);  // start + register as one step
  const int rc = posix_spawnp(&pid, "gnuplot", &files, &attr, argv, environ);
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) {
    why = rc == ENOENT ? "gnuplot not found"
                       : std::string("cannot start gnuplot: ") + std::strerror(rc);
    return -1;
  }
  KillOnSignal kill_on_signal(pid);
  deferred.reset();
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return status;
}

void remove_quietly(const std::filesystem::path& p) {
  std::error_code ec;
  std::filesystem::remove(p, ec);
}

std::string read_plot_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A point label inside the data file's double quotes: plot_text() without the double quote, which
// would end the field (data files are never evaluated, so backticks there are plain text).
std::string data_label(const std::string& label) {
  std::string out = plot_text(label);
  for (char& c : out)
    if (c == '"') c = '\'';
  return out;
}

}  // namespace

std::string plot_text(const std::string& text) {
  std::string out;
  std::size_t chars = 0;
  for (std::size_t i = 0; i < text.size();) {
    if (chars == kPlotTextMax) {
      out += "...";
      break;
    }
    const std::size_t n = utf8_length(text, i);
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (n == 0)
      out += "?";  // a byte that is not UTF-8
    else if (c < 0x20 || c == 0x7F)
      out += " ";  // line breaks, NUL, other controls
    else
      out.append(text, i, n);
    i += n ? n : 1;
    ++chars;
  }
  return out;
}

bool drawable(const PlotSpec& spec) {
  for (const PlotSeries& line : spec.series)
    if (series_drawable(spec, line)) return true;
  return false;
}

std::string gnuplot_data(const PlotSpec& spec) {
  std::ostringstream s;
  for (const PlotSeries& line : spec.series) {
    if (!series_drawable(spec, line)) continue;
    s << "# " << plot_text(line.title) << "\n";
    for (std::size_t i = 0; i < line.x.size(); ++i) {
      if (!point_ok(spec, line.x[i], line.y[i])) continue;
      s << sig(line.x[i], 9) << " " << sig(line.y[i], 9);
      if (!line.labels.empty()) s << " \"" << data_label(line.labels[i]) << "\"";
      s << "\n";
    }
    s << "\n\n";
  }
  return s.str();
}

std::string gnuplot_script(const PlotSpec& spec, const std::string& data_file,
                           const std::string& svg_file) {
  std::ostringstream s;
  s << kPlotTerminal << "\nset termoption noenhanced\n";
  s << "set output " << quoted(svg_file) << "\n";
  s << axes(spec) << plot_command(spec, data_file) << "unset output\n";
  return s.str();
}

std::string render_plot(const PlotSpec& spec, const std::string& dir, const std::string& svg_name) {
  if (!drawable(spec)) return "no data to draw";
  const std::filesystem::path d(dir);
  const std::string stem = "." + svg_name;  // hidden work files, removed below
  write_file_atomic((d / (stem + ".dat")).string(), gnuplot_data(spec));
  write_file_atomic((d / (stem + ".gp")).string(),
                    gnuplot_script(spec, stem + ".dat", stem + ".part"));
  std::string why;
  const int status = run_gnuplot(dir, stem + ".gp", stem + ".log", why);
  if (status == -1 && why.empty()) why = "gnuplot could not be waited for";
  if (status != -1 && status != 0) {
    const std::string log = read_plot_text(d / (stem + ".log"));
    why = WIFEXITED(status) && WEXITSTATUS(status) == 127 ? "gnuplot not found"
                                                          : "gnuplot failed: " + log;
  } else if (status == 0) {
    std::error_code ec;
    std::filesystem::rename(d / (stem + ".part"), d / svg_name, ec);
    if (ec) why = "cannot move the SVG into place: " + ec.message();
  }
  for (const char* ext : {".dat", ".gp", ".log", ".part"}) remove_quietly(d / (stem + ext));
  return why;
}

}  // namespace dropcheck
