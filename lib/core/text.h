#pragma once
// Small text helpers used by error messages and the YAML writer.
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sdg::text {

// The candidate closest to `word` by edit distance, or "" when none is close
// enough to be a plausible typo.
std::string closestMatch(std::string_view word, std::span<const std::string> candidates);
// " (did you mean 'x'?)" or "".
std::string didYouMean(std::string_view word, std::span<const std::string> candidates);
// What an unknown behavior name says when no known name is close: it may
// be defined by a script (or plugin) that is not loaded.
inline constexpr std::string_view kScriptNotLoadedHint =
    "; a behavior defined in a script or plugin needs it loaded (the scene's scripts: or plugins:, or --script "
    "FILE.py / --plugin LIB)";
std::string join(std::span<const std::string> items, std::string_view separator);
// Shortest decimal text that reads back to exactly the same double.
std::string formatDouble(double value);
std::string formatFloat(float value);
// For messages: integers without a decimal point ("1", "0.5").
std::string formatNumber(double value);
// Quote a user string for a message: 'abc' (truncated when very long).
std::string quote(std::string_view value);
std::vector<std::string> splitCsv(std::string_view csv);

}  // namespace sdg::text
