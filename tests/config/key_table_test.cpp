// KeyTable lists what a reader asks for: the rows the scenario reference is made of.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "rpsd/config/key_table.h"

namespace rpsd::config {
namespace {

TEST(KeyTable, ListsEveryReadWithItsRangeAndDefault) {
  KeyTable table("clock");
  EXPECT_EQ(table.number("rate_hz", Number::between(1.0, 65536.0, "Hz", "steps per second")), 1.0);
  EXPECT_EQ(table.number_or("wait_s", 0.5, {"s", "a wait", 0.0, 60.0, true}), 0.5);
  EXPECT_FALSE(table.optional_number("end_s", Number::positive("s", "the end")));
  EXPECT_FALSE(table.optional_text("file", "a file"));
  EXPECT_FALSE(table.optional_numbers("values", Number::any("", "values"), 4));
  EXPECT_EQ(table.whole_number("channels", 1, 8, "channels"), 8);  // a list sized by it shows its longest
  EXPECT_EQ(table.choice_or("mode", {"a", "b"}, "b", "a mode"), "b");
  EXPECT_NE(table.optional_section("limits", "limits"), nullptr);  // a listing descends into it
  EXPECT_EQ(table.sections("stories", 200, "stories").size(), 1u);

  const auto& rows = table.rows();
  ASSERT_EQ(rows.size(), 9u);
  EXPECT_EQ(rows[0].path, "clock.rate_hz");
  EXPECT_EQ(rows[0].range, "1 to 65536");
  EXPECT_EQ(rows[0].unit, "Hz");
  EXPECT_EQ(rows[0].fallback, "");
  EXPECT_EQ(rows[1].range, "> 0 and <= 60");
  EXPECT_EQ(rows[1].fallback, "0.5");
  EXPECT_EQ(rows[2].range, "> 0");
  EXPECT_EQ(rows[2].fallback, "none");
  EXPECT_EQ(rows[4].type, "list of 1 to 4 numbers");
  EXPECT_EQ(rows[6].range, "a or b");
  EXPECT_EQ(rows[6].fallback, "b");
  EXPECT_EQ(rows[8].type, "list of 1 to 200 sections");
}

TEST(KeyTable, AFailureStopsTheListingWithItsOwnError) {
  KeyTable table;
  table.number("start", Number::positive("", "start"));
  EXPECT_THROW(table.fail("stop", "must be greater than start"), ListingStopped);
  EXPECT_THROW(table.fail_section("does not fit"), ListingStopped);
  EXPECT_EQ(table.rows().size(), 1u);
}

TEST(RangeText, SaysWhichBoundsAreOpen) {
  EXPECT_EQ(range_text(Number::between(0.0, 1.0, "", "")), "0 to 1");
  EXPECT_EQ(range_text({"", "", 0.0, 1000.0, true}), "> 0 and <= 1000");
  EXPECT_EQ(range_text({"", "", 0.0, 1.0, false, true}), ">= 0 and < 1");
  EXPECT_EQ(range_text(Number::non_negative("", "")), ">= 0");
  EXPECT_EQ(range_text(Number::any("", "")), "any");
}

}  // namespace
}  // namespace rpsd::config
