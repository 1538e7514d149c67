// Problems found in user input (parameter files, world and robot XML,
// command lines, bus messages) are data: each one carries where it was found
// so that the message a user reads points at the file, line and element.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace simpartner {

struct Diagnostic {
  std::string file;     // path as the user gave it, or "command line", or a channel name
  int line = 0;         // 1-based; 0 when there is no line (e.g. a whole file)
  std::string element;  // XML element, parameter key or message field; may be empty
  std::string message;  // what is wrong, naming the offending value

  // "file:line: element: message" (parts that are empty are left out).
  std::string Format() const;
};

// Collects diagnostics while a loader keeps going, so that one run reports
// every problem of a file instead of the first one only.
class DiagnosticList {
 public:
  void Add(Diagnostic diagnostic) { items_.push_back(std::move(diagnostic)); }
  void Add(const std::string& file, int line, const std::string& element,
           const std::string& message) {
    items_.push_back(Diagnostic{file, line, element, message});
  }
  void Append(const DiagnosticList& other) {
    items_.insert(items_.end(), other.items_.begin(), other.items_.end());
  }
  bool empty() const { return items_.empty(); }
  size_t size() const { return items_.size(); }
  const std::vector<Diagnostic>& items() const { return items_; }
  // One diagnostic per line, in the order found.
  std::string Format() const;

 private:
  std::vector<Diagnostic> items_;
};

// Base of all errors the libraries throw for bad user input.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// Bad input that has one or more located diagnostics.
class DiagnosticError : public Error {
 public:
  explicit DiagnosticError(DiagnosticList diagnostics)
      : Error(diagnostics.Format()), diagnostics_(std::move(diagnostics)) {}
  const DiagnosticList& diagnostics() const { return diagnostics_; }

 private:
  DiagnosticList diagnostics_;
};

// A parameters file or command line that is wrong (file, line, key).
class ConfigError : public DiagnosticError {
 public:
  using DiagnosticError::DiagnosticError;
};

// A world or robot file that is wrong (file, line, element).
class ModelError : public DiagnosticError {
 public:
  using DiagnosticError::DiagnosticError;
};

}  // namespace simpartner
