// The streaming loader hands a file over in order, in bounded pieces per pump,
// and reports read and consumer errors.
#include "kiosk/app/stream_loader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

namespace body::kiosk {
namespace {

std::string temp_file(const std::string& bytes) {
    char name[] = "/tmp/body_stream_XXXXXX";
    const int fd = ::mkstemp(name);
    EXPECT_GE(fd, 0);
    ::close(fd);
    std::ofstream(name, std::ios::binary) << bytes;
    return name;
}

TEST(StreamLoader, DeliversTheWholeFileInOrderWithinThePerPumpBudget) {
    std::string bytes;
    for (int i = 0; i < 100000; ++i) bytes.push_back(static_cast<char>(i * 7 % 251));
    const std::string path = temp_file(bytes);
    std::string got;
    {
        StreamLoader loader(path, 4096, 4);
        size_t pumps = 0;
        while (!loader.finished()) {
            loader.wait_for_data();
            auto n = loader.pump(
                [&](std::span<const uint8_t> chunk) {
                    got.append(reinterpret_cast<const char*>(chunk.data()), chunk.size());
                    return ok_status();
                },
                8192);
            ASSERT_TRUE(n) << n.error().message;
            EXPECT_LE(*n, 8192u);
            ++pumps;
        }
        EXPECT_EQ(loader.bytes_total(), bytes.size());
        EXPECT_EQ(loader.bytes_fed(), bytes.size());
        EXPECT_GE(pumps, bytes.size() / 8192);
    }
    EXPECT_EQ(got, bytes);
    ::unlink(path.c_str());
}

TEST(StreamLoader, ReportsAMissingFileAndAConsumerError) {
    StreamLoader missing("/nonexistent/model.bpm");
    missing.wait_for_data();
    auto r = missing.pump([](std::span<const uint8_t>) { return ok_status(); });
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("/nonexistent/model.bpm"), std::string::npos);
    EXPECT_TRUE(missing.finished());

    const std::string path = temp_file(std::string(50000, 'x'));
    StreamLoader loader(path, 1000, 2);  // the reader blocks on a full queue; destruction must still stop it
    loader.wait_for_data();
    auto e = loader.pump([](std::span<const uint8_t>) -> Status { return input_error("m.bpm: byte 0: bad magic"); });
    ASSERT_FALSE(e);
    EXPECT_EQ(e.error().message, "m.bpm: byte 0: bad magic");
    EXPECT_TRUE(loader.finished());
    ::unlink(path.c_str());
}

}  // namespace
}  // namespace body::kiosk
