#include "shared/cli_args.h"

#include <gtest/gtest.h>

namespace body {
namespace {

TEST(CliArgs, ParsesPositionalValuesAndFlags) {
    auto a = CliArgs::parse({"in.json", "-o", "out.obj", "--caps=dome", "--quiet", "--ratio", "0.5"},
                            {"output", "caps", "ratio"}, {"quiet"});
    ASSERT_TRUE(a.ok()) << a.error().message;
    EXPECT_EQ(a->positional(), std::vector<std::string>{"in.json"});
    EXPECT_EQ(a->get_or("output", ""), "out.obj");
    EXPECT_EQ(a->get_or("caps", ""), "dome");
    EXPECT_TRUE(a->has("quiet"));
    EXPECT_DOUBLE_EQ(*a->get_double("ratio", 1.0), 0.5);
    EXPECT_DOUBLE_EQ(*a->get_double("missing", 1.0), 1.0);
}

TEST(CliArgs, RejectsUnknownOptionsMissingValuesAndBadNumbers) {
    auto unknown = CliArgs::parse({"--cpas", "dome"}, {"caps"}, {});
    ASSERT_FALSE(unknown.ok());
    EXPECT_NE(unknown.error().message.find("--cpas"), std::string::npos);
    EXPECT_EQ(unknown.error().exit_code, kExitBadInput);
    EXPECT_FALSE(CliArgs::parse({"--caps"}, {"caps"}, {}).ok());
    EXPECT_FALSE(CliArgs::parse({"--quiet=1"}, {}, {"quiet"}).ok());
    auto bad = CliArgs::parse({"--ratio", "half"}, {"ratio"}, {});
    ASSERT_TRUE(bad.ok());
    auto r = bad->get_double("ratio", 1.0);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("half"), std::string::npos);
}

TEST(CliArgs, NegativeNumbersArePositional) {
    auto a = CliArgs::parse({"-1.5", "-.5"}, {}, {});
    ASSERT_TRUE(a.ok());
    EXPECT_EQ(a->positional().size(), 2u);
}

TEST(CliArgs, JobsAreOneTo256WithTheFallbackWhenAbsent) {
    const auto jobs = [](std::vector<std::string> argv) { return CliArgs::parse(argv, {"jobs"}, {})->get_jobs(3); };
    EXPECT_EQ(*jobs({}), 3u);
    EXPECT_EQ(*jobs({"--jobs", "1"}), 1u);
    EXPECT_EQ(*jobs({"--jobs=256"}), 256u);
    for (const char* bad : {"0", "257", "-2", "two"}) {
        auto r = jobs({"--jobs", bad});
        ASSERT_FALSE(r.ok()) << bad;
        EXPECT_NE(r.error().message.find("--jobs"), std::string::npos);
        EXPECT_EQ(r.error().exit_code, kExitBadInput);
    }
}

}  // namespace
}  // namespace body
