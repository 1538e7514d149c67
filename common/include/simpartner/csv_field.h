// One field of a CSV file SimPartner writes (simpartner-query's exports,
// simpartner-batch's summary), as a spreadsheet must read it: RFC 4180
// quoting, and no formula. Text from a batch file or the bus may begin
// with '=', '+', '-', '@', a tab or a carriage return, which a spreadsheet
// runs as a formula (=HYPERLINK(...)); such a field is written as text,
// behind a single quote, as OWASP's CSV-injection guidance says. A number
// ("-1.5", "+2e3") stays a number.
#pragma once

#include <string>

namespace simpartner {

std::string CsvField(const std::string& text);

}  // namespace simpartner
