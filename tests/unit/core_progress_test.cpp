// Progress output: one rewritten line on a terminal, readable lines in a log.

#include <sierra/core/Progress.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace {

std::string capture(bool terminal, int total) {
    std::FILE* f = std::tmpfile();
    sierra::Progress p("frames", total, f, terminal ? 1 : 0);
    for (int k = 1; k <= total; ++k) p.update(k, "ok");
    p.finish();
    std::rewind(f);
    std::string text;
    for (int c; (c = std::fgetc(f)) != EOF;) text.push_back(char(c));
    std::fclose(f);
    return text;
}

TEST(Progress, RedirectedOutputHasPlainLinesAtMostPerTenth) {
    std::string log = capture(false, 200);
    EXPECT_EQ(log.find('\r'), std::string::npos);
    EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 11) << log;  // 0%, 10%, ..., 100%
    EXPECT_NE(log.find("frames 200/200: ok\n"), std::string::npos);
    // Fewer steps than tenths: one line per step.
    std::string few = capture(false, 3);
    EXPECT_EQ(std::count(few.begin(), few.end(), '\n'), 3);
}

TEST(Progress, TerminalRewritesOneLine) {
    std::string screen = capture(true, 50);
    EXPECT_EQ(std::count(screen.begin(), screen.end(), '\r'), 50);
    EXPECT_EQ(std::count(screen.begin(), screen.end(), '\n'), 1);
}

TEST(Progress, FixedNeverUsesScientificNotation) {
    EXPECT_EQ(sierra::fixed(3e-05), "0.000");
    EXPECT_EQ(sierra::fixed(0.031234), "0.031");
    EXPECT_EQ(sierra::fixed(1234.5, 1), "1234.5");
}

}  // namespace
