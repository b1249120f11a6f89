// Tests of the demo's command-line parser (--frames N, --help, errors) and key -> action map.
#include "TestFramework.hpp"

#include "Platform/Demo/CommandLine.hpp"
#include "Platform/Demo/Input.hpp"

using sr::demo::parseCommandLine;

TEST_CASE("no arguments: run until closed", "[platform]") {
    const auto r = parseCommandLine({});
    REQUIRE(r.ok);
    CHECK_FALSE(r.options.frames.has_value());
    CHECK_FALSE(r.options.help);
    CHECK(r.error.empty());
}

TEST_CASE("--frames N and --frames=N", "[platform]") {
    auto r = parseCommandLine({"--frames", "5"});
    REQUIRE(r.ok);
    CHECK(r.options.frames == 5);

    r = parseCommandLine({"--frames=120"});
    REQUIRE(r.ok);
    CHECK(r.options.frames == 120);

    r = parseCommandLine({"--frames", "2000000000"});
    REQUIRE(r.ok);
    CHECK(r.options.frames == sr::demo::kMaxFrames);
}

TEST_CASE("--help, -h and /? ask for help", "[platform]") {
    for (const char* flag : {"--help", "-h", "/?"}) {
        const auto r = parseCommandLine({flag});
        REQUIRE(r.ok);
        CHECK(r.options.help);
    }
    const auto both = parseCommandLine({"--frames", "3", "--help"});
    REQUIRE(both.ok);
    CHECK(both.options.help);
    CHECK(both.options.frames == 3);
}

TEST_CASE("bad --frames values are rejected with the value in the message", "[platform]") {
    for (const char* bad : {"0", "-1", "+3", "abc", "12x", " 7", "3.5", "", "2000000001", "99999999999999999999"}) {
        INFO("value: '" << bad << "'");
        const auto r = parseCommandLine({"--frames", bad});
        CHECK_FALSE(r.ok);
        CHECK(r.error.find("--frames") != std::string::npos);
        CHECK(r.error.find(std::string("'") + bad + "'") != std::string::npos);
    }
    const auto eq = parseCommandLine({"--frames=-4"});
    CHECK_FALSE(eq.ok);
}

TEST_CASE("--frames without a value, or twice, is an error", "[platform]") {
    auto r = parseCommandLine({"--frames"});
    CHECK_FALSE(r.ok);
    CHECK(r.error.find("needs a value") != std::string::npos);

    r = parseCommandLine({"--frames", "2", "--frames=3"});
    CHECK_FALSE(r.ok);
    CHECK(r.error.find("twice") != std::string::npos);
}

TEST_CASE("unknown arguments are named in the error", "[platform]") {
    for (const char* bad : {"--frame", "frames", "--FRAMES", "-x", "--help=1", "--frames5"}) {
        INFO("argument: " << bad);
        const auto r = parseCommandLine({bad});
        CHECK_FALSE(r.ok);
        CHECK(r.error.find(std::string("'") + bad + "'") != std::string::npos);
    }
    CHECK_FALSE(parseCommandLine({""}).ok);
    // A non-ASCII argument (UTF-8) is reported, not mangled.
    const auto r = parseCommandLine({"--f\xC3\xA9"});
    CHECK_FALSE(r.ok);
    CHECK(r.error.find("--f\xC3\xA9") != std::string::npos);
}

TEST_CASE("usage text names the program and every flag", "[platform]") {
    const std::string text = sr::demo::usageText("SoftRaster.exe");
    CHECK(text.find("SoftRaster.exe") != std::string::npos);
    CHECK(text.find("--frames N") != std::string::npos);
    CHECK(text.find("--help") != std::string::npos);
    CHECK(text.back() == '\n');
}

TEST_CASE("Escape quits, other keys do nothing", "[platform]") {
    using sr::demo::Action;
    using sr::demo::Key;
    CHECK(sr::demo::actionForKey(Key::Escape) == Action::Quit);
    CHECK(sr::demo::actionForKey(Key::Unknown) == Action::None);
    STATIC_REQUIRE(sr::demo::actionForKey(Key::Escape) == Action::Quit);
}
