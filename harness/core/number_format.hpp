// Numbers as text, in one place, on libfmt: every figure dropcheck prints goes through here, so the
// same value always gives the same bytes (reports, messages, CSV/JSON/baseline files).
//
// One number: call the function below that names its format. A sentence or table row with several
// figures: printf_string with a printf pattern ("%.4g", "%13.6f", "%lld"), which writes the bytes
// printf writes (fmt::vsprintf; fmt 9.1, measured over 9.6 million values: identical, inf/nan and
// widths included). For new code fmt::format("{:.4g}") is equally fine; give a width an explicit
// '>' ("{:>13.6f}"): fmt left-aligns inf and nan in a width unless told.
#pragma once

#include <fmt/printf.h>

#include <string>

namespace dropcheck {

// fmt::sprintf(pattern, args...), with fmt's printf engine instantiated once (number_format.cpp)
// instead of in every source that prints a row: ~10 s less per such source in the ci build.
std::string vprintf_string(fmt::string_view pattern, fmt::printf_args args);

// A printf pattern filled with args: the bytes fmt::sprintf(pattern, args...) writes.
template <typename... Args>
std::string printf_string(fmt::string_view pattern, const Args&... args) {
  return vprintf_string(pattern, fmt::make_printf_args(args...));
}

// v with `digits` significant digits, as printf's "%.<digits>g" ("inf", "-inf", "nan").
std::string sig(double v, int digits);

// sig(v, 3): the default for an error, a tolerance or a ratio in a message.
std::string g3(double v);

// v with `decimals` digits after the point, as printf's "%.<decimals>f".
std::string fixed(double v, int decimals);

// "%.17g": reads back to the same double. The file contract of CSV, JSON, baselines and the exec
// protocol (docs/protocol.md); use it for every number written to a file that is read back.
std::string exact(double v);

// The shortest text that reads back to the same double (std::to_chars: 0.1 stays "0.1"), for a
// number the user wrote and sees again (a scene's step).
std::string shortest(double v);

// A length with the unit that keeps 3 significant digits readable: "1.23 m", "3.2 cm", "4.5 mm",
// "7 um", below 1 um "%.2g m"; "0 m" for zero, "inf" for a non-finite length.
std::string format_length(double metres);

// A step h divided by n, as text: "1/(N*n)" when h is written "1/N" and N*n fits a long long (the
// form the user chose survives the sweep), else the seconds with 6 significant digits.
std::string divided_step_text(const std::string& h_text, double h_seconds, long long n);

}  // namespace dropcheck
