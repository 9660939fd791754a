// Help text within 100 columns: wrapping at word boundaries and one-line command summaries.
#include "app/help_formatter.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(HelpFormatter, WrapsAtSpacesAndKeepsLineBreaks) {
  EXPECT_EQ(wrapText("one two three four", 9), "one two\nthree\nfour");
  EXPECT_EQ(wrapText("a\nb c", 80), "a\nb c");
  EXPECT_EQ(wrapText("unbreakable-word-longer-than-width x", 5), "unbreakable-word-longer-than-width\nx");
}

TEST(HelpFormatter, SummariesAreTheFirstSentenceOrItsFirstClause) {
  EXPECT_EQ(firstSentence("Learn a scene. Writes RUN/config.json.", 60), "Learn a scene");
  EXPECT_EQ(firstSentence("Write RUN/report.html, one page (no network) of a run: its dataset", 30),
            "Write RUN/report.html");
  EXPECT_EQ(firstSentence("aaaa bbbb cccc dddd eeee ffff", 16), "aaaa bbbb...");
}

}  // namespace
}  // namespace glint
