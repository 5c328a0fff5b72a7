#pragma once
// Every program logs to standard error: standard output carries only its result (a table, JSON,
// scans), so that `PROGRAM --json | jq .` and `PROGRAM > table.md` take nothing else.

#include <string>

namespace mrslam {

/// Makes spdlog's default logger write to standard error, named after the program.
void logToStandardError(const std::string& program);

}  // namespace mrslam
