// Tests of app/cli_text.cpp: the locale rule for µm and χ², plurals, cut text, near names.
#include "app/cli_text.hpp"

#include <string>

#include <gtest/gtest.h>

namespace gpm::cli {
namespace {

TEST(CliText, Utf8IsTheFirstSetLocaleVariable) {
  EXPECT_TRUE(locale_is_utf8(nullptr, nullptr, "en_GB.UTF-8"));
  EXPECT_TRUE(locale_is_utf8(nullptr, nullptr, "C.utf8"));
  EXPECT_FALSE(locale_is_utf8(nullptr, nullptr, "C"));
  EXPECT_FALSE(locale_is_utf8(nullptr, nullptr, nullptr));
  EXPECT_FALSE(locale_is_utf8("C", nullptr, "en_GB.UTF-8"));  // LC_ALL wins
  EXPECT_TRUE(locale_is_utf8("", "de_DE.UTF-8", "C"));        // an empty one does not count
}

TEST(CliText, CountsTakeThePluralUnlessOne) {
  EXPECT_EQ(count_of(1, "alarm"), "1 alarm");
  EXPECT_EQ(count_of(0, "alarm"), "0 alarms");
  EXPECT_EQ(count_of(2, "alarm"), "2 alarms");
  EXPECT_EQ(count_of(3, "mouse", "mice"), "3 mice");
}

TEST(CliText, LongTextIsCutToFortyCharactersAndAnEllipsis) {
  const std::string digits(300, '7');
  EXPECT_EQ(cut(digits), std::string(40, '7') + "\u2026");
  EXPECT_EQ(cut("12345"), "12345");
  const std::string micro = std::string(39, 'a') + "\u00b5m";  // never half a UTF-8 character
  EXPECT_EQ(cut(micro), std::string(39, 'a') + "\u2026");
}

TEST(CliText, CloseNamesByEditsOrPrefix) {
  const std::vector<std::string> names{"home", "ik", "fk"};
  EXPECT_EQ(edit_distance("hom", "home"), 1u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(close_names("hom", names), std::vector<std::string>{"home"});
  EXPECT_EQ(close_names("xyzzy", names), std::vector<std::string>{});
  EXPECT_EQ(close_names("sim", {"simulate", "sample"}), std::vector<std::string>{"simulate"});
}

}  // namespace
}  // namespace gpm::cli
