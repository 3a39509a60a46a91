#include "core/csv.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace hapcine {
namespace {

using Fields = std::vector<std::string>;

TEST(CsvFieldsTest, UnquotedFieldsAreTrimmed) {
  EXPECT_EQ(SplitCsvLine("a, b ,c\r"), (Fields{"a", "b", "c"}));
  EXPECT_EQ(SplitCsvLine("1,2.5,,x y"), (Fields{"1", "2.5", "", "x y"}));
}

TEST(CsvFieldsTest, EmptyLineAndEmptyFields) {
  EXPECT_EQ(SplitCsvLine(""), (Fields{""}));
  EXPECT_EQ(SplitCsvLine(","), (Fields{"", ""}));
  EXPECT_EQ(SplitCsvLine("a,"), (Fields{"a", ""}));
  EXPECT_EQ(SplitCsvLine("\"\""), (Fields{""}));
}

TEST(CsvFieldsTest, QuotedFieldsKeepCommasQuotesAndSpaces) {
  EXPECT_EQ(SplitCsvLine("\"a,b\",\"say \"\"hi\"\"\",\" pad \""),
            (Fields{"a,b", "say \"hi\"", " pad "}));
  // White space around the quotes is not part of the field.
  EXPECT_EQ(SplitCsvLine("  \"x\"  ,y"), (Fields{"x", "y"}));
  // A quote inside an unquoted field is an ordinary character.
  EXPECT_EQ(SplitCsvLine("5\" disk,b"), (Fields{"5\" disk", "b"}));
}

TEST(CsvFieldsTest, UnterminatedQuoteRunsToTheEndOfTheLine) {
  EXPECT_EQ(SplitCsvLine("a,\"b,c"), (Fields{"a", "b,c"}));
}

TEST(CsvFieldsTest, QuoteOnlyWhatNeedsIt) {
  EXPECT_EQ(QuoteCsvField("plain"), "plain");
  EXPECT_EQ(QuoteCsvField(""), "");
  EXPECT_EQ(QuoteCsvField("a,b"), "\"a,b\"");
  EXPECT_EQ(QuoteCsvField("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(QuoteCsvField(" pad"), "\" pad\"");
  EXPECT_EQ(QuoteCsvField("line\nbreak"), "\"line\nbreak\"");
  EXPECT_EQ(JoinCsvLine({"1", "a,b", ""}), "1,\"a,b\",");
  EXPECT_EQ(JoinCsvLine({}), "");
}

TEST(CsvFieldsTest, JoinThenSplitGivesTheFieldsBack) {
  const Fields fields = {"films/a, the.mp4", "x\"y", " lead", "trail\t", "", "\"", "r\rn"};
  EXPECT_EQ(SplitCsvLine(JoinCsvLine(fields)), fields);
}

}  // namespace
}  // namespace hapcine
