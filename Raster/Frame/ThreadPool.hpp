// ThreadPool: a persistent fork-join pool (std::thread + condition variables) owned by a RenderContext.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace sr {

// Runs one job on N "lanes" at a time: lane 0 on the calling thread, lanes 1..N-1 on
// persistent workers that sleep on a condition variable between jobs. run() returns when every
// lane has finished (fork-join), so the caller's stack objects the job refers to stay valid.
// No allocation per job: the job is a function pointer plus a context pointer. Not reentrant
// (a job must not call run() on the same pool). A pool of 1 lane has no worker thread.
// Waking a sleeping thread takes tens of microseconds (15 us on a 2-vCPU VM, measured), and a
// frame has a few jobs per draw, so both sides first poll for a while (kSpinTime) before they
// sleep on the condition variables: a worker waiting for the next draw while the calling thread
// sets it up, the calling thread waiting for a lane that got the larger share of a draw. A pool
// with more lanes than this process may run on at once (usableHardwareThreads) never polls: a
// polling lane would hold a core that a working lane needs (docs/PERFORMANCE.md, Threads).
class ThreadPool {
public:
    explicit ThreadPool(int lanes, int hardwareThreads = usableHardwareThreads())
        : lanes_(std::max(lanes, 1)), polls_(hardwareThreads <= 0 || lanes_ <= hardwareThreads) {
        workers_.reserve(std::size_t(lanes_ - 1));
        for (int lane = 1; lane < lanes_; ++lane) workers_.emplace_back([this, lane] { workerLoop(lane); });
    }
    ~ThreadPool() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_all();
        for (std::thread& t : workers_) t.join();
    }
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int lanes() const { return lanes_; }
    // The hardware threads this process may run on: its CPU affinity where the system says (Linux:
    // sched_getaffinity, so `taskset -c 0` gives 1), else std::thread::hardware_concurrency; 0
    // when unknown.
    static int usableHardwareThreads();
    // The render threads worth starting for `requested`: at least 1 and at most the hardware
    // threads this process may use (an unknown count, 0, limits nothing). More would only take
    // turns on the same CPUs: the image is the same whatever the count, the frame slower
    // (docs/PERFORMANCE.md, Threads).
    static int threadsWorthStarting(int requested, int usable = usableHardwareThreads()) {
        const int n = std::max(requested, 1);
        return usable > 0 ? std::min(n, usable) : n;
    }
    // Whether waits poll before they sleep (not when the lanes outnumber the hardware threads;
    // an unknown count, 0, counts as enough).
    bool polls() const { return polls_; }

    // Calls job(lane) for lane = 0 .. lanes()-1 concurrently and waits for all of them.
    template <class Job>
    void run(Job& job) {
        if (lanes_ == 1) {
            job(0);
            return;
        }
        {
            std::lock_guard<std::mutex> lock(mutex_);
            call_ = [](void* j, int lane) { (*static_cast<Job*>(j))(lane); };
            context_ = &job;
            pending_.store(lanes_ - 1, std::memory_order_relaxed);
            generation_.fetch_add(1, std::memory_order_release);
        }
        wake_.notify_all();
        job(0);
        if (spinUntil([this] { return pending_.load(std::memory_order_acquire) == 0; })) return;
        std::unique_lock<std::mutex> lock(mutex_);
        done_.wait(lock, [this] { return pending_.load(std::memory_order_acquire) == 0; });
    }

private:
    void workerLoop(int lane) {
        std::uint64_t seen = 0;
        for (;;) {
            void (*call)(void*, int) = nullptr;
            void* context = nullptr;
            spinUntil([&] { return generation_.load(std::memory_order_acquire) != seen; });
            {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [&] { return stopping_ || generation_.load(std::memory_order_relaxed) != seen; });
                if (stopping_) return;
                seen = generation_.load(std::memory_order_relaxed);
                call = call_;
                context = context_;
            }
            call(context, lane);
            if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
                // Under the mutex, so a run() that has just found pending_ != 0 is already waiting.
                std::lock_guard<std::mutex> lock(mutex_);
                done_.notify_one();
            }
        }
    }

    int lanes_;
    bool polls_;
    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    void (*call_)(void*, int) = nullptr;
    void* context_ = nullptr;
    // One spin-wait hint (x86 PAUSE; elsewhere a yield). Out of line (ThreadPool.cpp), so this
    // header, which Scene.hpp and the Platform files include, pulls in no intrinsics header.
    static void pause();
    // Polls `ready` (with a pause between polls) until it holds or kSpinTime has passed; returns
    // whether it holds. Timed rather than counted, since a pause takes 10 to 150 cycles by CPU.
    // Without polling (polls_ false): one look.
    template <class Ready>
    bool spinUntil(Ready ready) const {
        if (!polls_) return ready();
        const auto deadline = std::chrono::steady_clock::now() + kSpinTime;
        for (;;) {
            for (int i = 0; i < 16; ++i) {
                if (ready()) return true;
                pause();
            }
            if (std::chrono::steady_clock::now() >= deadline) return ready();
        }
    }
    static constexpr std::chrono::microseconds kSpinTime{300};

    std::atomic<int> pending_{0};
    std::atomic<std::uint64_t> generation_{0};
    bool stopping_ = false;
};

} // namespace sr
