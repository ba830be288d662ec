// A stand-in for libFuzzer's main, for builds without it (the ci preset's): runs a fuzz
// target (LLVMFuzzerTestOneInput) on every file of the corpus directories given, then on a fixed
// number of deterministic mutations of them (bit flips, interesting bytes and tokens, deletions,
// duplications, splices), so the same inputs run on every machine. With the ci preset's sanitizers
// a bug aborts the run and fails its ctest entry (label `fuzz`).
//
//   replay [--mutations N] [--seconds S] DIR...    (defaults: 3000 mutations, at most 20 s)
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

// splitmix64: a small, fixed PRNG, so the mutations are the same everywhere.
struct Rng {
  std::uint64_t s = 0x9E3779B97F4A7C15ull;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  std::size_t below(std::size_t n) { return n ? static_cast<std::size_t>(next() % n) : 0; }
};

// Text that scene and baseline parsers treat specially: extreme numbers, structure, quoting.
const char* const kTokens[] = {
    "1e308",       "-1.7976931348623157e308",
    "5e-324",      "nan",
    "inf",         "-0.0",
    "0",           "1/0",
    "1/60",        "99999999999999999999",
    "\"",          "'",
    "\\",          "\\u0000",
    "\n",          "\r\n",
    "[[body]]\n",  "[world]\n",
    "[[force]]\n", "name = ",
    " = ",         "[",
    "]",           "{",
    "}",           ",",
    "#",           "sample ",
    "bodies ",     "dt ",
    "sweep h=",    " / ",
    "status ",     "\xff",
    "\xc3\x28",    "`touch x`",
};

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void run(const std::string& input) {
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
}

// One random edit of `s` (`other` is another corpus file, for splices).
void mutate(std::string& s, const std::string& other, Rng& rng) {
  const std::size_t at = rng.below(s.size() + 1);
  switch (rng.below(6)) {
    case 0:
      if (!s.empty()) s[rng.below(s.size())] ^= static_cast<char>(1u << rng.below(8));
      break;
    case 1: {
      const char bytes[] = {'\0', '\n', '"', '[', '=', '.', 'e', '-', '9', '\x7f', '\xff'};
      if (!s.empty()) s[rng.below(s.size())] = bytes[rng.below(sizeof bytes)];
      break;
    }
    case 2:
      s.insert(at, kTokens[rng.below(std::size(kTokens))]);
      break;
    case 3:
      s.erase(at, rng.below(16));
      break;
    case 4:
      s.insert(at, s.substr(rng.below(s.size() + 1), rng.below(64)));
      break;
    default:
      s.insert(at, other.substr(rng.below(other.size() + 1), rng.below(256)));
      break;
  }
}

}  // namespace

int main(int argc, char** argv) {
  long mutations = 3000;
  double seconds = 20.0;
  std::vector<std::string> corpus;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--mutations" && i + 1 < argc)
      mutations = std::atol(argv[++i]);
    else if (a == "--seconds" && i + 1 < argc)
      seconds = std::atof(argv[++i]);
    else {
      std::vector<std::filesystem::path> files;
      for (const auto& e : std::filesystem::recursive_directory_iterator(a))
        if (e.is_regular_file()) files.push_back(e.path());
      std::sort(files.begin(), files.end());
      for (const auto& f : files) corpus.push_back(read_file(f));
    }
  }
  if (corpus.empty()) {
    std::fprintf(stderr, "replay: no corpus files given\n");
    return 2;
  }
  for (const std::string& input : corpus) run(input);
  const auto stop = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  Rng rng;
  long done = 0;
  for (; done < mutations && std::chrono::steady_clock::now() < stop; ++done) {
    std::string input = corpus[rng.below(corpus.size())];
    const std::string& other = corpus[rng.below(corpus.size())];
    for (std::size_t k = 1 + rng.below(4); k > 0; --k) mutate(input, other, rng);
    run(input);
  }
  std::printf("replay: %zu corpus files and %ld mutations ran without a finding\n", corpus.size(),
              done);
  return 0;
}
