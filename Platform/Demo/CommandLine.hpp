// Command-line parsing of the demo program (--frames N, --help): platform-free and unit-tested.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace sr::demo {

// Process exit codes shared by every front end.
inline constexpr int kExitOk = 0;
inline constexpr int kExitUsage = 2; // bad command line

struct DemoOptions {
    // Exit with kExitOk after this many rendered frames; empty = run until closed.
    std::optional<long long> frames;
    bool help = false;
};

// Either options or a one-line message naming the offending argument.
struct ParseResult {
    bool ok = false;
    DemoOptions options;
    std::string error;
};

// Largest accepted --frames value (about 1 year at 60 Hz: plenty, and far from overflow).
inline constexpr long long kMaxFrames = 2'000'000'000LL;

// Parses the arguments that follow the program name (UTF-8). Accepts "--frames N",
// "--frames=N" (1 <= N <= kMaxFrames), "--help", "-h" and "/?". Anything else is an error.
ParseResult parseCommandLine(const std::vector<std::string>& args);

// The usage text shown by --help and after an error (lines end in '\n').
std::string usageText(const std::string& programName);

} // namespace sr::demo
