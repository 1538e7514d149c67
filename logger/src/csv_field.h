// One field of simpartner-query's CSV: as it is, or quoted (RFC 4180) when
// it holds a comma, a quote or a line break.
#pragma once

#include <string>

namespace simpartner::logger {

std::string CsvField(const std::string& text);

}  // namespace simpartner::logger
