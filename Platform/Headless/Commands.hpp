// The headless command's subcommands (render, bench, report, compare); each returns a process exit code.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace sr::headless {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1; // the command ran but failed (unreadable model, I/O error)
inline constexpr int kExitUsage = 2;   // bad command line

// Where a command writes: `out` gets the machine-readable result (a path, one JSON line, ...),
// `err` diagnostics and errors (one line each). `progress` enables the report's live progress line.
struct Streams {
    std::ostream& out;
    std::ostream& err;
    bool progress = false;
};

// args exclude the program name and the subcommand.
int runRender(const std::vector<std::string>& args, Streams io);
int runBench(const std::vector<std::string>& args, Streams io);
int runReport(const std::vector<std::string>& args, Streams io);
// compare A B [--map OUT.png]: the error metrics of two image files (one JSON line) and their heat map.
int runCompare(const std::vector<std::string>& args, Streams io);

// Top-level dispatch: args exclude the program name ("render ...", "bench ...", "--help").
int runHeadless(const std::vector<std::string>& args, Streams io);

} // namespace sr::headless
