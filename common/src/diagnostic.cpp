#include "simpartner/diagnostic.h"

#include "simpartner/check.h"

namespace simpartner {

std::string Diagnostic::Format() const {
  std::string out = file.empty() ? std::string("<input>") : file;
  if (line > 0) out += ":" + std::to_string(line);
  out += ": ";
  if (!element.empty()) out += element + ": ";
  out += message;
  return out;
}

std::string DiagnosticList::Format() const {
  std::string out;
  for (const Diagnostic& d : items_) {
    if (!out.empty()) out += "\n";
    out += d.Format();
  }
  return out;
}

void ThrowInternalError(const char* condition, const char* func,
                        const char* file, int line, const std::string& detail) {
  std::string what = std::string("internal error: condition '") + condition +
                     "' failed in " + func + " at " + file + ":" +
                     std::to_string(line);
  if (!detail.empty()) what += ": " + detail;
  throw InternalError(what);
}

}  // namespace simpartner
