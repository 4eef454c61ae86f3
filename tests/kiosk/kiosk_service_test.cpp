// bodyview under a stand-in service manager (the notification socket of
// systemd's Type=notify, tests/platform/notify_listener.h): READY=1 comes after
// the first frame, WATCHDOG=1 while frames are drawn, STOPPING=1 at the end; a
// kiosk killed with SIGKILL and started again (Restart=always) is ready again.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "../cli/cli_test.h"
#include "tests/common/test_dir.h"
#include "tests/platform/notify_listener.h"

extern char** environ;

namespace body {
namespace {

namespace fs = std::filesystem;

class KioskService : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::fresh_test_dir("body_kiosk_service");
        socket_ = (dir_ / "notify").string();
        listener_ = std::make_unique<test::NotifyListener>(socket_);
        ASSERT_TRUE(listener_->bound());
        std::ofstream(dir_ / "scene.json")
            << R"({"models": [{"name": "smoke", "file": ")" << BODY_TEST_DATA_DIR << R"(/models/smoke.obj"}]})";
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Starts bodyview as the unit would (its own pid in WATCHDOG_PID); `extra` after the scene.
    pid_t start(const std::string& extra) {
        const std::string cmd = "WATCHDOG_PID=$$ exec " + test::bin("bodyview") +
                                " --headless --size 320x200 --scene " + (dir_ / "scene.json").string() + " " + extra;
        const std::string env_socket = "NOTIFY_SOCKET=" + socket_, env_usec = "WATCHDOG_USEC=40000";
        std::vector<std::string> env_strings = {env_socket, env_usec};
        for (char** e = environ; *e; ++e) env_strings.emplace_back(*e);
        std::vector<char*> envp;
        for (auto& s : env_strings) envp.push_back(s.data());
        envp.push_back(nullptr);
        const char* argv[] = {"/bin/sh", "-c", cmd.c_str(), nullptr};
        pid_t pid = -1;
        EXPECT_EQ(::posix_spawn(&pid, "/bin/sh", nullptr, nullptr, const_cast<char* const*>(argv), envp.data()), 0);
        return pid;
    }
    // Messages until one starts with `prefix` (or the process ends, or a minute passes).
    bool wait_for(const std::string& prefix, pid_t pid, std::vector<std::string>& seen) {
        for (int i = 0; i < 6000; ++i) {
            for (auto& m : listener_->drain()) {
                seen.push_back(m);
                if (m.rfind(prefix, 0) == 0) return true;
            }
            if (::waitpid(pid, nullptr, WNOHANG) == pid) return false;
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        return false;
    }

    fs::path dir_;
    std::string socket_;
    std::unique_ptr<test::NotifyListener> listener_;
};

TEST_F(KioskService, ReadyAfterTheFirstFrameWatchdogWhileDrawingStoppingAtTheEnd) {
    const pid_t pid = start("--frames 120");
    // Drained while it runs, as systemd does: a full socket queue blocks the sender.
    std::vector<std::string> messages;
    int status = 0;
    while (::waitpid(pid, &status, WNOHANG) != pid) {
        for (auto& m : listener_->drain()) messages.push_back(m);
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    for (auto& m : listener_->drain()) messages.push_back(m);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
    ASSERT_GE(messages.size(), 3u);
    EXPECT_EQ(messages.front().rfind("READY=1", 0), 0u) << messages.front();
    EXPECT_EQ(messages.back(), "STOPPING=1");
    // 120 llvmpipe frames take far longer than the 10 ms ping period.
    for (size_t i = 1; i + 1 < messages.size(); ++i) EXPECT_EQ(messages[i], "WATCHDOG=1");
}

TEST_F(KioskService, KilledKioskStartedAgainIsReadyAgain) {
    for (int round = 0; round < 2; ++round) {
        const pid_t pid = start("");
        std::vector<std::string> seen;
        ASSERT_TRUE(wait_for("READY=1", pid, seen)) << "round " << round;
        ASSERT_TRUE(wait_for("WATCHDOG=1", pid, seen)) << "round " << round;  // still drawing
        ASSERT_EQ(::kill(pid, SIGKILL), 0);
        int status = 0;
        ASSERT_EQ(::waitpid(pid, &status, 0), pid);
        EXPECT_TRUE(WIFSIGNALED(status));
    }
}

TEST_F(KioskService, SigtermEndsTheKioskCleanly) {
    const pid_t pid = start("");
    std::vector<std::string> seen;
    ASSERT_TRUE(wait_for("READY=1", pid, seen));
    ASSERT_EQ(::kill(pid, SIGTERM), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
    EXPECT_TRUE(wait_for("STOPPING=1", pid, seen) || (!seen.empty() && seen.back() == "STOPPING=1"));
}

}  // namespace
}  // namespace body
