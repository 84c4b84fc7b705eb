#include "core/text.h"

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cmath>
#include <cstdint>

namespace sdg::text {

namespace {

bool sameLetter(char a, char b) {
  return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
}

// Edits (insert, delete, substitute, swap two neighbours) from a to b,
// ignoring case: a swap is one typo, as people make them.
size_t typoDistance(std::string_view a, std::string_view b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (sameLetter(a[i - 1], b[j - 1]) ? 0 : 1)});
      if (i > 1 && j > 1 && sameLetter(a[i - 1], b[j - 2]) && sameLetter(a[i - 2], b[j - 1]))
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

}  // namespace

std::string closestMatch(std::string_view word, std::span<const std::string> candidates) {
  // Long keys are compared only when short enough; a 1 MB typo suggests nothing.
  if (word.size() > 256) return {};
  std::string best;
  size_t bestDistance = SIZE_MAX;
  for (const std::string& c : candidates) {
    // Judge the names after a namespace they share: `exposedVar:ns:nosuchvar`
    // is not a typo of `exposedVar:ns:interval` for sharing `exposedVar:ns:`.
    std::string_view w = word, k = c;
    size_t shared = 0;
    while (shared < w.size() && shared < k.size() && w[shared] == k[shared]) ++shared;
    const size_t colon = w.substr(0, shared).rfind(':');
    if (colon != std::string_view::npos) w.remove_prefix(colon + 1), k.remove_prefix(colon + 1);
    const size_t distance = typoDistance(w, k);
    // About one typo per three letters (at least two), and never a whole
    // different word, however short.
    const bool close = distance <= std::max<size_t>(2, w.size() / 3) && distance < std::max(w.size(), k.size());
    if (close && distance < bestDistance) {
      bestDistance = distance;
      best = c;
    }
  }
  return best;
}

std::string didYouMean(std::string_view word, std::span<const std::string> candidates) {
  std::string best = closestMatch(word, candidates);
  return best.empty() ? std::string{} : " (did you mean '" + best + "'?)";
}

std::string join(std::span<const std::string> items, std::string_view separator) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) {
    if (i) out += separator;
    out += items[i];
  }
  return out;
}

template <typename T>
static std::string shortest(T value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  char buffer[64];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string s(buffer, end);
  // Keep a decimal point so the text reads back as a number of the same kind.
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string formatDouble(double value) { return shortest(value); }
std::string formatFloat(float value) { return shortest(value); }

std::string formatNumber(double value) {
  std::string s = shortest(value);
  if (s.size() > 2 && s.ends_with(".0")) s.resize(s.size() - 2);
  return s;
}

std::string quote(std::string_view value) {
  constexpr size_t kMax = 80;
  if (value.size() > kMax) return "'" + std::string(value.substr(0, kMax)) + "...'";
  return "'" + std::string(value) + "'";
}

std::vector<std::string> splitCsv(std::string_view csv) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= csv.size()) {
    size_t comma = csv.find(',', start);
    if (comma == std::string_view::npos) comma = csv.size();
    std::string_view item = csv.substr(start, comma - start);
    while (!item.empty() && std::isspace(static_cast<unsigned char>(item.front()))) item.remove_prefix(1);
    while (!item.empty() && std::isspace(static_cast<unsigned char>(item.back()))) item.remove_suffix(1);
    if (!item.empty()) out.emplace_back(item);
    start = comma + 1;
  }
  return out;
}

}  // namespace sdg::text
