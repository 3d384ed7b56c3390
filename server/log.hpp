#pragma once
// The service's log on stderr: one line per event, with the time (UTC,
// milliseconds) and a level, so that an operator can sort, filter and
// correlate the lines of many processes:
//   2026-11-26T10:48:48.123Z WARN  gearsph worker vm:12:ab12cd34: renewing the leases failed: ...
#include <string>
#include <string_view>

namespace gearsph::server {

enum class LogLevel { info, warning, error };

// The text with every control character escaped (\n, \r, \t, \xHH) and
// backslashes doubled: what a log line holds of strings from requests.
std::string escape_log_text(std::string_view text);

// printf-style, its text escaped (escape_log_text) but for a final newline;
// the line is written with one call, so lines of different
// threads never interleave.
void log_line(LogLevel level, const char* format, ...) __attribute__((format(printf, 2, 3)));

}  // namespace gearsph::server
