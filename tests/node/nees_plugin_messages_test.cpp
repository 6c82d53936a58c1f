// The plugin protocol's lines against lines written by hand from OpenFresco's ECLabVIEW
// (control(): "propose\t%s", the first control point's name, "\t%s\t%s\t%.10E" per value,
// "\tcontrol-point\t%s" before the next; acquire(): "get-control-point\t%s" and the names,
// answers "OK\t<status>\t<transaction>\t<name>" and triples), never against rpsd's own
// encoder; numbers against printf's %.10E; answers as sites write them.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "rpsd/node/nees_plugin_messages.h"

namespace rpsd::node::nees_plugin {
namespace {

std::string printf_e10(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.10E", value);
  return text;
}

TEST(NeesPluginMessages, ANumberIsWrittenAsPrintfsE10) {
  for (const double v : {0.0, 1.0, -1.0, 0.0123456789012345, -2.5e-3, 156.0e3, 1e-300, -9.99999999999e99, 0.1,
                         12345.678901234567, 5e-324, 1.7976931348623157e308}) {
    LineWriter line;
    line.begin("v");
    line.number(v);
    ASSERT_TRUE(line.end());
    EXPECT_EQ(line.text(), "v\t" + printf_e10(v) + "\n") << v;
  }
}

TEST(NeesPluginMessages, AProposeIsLaidOutAsOpenFrescoWritesIt) {
  const std::vector<std::string> one{"MDL-00-01"};
  const std::vector<ChannelPoint> x{{0, Axis::kX, Motion::kTranslation}};
  LineWriter line;
  const double value[] = {0.0123456789012};
  ASSERT_TRUE(write_propose(line, "OPFTransaction20261126181701n7", one, x, value));
  EXPECT_EQ(line.text(), "propose\tOPFTransaction20261126181701n7\tMDL-00-01\tx\tdisplacement\t1.2345678901E-02\n");

  // Two channels on the first control point, a rotation on the second: "control-point"
  // before every name but the first, a control point's values together whatever the
  // channels' order.
  const std::vector<std::string> two{"LBCB1", "LBCB2"};
  const std::vector<ChannelPoint> three{
      {0, Axis::kX, Motion::kTranslation}, {1, Axis::kZ, Motion::kRotation}, {0, Axis::kY, Motion::kTranslation}};
  const double values[] = {1.5, -0.002, -25.4};
  ASSERT_TRUE(write_propose(line, "T1", two, three, values));
  EXPECT_EQ(line.text(),
            "propose\tT1\tLBCB1\tx\tdisplacement\t1.5000000000E+00\ty\tdisplacement\t-2.5400000000E+01"
            "\tcontrol-point\tLBCB2\tz\trotation\t-2.0000000000E-03\n");
}

TEST(NeesPluginMessages, AGetControlPointIsLaidOutAsOpenFrescoWritesIt) {
  LineWriter line;
  const std::vector<std::string> two{"LBCB1", "LBCB2"};
  ASSERT_TRUE(write_get_control_point(line, "T9", two));
  EXPECT_EQ(line.text(), "get-control-point\tT9\tLBCB1\tLBCB2\n");
}

TEST(NeesPluginMessages, ALineThatDoesNotFitOrANumberThatIsNotFiniteIsNotWritten) {
  LineWriter line;
  line.begin("propose");
  for (int i = 0; i < 100; ++i) line.field("a-long-control-point-name");
  EXPECT_FALSE(line.end());
  line.begin("propose");
  line.number(std::numeric_limits<double>::quiet_NaN());
  EXPECT_FALSE(line.end());
  line.begin("propose");
  line.number(1.0);
  EXPECT_TRUE(line.end());  // begin() starts afresh
}

TEST(NeesPluginMessages, AnAnswerIsReadAsSitesWriteIt) {
  ControlPointAnswer a;
  ASSERT_EQ(parse_control_point_answer("OK\t0\tOPFTransaction20261126181701n7\tMDL-00-01\tx\tdisplacement\t"
                                       "1.2345678901E-02\tx\tforce\t-3.2000000000E+03\n",
                                       a),
            AnswerError::kNone);
  EXPECT_EQ(a.status, "0");
  EXPECT_EQ(a.transaction, "OPFTransaction20261126181701n7");
  EXPECT_EQ(a.control_point, "MDL-00-01");
  ASSERT_EQ(a.count, 2u);
  EXPECT_EQ(a.values[0].axis, Axis::kX);
  EXPECT_EQ(a.values[0].parameter, Parameter::kDisplacement);
  EXPECT_DOUBLE_EQ(a.values[0].value, 0.012345678901);
  EXPECT_EQ(a.values[1].parameter, Parameter::kForce);
  EXPECT_DOUBLE_EQ(a.values[1].value, -3200.0);
  // CR LF, %g and a leading '+' (LabVIEW's own number formats), a rotation and a moment.
  ASSERT_EQ(parse_control_point_answer("OK\t1\tT\tCP\tz\trotation\t+1.5e-3\tz\tmoment\t42\r\n", a), AnswerError::kNone);
  EXPECT_EQ(a.status, "1");
  EXPECT_EQ(a.values[0].parameter, Parameter::kRotation);
  EXPECT_DOUBLE_EQ(a.values[0].value, 1.5e-3);
  EXPECT_EQ(a.values[1].parameter, Parameter::kMoment);
  EXPECT_DOUBLE_EQ(a.values[1].value, 42.0);
  // A control point with no values is an answer too (the caller finds its channels missing).
  ASSERT_EQ(parse_control_point_answer("OK\t0\tT\tCP\n", a), AnswerError::kNone);
  EXPECT_EQ(a.count, 0u);
}

TEST(NeesPluginMessages, AMalformedAnswerIsNamed) {
  ControlPointAnswer a;
  EXPECT_EQ(parse_control_point_answer("ERROR\tT\tproposal refused\n", a), AnswerError::kRefused);
  EXPECT_EQ(parse_control_point_answer("ok\t0\tT\tCP\n", a), AnswerError::kRefused);  // OK in capitals only
  EXPECT_EQ(parse_control_point_answer("\n", a), AnswerError::kRefused);
  EXPECT_EQ(parse_control_point_answer("OK\t0\tT\n", a), AnswerError::kTooFewFields);
  EXPECT_EQ(parse_control_point_answer("OK\t0\tT\tCP\tx\tdisplacement\n", a), AnswerError::kBadTriple);
  EXPECT_EQ(parse_control_point_answer("OK\t0\tT\tCP\tw\tdisplacement\t1\n", a), AnswerError::kBadTriple);
  EXPECT_EQ(parse_control_point_answer("OK\t0\tT\tCP\tx\tvelocity\t1\n", a), AnswerError::kBadTriple);
  for (const char* number : {"nan", "inf", "-inf", "1e999", "1.0abc", "", " 1", "0x10", "++1", "#garbage#"}) {
    EXPECT_EQ(parse_control_point_answer(std::string("OK\t0\tT\tCP\tx\tforce\t") + number + "\n", a),
              AnswerError::kBadNumber)
        << number;
  }
  std::string many = "OK\t0\tT\tCP";
  for (int i = 0; i < 21; ++i) many += "\tx\tforce\t1";
  EXPECT_EQ(parse_control_point_answer(many + "\n", a), AnswerError::kTooManyFields);
}

TEST(NeesPluginMessages, ARefusalIsAnyFirstFieldButOk) {
  Fields f;
  ASSERT_TRUE(split_fields("OK\t0\tT\n", f));
  EXPECT_TRUE(accepted(f));
  for (const char* line : {"ERROR\tlimit\n", "OKAY\n", " OK\t0\n", "NOK\n", "Ok\n"}) {
    ASSERT_TRUE(split_fields(line, f));
    EXPECT_FALSE(accepted(f)) << line;
  }
}

TEST(NeesPluginMessages, TransactionIdsNeverRepeatWithinASecondOrAcrossSessions) {
  TransactionIds ids;
  const std::time_t now = 1795000000;
  ids.begin(now);
  const std::string first(ids.next());
  const std::string second(ids.next());
  ids.begin(now);  // a new session in the same second
  const std::string third(ids.next());
  EXPECT_NE(first, second);
  EXPECT_NE(second, third);
  EXPECT_NE(first, third);
  ASSERT_EQ(first.rfind("OPFTransaction", 0), 0u) << first;
  EXPECT_EQ(first.size(), std::string("OPFTransaction").size() + 14 + 2) << first;  // YYYYmmddHHMMSS n 1
  EXPECT_EQ(first.substr(first.size() - 2), "n1");
  EXPECT_EQ(third.substr(third.size() - 2), "n3");
  EXPECT_TRUE(valid_name(third));
}

}  // namespace
}  // namespace rpsd::node::nees_plugin
