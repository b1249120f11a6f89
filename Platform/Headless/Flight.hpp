// `softraster bench --flight SEED`: a seeded random camera flight (with adversarial poses) that counts non-finite depth and tracks memory.
#pragma once

#include <cstdint>

#include "Platform/Headless/CommandArgs.hpp"
#include "Platform/Headless/Commands.hpp"

namespace sr::headless {

// Renders args.frames frames of the prepared scene, each from a new camera pose drawn from a
// generator seeded with `seed` (the same seed gives the same poses on every platform). One pose
// in eight each: eye exactly at a mesh vertex; eye and target in a triangle's plane; eye inside
// the bounding box; looking straight up or down (view direction parallel to "up"); extreme
// near/far/fov/distance. The rest orbit the model at random distances. Every frame's depth
// buffer is checked for non-finite values. Prints one JSON line (see usage(Bench)).
int runFlight(const CommandArgs& args, PreparedScene& prepared, std::uint32_t seed, Streams io);

// Resident set size now, its peak so far, and its anonymous part (heap and stacks, where a leak
// shows; the rest is file pages of the executable and libraries, which vary from run to run with
// page-cache sharing), in KiB (Linux: /proc/self/status VmRSS, VmHWM, RssAnon).
// Other platforms report -1: reading it on Windows needs psapi/windows.h, which only
// Platform/Win32 may include, so the soak test's memory check runs on Linux.
struct MemoryUsage {
    long long rssKb = -1, peakKb = -1, anonKb = -1;
};
MemoryUsage currentMemoryUsage();

} // namespace sr::headless
