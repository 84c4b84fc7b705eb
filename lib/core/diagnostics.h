#pragma once
// Problems found in user input are collected, not thrown one at a time, so a
// user sees every mistake of a file at once. The library never exits: it
// throws one of the two error types below and the CLI maps them to exit codes.
#include <stdexcept>
#include <string>
#include <vector>

#include "core/source_loc.h"

namespace sdg {

enum class Severity { Warning, Error };

struct Diagnostic {
  Severity severity = Severity::Error;
  SourceLoc loc;
  std::string message;
  // "file:line:col: error: message" (the compiler convention editors parse).
  std::string format() const;
};

class Diagnostics {
 public:
  void error(const SourceLoc& loc, std::string message);
  void warning(const SourceLoc& loc, std::string message);
  bool hasErrors() const { return errorCount_ > 0; }
  size_t errorCount() const { return errorCount_; }
  const std::vector<Diagnostic>& all() const { return items_; }
  void append(const Diagnostics& other);
  // Throws SceneError carrying every error collected so far, if any.
  void throwIfErrors() const;

 private:
  std::vector<Diagnostic> items_;
  size_t errorCount_ = 0;
};

// Invalid input: a scene, a flag, an override. The CLI exits with 2.
class SceneError : public std::runtime_error {
 public:
  explicit SceneError(std::vector<Diagnostic> problems);
  SceneError(const SourceLoc& loc, const std::string& message);
  const std::vector<Diagnostic>& problems() const { return problems_; }

 private:
  std::vector<Diagnostic> problems_;
};

// A failure while running a valid scene (I/O, physics, rendering). Exit 1.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace sdg
