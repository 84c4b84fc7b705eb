// Throughput of the crate reader next to plain reading of the same bytes:
// for every crate layer given (a .usdc file, or each .usdc entry of a .usdz
// package) it times reading the bytes (the file, or the package entry
// through libzip) and parsing them into a Layer (readCrateLayer), each
// repeated N times, and prints MB/s of crate bytes for both.
//
//   sdg_usd_read_bench [--repeat N] FILE.usdz|FILE.usdc...
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "usd/layer_io.h"
#include "usd/usdz_package.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Source {
  std::string name;
  std::string package;  // "" for a plain file
  std::string entry;
};

std::vector<uint8_t> readPlain(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open it");
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

std::vector<uint8_t> readSource(const Source& s) {
  if (s.package.empty()) return readPlain(s.entry);
  return sdg::usd::UsdzPackage(s.package).read(s.entry);
}

bool endsWith(const std::string& s, const char* suffix) {
  size_t n = std::strlen(suffix);
  return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

template <class F>
double secondsFor(int repeat, F&& f) {
  auto start = Clock::now();
  for (int i = 0; i < repeat; ++i) f();
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 200;
  std::vector<Source> sources;
  try {
    for (int i = 1; i < argc; ++i) {
      std::string arg = argv[i];
      if (arg == "--repeat" && i + 1 < argc) {
        repeat = std::max(1, std::atoi(argv[++i]));
      } else if (endsWith(arg, ".usdz")) {
        sdg::usd::UsdzPackage pkg(arg);
        for (const auto& e : pkg.entries())
          if (endsWith(e, ".usdc")) sources.push_back({arg.substr(arg.rfind('/') + 1) + "[" + e + "]", arg, e});
      } else {
        sources.push_back({arg.substr(arg.rfind('/') + 1), "", arg});
      }
    }
    if (sources.empty()) {
      std::fprintf(stderr, "usage: %s [--repeat N] FILE.usdz|FILE.usdc...\n", argv[0]);
      return 2;
    }
    std::printf("%-50s %9s %7s %12s %12s %8s\n", "crate layer", "bytes", "specs", "read MB/s", "parse MB/s",
                "parse/read");
    double totalBytes = 0, totalRead = 0, totalParse = 0;
    for (const auto& s : sources) {
      const auto bytes = readSource(s);
      size_t specs = 0;
      double read = secondsFor(repeat, [&] {
        auto b = readSource(s);
        if (b.size() != bytes.size()) throw std::runtime_error(s.name + " changed while reading");
      });
      double parse = secondsFor(repeat, [&] { specs = sdg::usd::readCrateLayer(bytes, s.name).specs.size(); });
      double mb = double(bytes.size()) * repeat / 1e6;
      std::printf("%-50s %9zu %7zu %12.1f %12.1f %8.2f\n", s.name.c_str(), bytes.size(), specs, mb / read,
                  mb / parse, parse / read);
      totalBytes += mb, totalRead += read, totalParse += parse;
    }
    std::printf("%-50s %9s %7s %12.1f %12.1f %8.2f\n", "all", "", "", totalBytes / totalRead,
                totalBytes / totalParse, totalParse / totalRead);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
