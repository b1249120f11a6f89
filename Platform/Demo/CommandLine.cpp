// Command-line parsing of the demo program: strict, with messages that name the bad value.
#include "Platform/Demo/CommandLine.hpp"

#include <cctype>

namespace sr::demo {

namespace {

// Parses a whole string as a decimal integer in [1, kMaxFrames]; no sign, no spaces, no suffix.
std::optional<long long> parseFrameCount(const std::string& text) {
    if (text.empty() || text.size() > 10)
        return std::nullopt;
    long long value = 0;
    for (const char c : text) {
        if (!std::isdigit(static_cast<unsigned char>(c)))
            return std::nullopt;
        value = value * 10 + (c - '0');
    }
    if (value < 1 || value > kMaxFrames)
        return std::nullopt;
    return value;
}

ParseResult failure(std::string message) {
    ParseResult r;
    r.error = std::move(message);
    return r;
}

} // namespace

ParseResult parseCommandLine(const std::vector<std::string>& args) {
    ParseResult result;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg == "--help" || arg == "-h" || arg == "/?") {
            result.options.help = true;
            continue;
        }

        // --frames N or --frames=N
        std::optional<std::string> value;
        if (arg == "--frames") {
            if (i + 1 >= args.size())
                return failure("--frames needs a value: --frames N (N >= 1)");
            value = args[++i];
        } else if (arg.rfind("--frames=", 0) == 0) {
            value = arg.substr(9);
        }
        if (value) {
            if (result.options.frames)
                return failure("--frames given twice");
            const std::optional<long long> n = parseFrameCount(*value);
            if (!n)
                return failure("bad value for --frames: '" + *value + "' (expected an integer from 1 to " +
                               std::to_string(kMaxFrames) + ")");
            result.options.frames = n;
            continue;
        }

        if (arg.empty())
            return failure("empty argument");
        return failure("unknown argument: '" + arg + "'");
    }
    result.ok = true;
    return result;
}

std::string usageText(const std::string& programName) {
    return "Usage: " + programName + " [--frames N] [--help]\n"
           "  --frames N   exit with code 0 after N rendered frames (for scripts and tests)\n"
           "  --help       show this text\n"
           "Keys: Esc quits.\n";
}

} // namespace sr::demo
