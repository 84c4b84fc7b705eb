#include "core/diagnostics.h"

#include <algorithm>
#include <tuple>

namespace sdg {

std::string SourceLoc::str() const {
  if (file.empty()) return {};
  if (line <= 0) return file.str();
  if (column <= 0) return file.str() + ":" + std::to_string(line);
  return file.str() + ":" + std::to_string(line) + ":" + std::to_string(column);
}

std::string SourceLoc::referenceChain() const {
  std::string out;
  for (const SourceLoc* from = via.get(); from; from = from->via.get())
    out += (out.empty() ? "referenced from " : ", from ") + from->str();
  return out;
}

std::string Diagnostic::format() const {
  std::string out = loc.str();
  if (!out.empty()) out += ": ";
  out += severity == Severity::Error ? "error: " : "warning: ";
  out += message;
  if (loc.via) out += " (" + loc.referenceChain() + ")";
  return out;
}

void Diagnostics::error(const SourceLoc& loc, std::string message) {
  items_.push_back({Severity::Error, loc, std::move(message)});
  ++errorCount_;
}

void Diagnostics::warning(const SourceLoc& loc, std::string message) {
  items_.push_back({Severity::Warning, loc, std::move(message)});
}

void Diagnostics::append(const Diagnostics& other) {
  for (const Diagnostic& d : other.items_) {
    items_.push_back(d);
    if (d.severity == Severity::Error) ++errorCount_;
  }
}

void Diagnostics::throwIfErrors() const {
  if (!hasErrors()) return;
  std::vector<Diagnostic> errors;
  for (const Diagnostic& d : items_)
    if (d.severity == Severity::Error) errors.push_back(d);
  // In reading order, as a user fixes them top to bottom.
  std::stable_sort(errors.begin(), errors.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::tie(a.loc.file, a.loc.line, a.loc.column) < std::tie(b.loc.file, b.loc.line, b.loc.column);
  });
  throw SceneError(std::move(errors));
}

static std::string joinProblems(const std::vector<Diagnostic>& problems) {
  std::string text;
  for (const Diagnostic& d : problems) {
    if (!text.empty()) text += '\n';
    text += d.format();
  }
  return text;
}

SceneError::SceneError(std::vector<Diagnostic> problems)
    : std::runtime_error(joinProblems(problems)), problems_(std::move(problems)) {}

SceneError::SceneError(const SourceLoc& loc, const std::string& message)
    : SceneError(std::vector<Diagnostic>{{Severity::Error, loc, message}}) {}

}  // namespace sdg
