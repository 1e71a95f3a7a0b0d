#include "welkin/core/child_process.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cstring>
#include <stdexcept>

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define WELKIN_TEST_UNDER_ASAN 1
#endif
#endif

namespace welkin {
namespace {

std::vector<uint8_t> bytes(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }

TEST(ChildProcess, ReturnsTheWorksBytes) {
  // Larger than a pipe's buffer: the parent reads while the child writes.
  std::string big(300000, 'x');
  big[12345] = 'y';
  const ChildResult r = run_in_child([&] { return bytes(big); }, {});
  ASSERT_EQ(r.status, ChildResult::Status::ok) << r.detail;
  EXPECT_EQ(std::string(r.bytes.begin(), r.bytes.end()), big);
  // The work ran in another process.
  const pid_t parent = getpid();
  const ChildResult pid = run_in_child([&] { return bytes(getpid() == parent ? "same" : "other"); }, {});
  EXPECT_EQ(std::string(pid.bytes.begin(), pid.bytes.end()), "other");
}

TEST(ChildProcess, CpuTimeLimitKillsTheChild) {
  ChildLimits limits;
  limits.seconds = 1.0;
  const ChildResult r = run_in_child(
      [] {
        volatile uint64_t x = 0;
        for (;;) x = x + 1;
        return std::vector<uint8_t>{};
      },
      limits);
  EXPECT_EQ(r.status, ChildResult::Status::over_time) << r.detail;
  EXPECT_EQ(describe(r, limits), "more than 1 s of CPU time");
}

TEST(ChildProcess, WallClockLimitKillsABlockedChild) {
  ChildLimits limits;
  limits.wall_seconds = 0.3;
  const ChildResult r = run_in_child(
      [] {
        pause();  // blocks without spending CPU time
        return std::vector<uint8_t>{};
      },
      limits);
  EXPECT_EQ(r.status, ChildResult::Status::over_time);
  EXPECT_EQ(r.detail, "wall-clock limit");
}

TEST(ChildProcess, MemoryLimitFailsTheAllocation) {
  ChildLimits limits;
  limits.memory_bytes = 64ull << 20;
  const ChildResult r = run_in_child(
      [] {
        std::vector<uint8_t> v(1ull << 30);  // 1 GiB, above the 64 MiB the child may add
        v[v.size() - 1] = 1;
        return std::vector<uint8_t>{v.back()};
      },
      limits);
#ifdef WELKIN_TEST_UNDER_ASAN
  EXPECT_EQ(r.status, ChildResult::Status::failed) << r.detail;  // ASan's `new` exits instead of throwing
#else
  EXPECT_EQ(r.status, ChildResult::Status::over_memory) << r.detail;
  EXPECT_EQ(describe(r, limits), "more than 64 MiB of memory");
#endif
  // The same work within a larger budget succeeds.
  limits.memory_bytes = 2ull << 30;
  const ChildResult ok = run_in_child(
      [] {
        std::vector<uint8_t> v(256ull << 20);
        v.back() = 7;
        return std::vector<uint8_t>{v.back()};
      },
      limits);
  ASSERT_EQ(ok.status, ChildResult::Status::ok) << ok.detail;
  EXPECT_EQ(ok.bytes, std::vector<uint8_t>{7});
}

TEST(ChildProcess, OversizedResultIsRefused) {
  ChildLimits limits;
  limits.max_result_bytes = 1000;
  EXPECT_EQ(run_in_child([] { return std::vector<uint8_t>(1000, 1); }, limits).status, ChildResult::Status::ok);
  EXPECT_EQ(run_in_child([] { return std::vector<uint8_t>(200000, 1); }, limits).status,
            ChildResult::Status::over_result);
}

TEST(ChildProcess, ACrashOrAnExceptionInTheChildIsReportedNotInherited) {
  const ChildResult crash = run_in_child(
      [] {
        raise(SIGSEGV);
        return std::vector<uint8_t>{};
      },
      {});
  EXPECT_EQ(crash.status, ChildResult::Status::failed);
  EXPECT_NE(crash.detail.find("signal " + std::to_string(SIGSEGV)), std::string::npos) << crash.detail;
  const ChildResult thrown = run_in_child([]() -> std::vector<uint8_t> { throw std::runtime_error("no"); }, {});
  EXPECT_EQ(thrown.status, ChildResult::Status::failed);
  EXPECT_EQ(thrown.detail, "an exception");
}

}  // namespace
}  // namespace welkin
